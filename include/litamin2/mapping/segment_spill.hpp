#pragma once
/// Where the tile map puts the moments of rigid segments (segment_voxels.hpp) that its segment
/// cache evicts, so that a segment moved again later is read back (one read of its voxels)
/// instead of recomputed from its keyframes' distributions (each read from the store, decoded,
/// checked, regularised and fused again: about ten times the CPU at a fleet's scale).
///
/// A scratch file private to the process, not state: created empty (truncated) at `path` and
/// unlinked at once, so it is gone when the process ends, killed or not, and never read by a
/// restart (which recomputes what it needs from the store, as before). The voxels are written
/// as they are in memory (no format to validate: nothing but this object writes the file).
/// Space is reused: a segment written again takes its old slot when it fits, else the smallest
/// free slot that fits, else the end of the file; a slot holds a quarter more voxels than
/// written, for a segment that grows by a few keyframes.
///
/// Not thread-safe (the mapping thread's).

#include "litamin2/mapping/segment_voxels.hpp"

#include <cstddef>
#include <cstdint>
#include <map>
#include <string>

namespace litamin2::mapping {

class SegmentSpill {
 public:
  /// A segment's place in the file (capacity 0: none).
  struct Slot {
    std::uint64_t offset = 0;
    std::uint32_t capacity = 0;
    std::uint32_t voxels = 0;
  };

  /// Creates the file (std::runtime_error if it cannot).
  explicit SegmentSpill(const std::string& path);
  ~SegmentSpill();
  SegmentSpill(const SegmentSpill&) = delete;
  SegmentSpill& operator=(const SegmentSpill&) = delete;

  /// Writes the segment's voxels, in `previous` when they fit (else `previous` is freed).
  /// Returns where they are. Throws std::runtime_error on a write error.
  Slot write(const SegmentVoxels& segment, Slot previous);
  /// The segment as written at `slot`. Throws std::runtime_error on a read error.
  SegmentVoxels read(const Slot& slot) const;
  /// Frees a slot (capacity 0: nothing).
  void release(const Slot& slot);

  /// Bytes of the file, and of the voxels written in it now.
  std::uint64_t file_bytes() const { return end_; }
  std::uint64_t live_bytes() const { return live_bytes_; }

 private:
  int fd_ = -1;
  std::string path_;
  std::uint64_t end_ = 0;
  std::uint64_t live_bytes_ = 0;
  /// Free slots by capacity (voxels), with their offsets.
  std::multimap<std::uint32_t, std::uint64_t> free_;
};

}  // namespace litamin2::mapping
