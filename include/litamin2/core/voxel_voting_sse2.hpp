#pragma once
/// The SSE2 kernel of vote_points (x86-64 baseline, no -march needed).
///
/// Same result as the scalar loop up to float rounding, about twice as fast. Blocks of points
/// are first moved and keyed in float, four at a time or, on CPUs with AVX2 (chosen at run
/// time), eight (phase A, branch-free, voxel_keying.hpp), then summed in runs of same-voxel
/// points (phase B). Two choices keep float exact enough:
/// - points are moved into a local frame whose origin is the voxel corner next to the pose's
///   translation, so coordinates stay within the scan's range (float error ~1e-5 m at 100 m)
///   and the voxel indices of a scan fit in 10 bits per axis;
/// - a run's second moments are summed about the run's first point, not the voxel centre, so
///   a flat run's variance along its normal (~4e-4 m^2 for 2 cm noise) is not the small
///   difference of two large float sums. Each run is shifted to the voxel centre and merged
///   into the voxel's double moments.

#include "litamin2/core/voxel_key.hpp"
#include "litamin2/core/voxel_keying.hpp"
#include "litamin2/core/voxel_moments.hpp"
#include "litamin2/core/voxelizer.hpp"

#include <Eigen/Geometry>

#include <cmath>
#include <cstdint>

#if defined(__SSE2__)
#include <emmintrin.h>
#define LITAMIN2_HAVE_SSE2_VOTING 1
#endif

namespace litamin2 {
namespace sse2_voting {

/// Points moved and keyed per phase-A block.
constexpr int kBlockPoints = 256;

/// True when every voxel a point within max_range can fall in has a local key: |index| of the
/// local frame below the bias, with a margin for the origin's offset and float rounding.
inline bool fits(const VoxelizerConfig& config) {
  const double reach = config.max_range / config.voxel_size + 3.0;
  return std::isfinite(reach) && reach < static_cast<double>(kLocalBias);
}

}  // namespace sse2_voting

#if defined(LITAMIN2_HAVE_SSE2_VOTING)

namespace sse2_voting {

/// A run of same-voxel points: sums of (point - origin) as (xx, xy, xz, x), (yx, yy, yz, y),
/// (zx, zy, zz, z), where the origin is the run's first point (as an offset from the voxel
/// centre, w lane 0).
struct Run {
  /// Before the first point: neither a voxel's key (below 2^30) nor kInvalidKey.
  static constexpr std::uint32_t kNoRun = kInvalidKey - 1;
  static_assert(3 * kLocalBits < 32 && (1u << (3 * kLocalBits)) <= kNoRun);
  std::uint32_t key = kNoRun;
  int count = 0;
  __m128 origin = _mm_setzero_ps();
  __m128 sum_x = _mm_setzero_ps(), sum_y = _mm_setzero_ps(), sum_z = _mm_setzero_ps();

  /// Starts a run at a point given as (offset from the voxel centre, 1).
  void start(std::uint32_t run_key, __m128 offset) {
    key = run_key;
    count = 0;
    origin = _mm_and_ps(offset, _mm_castsi128_ps(_mm_set_epi32(0, -1, -1, -1)));
    sum_x = sum_y = sum_z = _mm_setzero_ps();
  }

  /// Adds a point given as (offset from the voxel centre, 1).
  void add(__m128 offset) {
    const __m128 v = _mm_sub_ps(offset, origin);  // (dx, dy, dz, 1)
    sum_x = _mm_add_ps(sum_x, _mm_mul_ps(v, _mm_shuffle_ps(v, v, _MM_SHUFFLE(0, 0, 0, 0))));
    sum_y = _mm_add_ps(sum_y, _mm_mul_ps(v, _mm_shuffle_ps(v, v, _MM_SHUFFLE(1, 1, 1, 1))));
    sum_z = _mm_add_ps(sum_z, _mm_mul_ps(v, _mm_shuffle_ps(v, v, _MM_SHUFFLE(2, 2, 2, 2))));
    ++count;
  }

  /// The run's moments about the voxel centre, in double: with delta = origin - centre,
  /// sum' = sum + n delta, S' = S + sum delta^T + delta sum^T + n delta delta^T.
  VoxelMoments about_voxel_centre() const {
    alignas(16) float sx[4], sy[4], sz[4], o[4];
    _mm_store_ps(sx, sum_x);
    _mm_store_ps(sy, sum_y);
    _mm_store_ps(sz, sum_z);
    _mm_store_ps(o, origin);
    const double n = count;
    const double dx = o[0], dy = o[1], dz = o[2];
    const double x = sx[3], y = sy[3], z = sz[3];
    VoxelMoments out;
    out.count = count;
    out.sum << x + n * dx, y + n * dy, z + n * dz;
    out.sum_sq << sx[0] + 2.0 * x * dx + n * dx * dx, sx[1] + x * dy + dx * y + n * dx * dy,
        sx[2] + x * dz + dx * z + n * dx * dz, sy[1] + 2.0 * y * dy + n * dy * dy,
        sy[2] + y * dz + dy * z + n * dy * dz, sz[2] + 2.0 * z * dz + n * dz * dz;
    return out;
  }
};

}  // namespace sse2_voting

/// vote_points for configs where sse2_voting::fits(config).
template <class MomentsOf>
void vote_points_sse2(const Eigen::Vector3f* begin, const Eigen::Vector3f* end,
                      const Eigen::Isometry3d& pose, const VoxelizerConfig& config,
                      MomentsOf&& moments_of) {
  using namespace sse2_voting;
  const double size = config.voxel_size;
  // Local frame: origin at the voxel corner below the pose's translation (exact in double).
  const Eigen::Vector3d translation = pose.translation();
  const Eigen::Vector3i corner_index((translation / size).array().floor().cast<int>());
  const Eigen::Vector3d corner = corner_index.cast<double>() * size;
  const Eigen::Vector3f local_t = (translation - corner).cast<float>();  // in [0, size)^3
  const Eigen::Matrix3f r = pose.linear().cast<float>();
  KeyingFrame frame;
  for (int row = 0; row < 3; ++row) {
    for (int col = 0; col < 3; ++col) frame.rotation[3 * row + col] = r(row, col);
    frame.translation[row] = local_t(row);
  }
  frame.voxel_size = static_cast<float>(size);
  frame.inv_voxel_size = static_cast<float>(1.0 / size);
  frame.min_range_sq = static_cast<float>(config.min_range * config.min_range);
  frame.max_range_sq = static_cast<float>(config.max_range * config.max_range);
  const bool avx2 = use_avx2_keying();

  alignas(32) std::uint32_t keys[kBlockPoints];
  alignas(32) float offsets[kBlockPoints][4];  // point - voxel centre (local frame), then 1

  Run run;
  auto flush = [&](const Run& finished) {
    if (finished.count == 0) return;
    const std::uint32_t key = finished.key;
    const VoxelIndex index(
        corner_index.x() + static_cast<int>(key & kLocalMask) - kLocalBias,
        corner_index.y() + static_cast<int>((key >> kLocalBits) & kLocalMask) - kLocalBias,
        corner_index.z() + static_cast<int>((key >> (2 * kLocalBits)) & kLocalMask) - kLocalBias);
    moments_of(index).merge(finished.about_voxel_centre());
  };

  for (const Eigen::Vector3f* block = begin; block < end; block += kBlockPoints) {
    const int count = static_cast<int>(std::min<std::ptrdiff_t>(kBlockPoints, end - block));
    // Phase A: move, range-check and key the block (voxel_keying.hpp).
    if (avx2) {
      key_block_avx2(block, count, frame, keys, offsets);
    } else {
      key_block_sse2(block, count, frame, keys, offsets);
    }
    // Phase B: sum runs of same-voxel points. A point of the run's voxel takes one test; a
    // point outside the range limits has kInvalidKey, which no run has.
    for (int i = 0; i < count; ++i) {
      const std::uint32_t key = keys[i];
      if (key != run.key) {
        if (key == kInvalidKey) continue;
        flush(run);
        run.start(key, _mm_load_ps(offsets[i]));
      }
      run.add(_mm_load_ps(offsets[i]));
    }
  }
  flush(run);
}

#endif  // LITAMIN2_HAVE_SSE2_VOTING

}  // namespace litamin2
