#pragma once
/// Phase A of the SIMD voting kernel (voxel_voting_sse2.hpp): a block of points moved into the
/// kernel's local frame, range-checked and given their voxel's local key and their offset from
/// the voxel's centre. Pure arithmetic on arrays, so it can be compiled for more than one
/// instruction set and chosen at run time: the AVX2 version does eight points per step where
/// the SSE2 baseline does four, with the same operations in the same order (no FMA), so both
/// give bit-identical keys and offsets (tests/unit/core_voxel_voting_test.cpp).

#include <Eigen/Core>

#include <cmath>
#include <cstdint>
#include <cstring>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

namespace litamin2::sse2_voting {

/// Bits per axis of the local (per-call) voxel key.
constexpr int kLocalBits = 10;
constexpr std::int32_t kLocalBias = 1 << (kLocalBits - 1);
constexpr std::uint32_t kLocalMask = (1u << kLocalBits) - 1;
constexpr std::uint32_t kInvalidKey = 0xFFFFFFFFu;

/// The pose in the local frame and the grid, in float.
struct KeyingFrame {
  /// Rotation, row-major.
  float rotation[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1};
  /// Translation of the local frame (the pose's translation minus the local origin).
  float translation[3] = {0, 0, 0};
  float voxel_size = 1.0f;
  float inv_voxel_size = 1.0f;
  float min_range_sq = 0.0f;
  float max_range_sq = 0.0f;
};

/// key_block_avx2 and key_block_sse2 key `count` points: keys[i] is the local key of point
/// i's voxel (10 bits per axis, biased by kLocalBias) or kInvalidKey when its range is outside
/// [min, max] or not finite; offsets[i] is (point in the local frame - voxel centre, 1). keys
/// and offsets hold `count` entries and are 16-byte aligned.
///
/// Eight points per step; only for CPUs with AVX2 (voxel_keying_avx2.cpp).
void key_block_avx2(const Eigen::Vector3f* points, int count, const KeyingFrame& frame,
                    std::uint32_t* keys, float (*offsets)[4]);

/// True when this CPU runs key_block_avx2.
bool cpu_has_avx2();

/// Whether vote_points_sse2 uses key_block_avx2, decided once: where the CPU has AVX2, unless
/// the environment variable LITAMIN2_KEYING=sse2 asks for the baseline (to compare the two).
bool use_avx2_keying();

#if defined(__SSE2__)
namespace detail {

/// floor of four floats: truncate, then subtract 1 where truncation rounded up (negatives).
inline __m128i floor_epi32(__m128 v) {
  const __m128i truncated = _mm_cvttps_epi32(v);
  const __m128 rounded_up = _mm_cmplt_ps(v, _mm_cvtepi32_ps(truncated));
  return _mm_add_epi32(truncated, _mm_castps_si128(rounded_up));  // mask is -1 where set
}

/// The per-call constants of key_block_sse2, broadcast.
struct Constants {
  explicit Constants(const KeyingFrame& f)
      : r00(_mm_set1_ps(f.rotation[0])),
        r01(_mm_set1_ps(f.rotation[1])),
        r02(_mm_set1_ps(f.rotation[2])),
        r10(_mm_set1_ps(f.rotation[3])),
        r11(_mm_set1_ps(f.rotation[4])),
        r12(_mm_set1_ps(f.rotation[5])),
        r20(_mm_set1_ps(f.rotation[6])),
        r21(_mm_set1_ps(f.rotation[7])),
        r22(_mm_set1_ps(f.rotation[8])),
        tx(_mm_set1_ps(f.translation[0])),
        ty(_mm_set1_ps(f.translation[1])),
        tz(_mm_set1_ps(f.translation[2])),
        inv_size(_mm_set1_ps(f.inv_voxel_size)),
        size(_mm_set1_ps(f.voxel_size)),
        min_range_sq(_mm_set1_ps(f.min_range_sq)),
        max_range_sq(_mm_set1_ps(f.max_range_sq)) {}
  __m128 r00, r01, r02, r10, r11, r12, r20, r21, r22, tx, ty, tz;
  __m128 inv_size, size, min_range_sq, max_range_sq;
};

/// Keys four points given as x, y, z vectors: returns the masked keys and leaves the four
/// (offset, 1) rows in row0..row3.
__attribute__((always_inline)) inline __m128i key_group(const Constants& c, __m128 x, __m128 y,
                                                        __m128 z, __m128& row0, __m128& row1,
                                                        __m128& row2, __m128& row3) {
  const __m128 half = _mm_set1_ps(0.5f);
  const __m128i bias = _mm_set1_epi32(kLocalBias);
  const __m128i invalid = _mm_set1_epi32(static_cast<int>(kInvalidKey));
  const __m128 range_sq =
      _mm_add_ps(_mm_add_ps(_mm_mul_ps(x, x), _mm_mul_ps(y, y)), _mm_mul_ps(z, z));
  // Ordered compares: false for NaN, so non-finite points are dropped too.
  const __m128 in_range =
      _mm_and_ps(_mm_cmpge_ps(range_sq, c.min_range_sq), _mm_cmple_ps(range_sq, c.max_range_sq));
  const __m128 wx = _mm_add_ps(
      _mm_add_ps(_mm_add_ps(_mm_mul_ps(c.r00, x), _mm_mul_ps(c.r01, y)), _mm_mul_ps(c.r02, z)),
      c.tx);
  const __m128 wy = _mm_add_ps(
      _mm_add_ps(_mm_add_ps(_mm_mul_ps(c.r10, x), _mm_mul_ps(c.r11, y)), _mm_mul_ps(c.r12, z)),
      c.ty);
  const __m128 wz = _mm_add_ps(
      _mm_add_ps(_mm_add_ps(_mm_mul_ps(c.r20, x), _mm_mul_ps(c.r21, y)), _mm_mul_ps(c.r22, z)),
      c.tz);
  const __m128i ix = floor_epi32(_mm_mul_ps(wx, c.inv_size));
  const __m128i iy = floor_epi32(_mm_mul_ps(wy, c.inv_size));
  const __m128i iz = floor_epi32(_mm_mul_ps(wz, c.inv_size));
  // Offsets from the voxel centres.
  row0 = _mm_sub_ps(wx, _mm_mul_ps(_mm_add_ps(_mm_cvtepi32_ps(ix), half), c.size));
  row1 = _mm_sub_ps(wy, _mm_mul_ps(_mm_add_ps(_mm_cvtepi32_ps(iy), half), c.size));
  row2 = _mm_sub_ps(wz, _mm_mul_ps(_mm_add_ps(_mm_cvtepi32_ps(iz), half), c.size));
  row3 = _mm_set1_ps(1.0f);
  _MM_TRANSPOSE4_PS(row0, row1, row2, row3);
  const __m128i key = _mm_or_si128(
      _mm_or_si128(_mm_add_epi32(ix, bias), _mm_slli_epi32(_mm_add_epi32(iy, bias), kLocalBits)),
      _mm_slli_epi32(_mm_add_epi32(iz, bias), 2 * kLocalBits));
  const __m128i valid = _mm_castps_si128(in_range);
  return _mm_or_si128(_mm_and_si128(valid, key), _mm_andnot_si128(valid, invalid));
}

}  // namespace detail

/// Four points per step (x86-64 baseline); inline, so that the kernel keeps it in its loop.
inline void key_block_sse2(const Eigen::Vector3f* points, int count, const KeyingFrame& frame,
                           std::uint32_t* keys, float (*offsets)[4]) {
  using namespace detail;
  const Constants c(frame);
  __m128 row0, row1, row2, row3;
  int i = 0;
  for (; i + 4 <= count; i += 4) {
    const Eigen::Vector3f* p = points + i;
    const __m128 x = _mm_set_ps(p[3].x(), p[2].x(), p[1].x(), p[0].x());
    const __m128 y = _mm_set_ps(p[3].y(), p[2].y(), p[1].y(), p[0].y());
    const __m128 z = _mm_set_ps(p[3].z(), p[2].z(), p[1].z(), p[0].z());
    const __m128i key = key_group(c, x, y, z, row0, row1, row2, row3);
    _mm_store_ps(offsets[i], row0);
    _mm_store_ps(offsets[i + 1], row1);
    _mm_store_ps(offsets[i + 2], row2);
    _mm_store_ps(offsets[i + 3], row3);
    _mm_store_si128(reinterpret_cast<__m128i*>(keys + i), key);
  }
  if (i == count) return;
  // The last one to three points: lanes past the end are NaN (they fail the range test) and
  // are not stored.
  alignas(16) float px[4], py[4], pz[4];
  for (int lane = 0; lane < 4; ++lane) {
    const bool inside = i + lane < count;
    px[lane] = inside ? points[i + lane].x() : NAN;
    py[lane] = inside ? points[i + lane].y() : NAN;
    pz[lane] = inside ? points[i + lane].z() : NAN;
  }
  alignas(16) std::uint32_t group_keys[4];
  alignas(16) float group_offsets[4][4];
  _mm_store_si128(
      reinterpret_cast<__m128i*>(group_keys),
      key_group(c, _mm_load_ps(px), _mm_load_ps(py), _mm_load_ps(pz), row0, row1, row2, row3));
  _mm_store_ps(group_offsets[0], row0);
  _mm_store_ps(group_offsets[1], row1);
  _mm_store_ps(group_offsets[2], row2);
  _mm_store_ps(group_offsets[3], row3);
  for (int lane = 0; i + lane < count; ++lane) {
    keys[i + lane] = group_keys[lane];
    std::memcpy(offsets[i + lane], group_offsets[lane], sizeof(group_offsets[lane]));
  }
}
#endif  // __SSE2__

}  // namespace litamin2::sse2_voting
