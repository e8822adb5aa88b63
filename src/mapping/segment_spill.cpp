#include "litamin2/mapping/segment_spill.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <stdexcept>
#include <type_traits>

namespace litamin2::mapping {

namespace {

static_assert(std::is_trivially_copyable_v<SegmentVoxels::Voxel>,
              "segment voxels are written to the spill file as they are in memory");
constexpr std::uint64_t kVoxelBytes = sizeof(SegmentVoxels::Voxel);

std::string error_text(const std::string& what, const std::string& path) {
  return "segment spill " + path + ": " + what + ": " + std::strerror(errno);
}

}  // namespace

SegmentSpill::SegmentSpill(const std::string& path) : path_(path) {
  fd_ = ::open(path.c_str(), O_RDWR | O_CREAT | O_TRUNC | O_CLOEXEC, 0600);
  if (fd_ < 0) throw std::runtime_error(error_text("cannot create", path));
  // Nothing else opens it: gone when the process ends, however it ends.
  if (::unlink(path.c_str()) != 0) {
    const std::string message = error_text("cannot unlink", path);
    ::close(fd_);
    throw std::runtime_error(message);
  }
}

SegmentSpill::~SegmentSpill() {
  if (fd_ >= 0) ::close(fd_);
}

void SegmentSpill::release(const Slot& slot) {
  if (slot.capacity == 0) return;
  free_.emplace(slot.capacity, slot.offset);
  live_bytes_ -= slot.voxels * kVoxelBytes;
}

SegmentSpill::Slot SegmentSpill::write(const SegmentVoxels& segment, Slot previous) {
  const auto& voxels = segment.voxels();
  const auto count = static_cast<std::uint32_t>(voxels.size());
  Slot slot;
  if (previous.capacity > 0 && previous.capacity >= count) {
    slot = previous;
    live_bytes_ -= previous.voxels * kVoxelBytes;
  } else {
    release(previous);
    const auto fit = free_.lower_bound(count);
    if (count > 0 && fit != free_.end()) {
      slot.offset = fit->second;
      slot.capacity = fit->first;
      free_.erase(fit);
    } else {
      slot.offset = end_;
      slot.capacity = count + count / 4 + 1;
      end_ += slot.capacity * kVoxelBytes;
    }
  }
  slot.voxels = count;
  const auto* data = reinterpret_cast<const char*>(voxels.data());
  std::uint64_t done = 0;
  const std::uint64_t total = count * kVoxelBytes;
  while (done < total) {
    const ssize_t n =
        ::pwrite(fd_, data + done, total - done, static_cast<off_t>(slot.offset + done));
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) throw std::runtime_error(error_text("cannot write", path_));
    done += static_cast<std::uint64_t>(n);
  }
  live_bytes_ += total;
  return slot;
}

SegmentVoxels SegmentSpill::read(const Slot& slot) const {
  std::vector<SegmentVoxels::Voxel> voxels(slot.voxels);
  auto* data = reinterpret_cast<char*>(voxels.data());
  std::uint64_t done = 0;
  const std::uint64_t total = slot.voxels * kVoxelBytes;
  while (done < total) {
    const ssize_t n =
        ::pread(fd_, data + done, total - done, static_cast<off_t>(slot.offset + done));
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) throw std::runtime_error(error_text("cannot read", path_));
    done += static_cast<std::uint64_t>(n);
  }
  return SegmentVoxels::of(std::move(voxels));
}

}  // namespace litamin2::mapping
