#pragma once
/// Integer voxel coordinates and their packing into one 64-bit hash key.

#include <Eigen/Core>
#include <cmath>
#include <cstdint>

namespace litamin2 {

using VoxelIndex = Eigen::Vector3i;

/// floor(x) as an int for |x| < 2^31; inline (std::floor is a library call without SSE4.1, and
/// this runs three times per point).
inline int fast_floor(double x) {
  const int truncated = static_cast<int>(x);
  return truncated - (x < static_cast<double>(truncated) ? 1 : 0);
}

/// Voxel holding point p for voxels of edge `inv_size`^-1 aligned at the origin.
inline VoxelIndex voxel_index(const Eigen::Vector3d& p, double inv_size) {
  return VoxelIndex(fast_floor(p.x() * inv_size), fast_floor(p.y() * inv_size),
                    fast_floor(p.z() * inv_size));
}

/// Bits per axis of a packed voxel key.
constexpr int kVoxelKeyBits = 21;
constexpr std::uint64_t kVoxelKeyMask = (1ull << kVoxelKeyBits) - 1;
/// Offset added to each axis index before packing: indices in [-2^20, 2^20) are representable.
constexpr std::int64_t kVoxelKeyOffset = 1ll << (kVoxelKeyBits - 1);

/// Packs a voxel index into 64 bits: 21 bits per axis, i.e. +-1M voxels (3000 km at 3 m).
inline std::uint64_t pack_voxel(const VoxelIndex& v) {
  return (static_cast<std::uint64_t>(v.x() + kVoxelKeyOffset) & kVoxelKeyMask) |
         ((static_cast<std::uint64_t>(v.y() + kVoxelKeyOffset) & kVoxelKeyMask) << kVoxelKeyBits) |
         ((static_cast<std::uint64_t>(v.z() + kVoxelKeyOffset) & kVoxelKeyMask)
          << (2 * kVoxelKeyBits));
}

/// Inverse of pack_voxel.
inline VoxelIndex unpack_voxel(std::uint64_t key) {
  constexpr int kOffset = static_cast<int>(kVoxelKeyOffset);
  return VoxelIndex(static_cast<int>(key & kVoxelKeyMask) - kOffset,
                    static_cast<int>((key >> kVoxelKeyBits) & kVoxelKeyMask) - kOffset,
                    static_cast<int>((key >> (2 * kVoxelKeyBits)) & kVoxelKeyMask) - kOffset);
}

/// Hash for packed keys: a multiplicative mix, since the packed key's low bits are one axis.
struct VoxelKeyHash {
  std::size_t operator()(std::uint64_t key) const {
    key ^= key >> 31;
    key *= 0x9E3779B97F4A7C15ull;
    return static_cast<std::size_t>(key ^ (key >> 29));
  }
};

}  // namespace litamin2
