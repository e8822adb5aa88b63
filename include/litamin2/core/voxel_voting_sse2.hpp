#pragma once
/// The SSE2 kernel of vote_points (x86-64 baseline, no -march needed).
///
/// Same result as the scalar loop up to float rounding, about twice as fast. Blocks of points
/// are first moved and keyed four at a time in float (phase A, branch-free), then summed in
/// runs of same-voxel points (phase B). Two choices keep float exact enough:
/// - points are moved into a local frame whose origin is the voxel corner next to the pose's
///   translation, so coordinates stay within the scan's range (float error ~1e-5 m at 100 m)
///   and the voxel indices of a scan fit in 10 bits per axis;
/// - a run's second moments are summed about the run's first point, not the voxel centre, so
///   a flat run's variance along its normal (~4e-4 m^2 for 2 cm noise) is not the small
///   difference of two large float sums. Each run is shifted to the voxel centre and merged
///   into the voxel's double moments.

#include "litamin2/core/voxel_key.hpp"
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

/// Bits per axis of the local (per-call) voxel key.
constexpr int kLocalBits = 10;
constexpr std::int32_t kLocalBias = 1 << (kLocalBits - 1);
constexpr std::uint32_t kLocalMask = (1u << kLocalBits) - 1;
constexpr std::uint32_t kInvalidKey = 0xFFFFFFFFu;
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
  std::uint32_t key = kInvalidKey;
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

  const __m128 r00 = _mm_set1_ps(r(0, 0)), r01 = _mm_set1_ps(r(0, 1)), r02 = _mm_set1_ps(r(0, 2));
  const __m128 r10 = _mm_set1_ps(r(1, 0)), r11 = _mm_set1_ps(r(1, 1)), r12 = _mm_set1_ps(r(1, 2));
  const __m128 r20 = _mm_set1_ps(r(2, 0)), r21 = _mm_set1_ps(r(2, 1)), r22 = _mm_set1_ps(r(2, 2));
  const __m128 tx = _mm_set1_ps(local_t.x()), ty = _mm_set1_ps(local_t.y()),
               tz = _mm_set1_ps(local_t.z());
  const __m128 inv_size = _mm_set1_ps(static_cast<float>(1.0 / size));
  const __m128 size_f = _mm_set1_ps(static_cast<float>(size));
  const __m128 half = _mm_set1_ps(0.5f);
  const __m128 one = _mm_set1_ps(1.0f);
  const __m128 min_range_sq = _mm_set1_ps(static_cast<float>(config.min_range * config.min_range));
  const __m128 max_range_sq = _mm_set1_ps(static_cast<float>(config.max_range * config.max_range));
  const __m128i bias = _mm_set1_epi32(kLocalBias);
  const __m128i invalid = _mm_set1_epi32(static_cast<int>(kInvalidKey));

  alignas(16) std::uint32_t keys[kBlockPoints];
  alignas(16) float offsets[kBlockPoints][4];  // point - voxel centre (local frame), then 1

  // floor of four floats: truncate, then subtract 1 where truncation rounded up (negatives).
  auto floor_epi32 = [](__m128 v) {
    const __m128i truncated = _mm_cvttps_epi32(v);
    const __m128 rounded_up = _mm_cmplt_ps(v, _mm_cvtepi32_ps(truncated));
    return _mm_add_epi32(truncated, _mm_castps_si128(rounded_up));  // mask is -1 where set
  };

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
    // Phase A: move, range-check and key four points at a time.
    for (int i = 0; i < count; i += 4) {
      __m128 x, y, z;
      if (i + 4 <= count) {
        const Eigen::Vector3f* p = block + i;
        x = _mm_set_ps(p[3].x(), p[2].x(), p[1].x(), p[0].x());
        y = _mm_set_ps(p[3].y(), p[2].y(), p[1].y(), p[0].y());
        z = _mm_set_ps(p[3].z(), p[2].z(), p[1].z(), p[0].z());
      } else {
        // The last group of a short block: lanes past the end are NaN and fail the range test.
        alignas(16) float px[4], py[4], pz[4];
        for (int lane = 0; lane < 4; ++lane) {
          const bool inside = i + lane < count;
          px[lane] = inside ? block[i + lane].x() : NAN;
          py[lane] = inside ? block[i + lane].y() : NAN;
          pz[lane] = inside ? block[i + lane].z() : NAN;
        }
        x = _mm_load_ps(px);
        y = _mm_load_ps(py);
        z = _mm_load_ps(pz);
      }
      const __m128 range_sq =
          _mm_add_ps(_mm_add_ps(_mm_mul_ps(x, x), _mm_mul_ps(y, y)), _mm_mul_ps(z, z));
      // Ordered compares: false for NaN, so non-finite points are dropped too.
      const __m128 in_range =
          _mm_and_ps(_mm_cmpge_ps(range_sq, min_range_sq), _mm_cmple_ps(range_sq, max_range_sq));
      const __m128 wx = _mm_add_ps(
          _mm_add_ps(_mm_add_ps(_mm_mul_ps(r00, x), _mm_mul_ps(r01, y)), _mm_mul_ps(r02, z)), tx);
      const __m128 wy = _mm_add_ps(
          _mm_add_ps(_mm_add_ps(_mm_mul_ps(r10, x), _mm_mul_ps(r11, y)), _mm_mul_ps(r12, z)), ty);
      const __m128 wz = _mm_add_ps(
          _mm_add_ps(_mm_add_ps(_mm_mul_ps(r20, x), _mm_mul_ps(r21, y)), _mm_mul_ps(r22, z)), tz);
      const __m128i ix = floor_epi32(_mm_mul_ps(wx, inv_size));
      const __m128i iy = floor_epi32(_mm_mul_ps(wy, inv_size));
      const __m128i iz = floor_epi32(_mm_mul_ps(wz, inv_size));
      // Offsets from the voxel centres.
      __m128 dx = _mm_sub_ps(wx, _mm_mul_ps(_mm_add_ps(_mm_cvtepi32_ps(ix), half), size_f));
      __m128 dy = _mm_sub_ps(wy, _mm_mul_ps(_mm_add_ps(_mm_cvtepi32_ps(iy), half), size_f));
      __m128 dz = _mm_sub_ps(wz, _mm_mul_ps(_mm_add_ps(_mm_cvtepi32_ps(iz), half), size_f));
      __m128 w = one;
      _MM_TRANSPOSE4_PS(dx, dy, dz, w);
      _mm_store_ps(offsets[i], dx);
      _mm_store_ps(offsets[i + 1], dy);
      _mm_store_ps(offsets[i + 2], dz);
      _mm_store_ps(offsets[i + 3], w);
      const __m128i key =
          _mm_or_si128(_mm_or_si128(_mm_add_epi32(ix, bias),
                                    _mm_slli_epi32(_mm_add_epi32(iy, bias), kLocalBits)),
                       _mm_slli_epi32(_mm_add_epi32(iz, bias), 2 * kLocalBits));
      const __m128i valid = _mm_castps_si128(in_range);
      _mm_store_si128(reinterpret_cast<__m128i*>(keys + i),
                      _mm_or_si128(_mm_and_si128(valid, key), _mm_andnot_si128(valid, invalid)));
    }
    // Phase B: sum runs of same-voxel points.
    for (int i = 0; i < count; ++i) {
      const std::uint32_t key = keys[i];
      if (key == kInvalidKey) continue;
      const __m128 offset = _mm_load_ps(offsets[i]);
      if (key != run.key || run.count == 0) {
        flush(run);
        run.start(key, offset);
      }
      run.add(offset);
    }
  }
  flush(run);
}

#endif  // LITAMIN2_HAVE_SSE2_VOTING

}  // namespace litamin2
