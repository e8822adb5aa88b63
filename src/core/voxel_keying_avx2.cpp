// key_block_avx2: key_block_sse2 eight points at a time. Compiled for AVX2 by a function
// attribute (not by a -m flag), so the rest of the library stays baseline x86-64; it is only
// called where cpu_has_avx2(). No FMA: the same roundings as the SSE2 version.
#include "litamin2/core/voxel_keying.hpp"

#if defined(__SSE2__) && defined(__GNUC__)
#include <immintrin.h>

namespace litamin2::sse2_voting {

static_assert(sizeof(Eigen::Vector3f) == 3 * sizeof(float), "points are packed x, y, z");

__attribute__((target("avx2"))) void key_block_avx2(const Eigen::Vector3f* points, int count,
                                                    const KeyingFrame& f, std::uint32_t* keys,
                                                    float (*offsets)[4]) {
  const __m256 r00 = _mm256_set1_ps(f.rotation[0]), r01 = _mm256_set1_ps(f.rotation[1]),
               r02 = _mm256_set1_ps(f.rotation[2]);
  const __m256 r10 = _mm256_set1_ps(f.rotation[3]), r11 = _mm256_set1_ps(f.rotation[4]),
               r12 = _mm256_set1_ps(f.rotation[5]);
  const __m256 r20 = _mm256_set1_ps(f.rotation[6]), r21 = _mm256_set1_ps(f.rotation[7]),
               r22 = _mm256_set1_ps(f.rotation[8]);
  const __m256 tx = _mm256_set1_ps(f.translation[0]), ty = _mm256_set1_ps(f.translation[1]),
               tz = _mm256_set1_ps(f.translation[2]);
  const __m256 inv_size = _mm256_set1_ps(f.inv_voxel_size);
  const __m256 size_f = _mm256_set1_ps(f.voxel_size);
  const __m256 half = _mm256_set1_ps(0.5f);
  const __m256 one = _mm256_set1_ps(1.0f);
  const __m256 min_range_sq = _mm256_set1_ps(f.min_range_sq);
  const __m256 max_range_sq = _mm256_set1_ps(f.max_range_sq);
  const __m256i bias = _mm256_set1_epi32(kLocalBias);
  const __m256i invalid = _mm256_set1_epi32(static_cast<int>(kInvalidKey));

  int i = 0;
  for (; i + 8 <= count; i += 8) {
    // x, y, z of points i..i+7 from 24 packed floats: each 128-bit half holds four points
    // (i..i+3 low, i+4..i+7 high), de-interleaved by five shuffles.
    const float* p = points[i].data();
    const __m256 m03 = _mm256_insertf128_ps(_mm256_castps128_ps256(_mm_loadu_ps(p)),
                                            _mm_loadu_ps(p + 12), 1);  // x0 y0 z0 x1
    const __m256 m14 = _mm256_insertf128_ps(_mm256_castps128_ps256(_mm_loadu_ps(p + 4)),
                                            _mm_loadu_ps(p + 16), 1);  // y1 z1 x2 y2
    const __m256 m25 = _mm256_insertf128_ps(_mm256_castps128_ps256(_mm_loadu_ps(p + 8)),
                                            _mm_loadu_ps(p + 20), 1);        // z2 x3 y3 z3
    const __m256 xy = _mm256_shuffle_ps(m14, m25, _MM_SHUFFLE(2, 1, 3, 2));  // x2 y2 x3 y3
    const __m256 yz = _mm256_shuffle_ps(m03, m14, _MM_SHUFFLE(1, 0, 2, 1));  // y0 z0 y1 z1
    const __m256 x = _mm256_shuffle_ps(m03, xy, _MM_SHUFFLE(2, 0, 3, 0));
    const __m256 y = _mm256_shuffle_ps(yz, xy, _MM_SHUFFLE(3, 1, 2, 0));
    const __m256 z = _mm256_shuffle_ps(yz, m25, _MM_SHUFFLE(3, 0, 3, 1));

    const __m256 range_sq =
        _mm256_add_ps(_mm256_add_ps(_mm256_mul_ps(x, x), _mm256_mul_ps(y, y)), _mm256_mul_ps(z, z));
    // Ordered compares: false for NaN, so non-finite points are dropped too.
    const __m256 in_range = _mm256_and_ps(_mm256_cmp_ps(range_sq, min_range_sq, _CMP_GE_OQ),
                                          _mm256_cmp_ps(range_sq, max_range_sq, _CMP_LE_OQ));
    const __m256 wx =
        _mm256_add_ps(_mm256_add_ps(_mm256_add_ps(_mm256_mul_ps(r00, x), _mm256_mul_ps(r01, y)),
                                    _mm256_mul_ps(r02, z)),
                      tx);
    const __m256 wy =
        _mm256_add_ps(_mm256_add_ps(_mm256_add_ps(_mm256_mul_ps(r10, x), _mm256_mul_ps(r11, y)),
                                    _mm256_mul_ps(r12, z)),
                      ty);
    const __m256 wz =
        _mm256_add_ps(_mm256_add_ps(_mm256_add_ps(_mm256_mul_ps(r20, x), _mm256_mul_ps(r21, y)),
                                    _mm256_mul_ps(r22, z)),
                      tz);
    // floor is exact, so these equal the SSE2 version's truncate-and-correct floors.
    const __m256 fx = _mm256_floor_ps(_mm256_mul_ps(wx, inv_size));
    const __m256 fy = _mm256_floor_ps(_mm256_mul_ps(wy, inv_size));
    const __m256 fz = _mm256_floor_ps(_mm256_mul_ps(wz, inv_size));
    const __m256i ix = _mm256_cvttps_epi32(fx);
    const __m256i iy = _mm256_cvttps_epi32(fy);
    const __m256i iz = _mm256_cvttps_epi32(fz);
    // Offsets from the voxel centres (float(index) as the SSE2 version computes it).
    const __m256 dx =
        _mm256_sub_ps(wx, _mm256_mul_ps(_mm256_add_ps(_mm256_cvtepi32_ps(ix), half), size_f));
    const __m256 dy =
        _mm256_sub_ps(wy, _mm256_mul_ps(_mm256_add_ps(_mm256_cvtepi32_ps(iy), half), size_f));
    const __m256 dz =
        _mm256_sub_ps(wz, _mm256_mul_ps(_mm256_add_ps(_mm256_cvtepi32_ps(iz), half), size_f));
    // (dx, dy, dz, 1) per point: a 4x4 transpose in each half, then pairs of rows stored.
    const __m256 t0 = _mm256_unpacklo_ps(dx, dy);                          // x0 y0 x1 y1
    const __m256 t1 = _mm256_unpackhi_ps(dx, dy);                          // x2 y2 x3 y3
    const __m256 t2 = _mm256_unpacklo_ps(dz, one);                         // z0 1 z1 1
    const __m256 t3 = _mm256_unpackhi_ps(dz, one);                         // z2 1 z3 1
    const __m256 p0 = _mm256_shuffle_ps(t0, t2, _MM_SHUFFLE(1, 0, 1, 0));  // points 0 | 4
    const __m256 p1 = _mm256_shuffle_ps(t0, t2, _MM_SHUFFLE(3, 2, 3, 2));  // points 1 | 5
    const __m256 p2 = _mm256_shuffle_ps(t1, t3, _MM_SHUFFLE(1, 0, 1, 0));  // points 2 | 6
    const __m256 p3 = _mm256_shuffle_ps(t1, t3, _MM_SHUFFLE(3, 2, 3, 2));  // points 3 | 7
    _mm256_storeu_ps(offsets[i], _mm256_permute2f128_ps(p0, p1, 0x20));
    _mm256_storeu_ps(offsets[i + 2], _mm256_permute2f128_ps(p2, p3, 0x20));
    _mm256_storeu_ps(offsets[i + 4], _mm256_permute2f128_ps(p0, p1, 0x31));
    _mm256_storeu_ps(offsets[i + 6], _mm256_permute2f128_ps(p2, p3, 0x31));

    const __m256i key =
        _mm256_or_si256(_mm256_or_si256(_mm256_add_epi32(ix, bias),
                                        _mm256_slli_epi32(_mm256_add_epi32(iy, bias), kLocalBits)),
                        _mm256_slli_epi32(_mm256_add_epi32(iz, bias), 2 * kLocalBits));
    const __m256i valid = _mm256_castps_si256(in_range);
    _mm256_storeu_si256(
        reinterpret_cast<__m256i*>(keys + i),
        _mm256_or_si256(_mm256_and_si256(valid, key), _mm256_andnot_si256(valid, invalid)));
  }
  if (i < count) key_block_sse2(points + i, count - i, f, keys + i, offsets + i);
}

}  // namespace litamin2::sse2_voting

#endif
