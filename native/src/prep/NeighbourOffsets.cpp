#include "prep/NeighbourOffsets.h"

#include <algorithm>

#include <immintrin.h>

#include "prep/CpuFeatures.h"

namespace spindrift {
namespace {

// AVX-512's lanes compacted in registers and stored whole (16 values), the pointers then advanced by how many
// were kept: each output has 16 entries of room past the last candidate. The compress is done in a register
// because some CPUs (AMD's Zen 4) microcode its form that stores to memory. |q|^2 is summed as the scalar
// code sums it, (qx qx + qy qy) + qz qz, without fused multiply-adds; the offsets kept are the same
// differences x_j - x_i the portable gathering computes.
__attribute__((target("avx512f"))) int keepWithinAvx512(const ParticleCloud& cloud, const IndexRange* ranges,
                                                        int rangeCount, float px, float py, float pz,
                                                        float inverseRadius, std::uint32_t* kept,
                                                        float* keptX, float* keptY, float* keptZ) {
  const __m512 particleX = _mm512_set1_ps(px), particleY = _mm512_set1_ps(py), particleZ = _mm512_set1_ps(pz);
  const __m512 scale = _mm512_set1_ps(inverseRadius), one = _mm512_set1_ps(1.0f);
  const __m512i lanes = _mm512_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15);
  const float* xs = cloud.x.data();
  const float* ys = cloud.y.data();
  const float* zs = cloud.z.data();
  int keptCount = 0;
  for (int r = 0; r < rangeCount; ++r) {
    const int length = int(ranges[r].end - ranges[r].begin);
    for (int j = 0; j < length; j += 16) {
      const __mmask16 valid = length - j >= 16 ? __mmask16(0xffff) : __mmask16((1u << (length - j)) - 1u);
      const std::size_t first = ranges[r].begin + std::size_t(j);
      const __m512 dx = _mm512_sub_ps(_mm512_maskz_loadu_ps(valid, xs + first), particleX);
      const __m512 dy = _mm512_sub_ps(_mm512_maskz_loadu_ps(valid, ys + first), particleY);
      const __m512 dz = _mm512_sub_ps(_mm512_maskz_loadu_ps(valid, zs + first), particleZ);
      const __m512 qx = _mm512_mul_ps(dx, scale), qy = _mm512_mul_ps(dy, scale),
                   qz = _mm512_mul_ps(dz, scale);
      const __m512 squared =
          _mm512_add_ps(_mm512_add_ps(_mm512_mul_ps(qx, qx), _mm512_mul_ps(qy, qy)), _mm512_mul_ps(qz, qz));
      const __mmask16 inside = _mm512_mask_cmp_ps_mask(valid, squared, one, _CMP_LT_OQ);
      const __m512i index = _mm512_add_epi32(_mm512_set1_epi32(int(first)), lanes);
      _mm512_storeu_si512(kept + keptCount, _mm512_maskz_compress_epi32(inside, index));
      _mm512_storeu_ps(keptX + keptCount, _mm512_maskz_compress_ps(inside, dx));
      _mm512_storeu_ps(keptY + keptCount, _mm512_maskz_compress_ps(inside, dy));
      _mm512_storeu_ps(keptZ + keptCount, _mm512_maskz_compress_ps(inside, dz));
      keptCount += __builtin_popcount(inside);
    }
  }
  return keptCount;
}

// The same without AVX-512: the distances vectorised, then each index written and only those inside kept.
int keepWithinPortable(const ParticleCloud& cloud, IndexRange range, float px, float py, float pz,
                       float inverseRadius, float* squaredDistances, std::uint32_t* kept) {
  // Contiguous loads need a pointer and a signed count: a 32-bit unsigned index may wrap, which makes the
  // vectoriser gather each element.
  const float* rangeX = cloud.x.data() + range.begin;
  const float* rangeY = cloud.y.data() + range.begin;
  const float* rangeZ = cloud.z.data() + range.begin;
  const int length = int(range.end - range.begin);
#pragma omp simd
  for (int j = 0; j < length; ++j) {
    const float qx = (rangeX[j] - px) * inverseRadius;
    const float qy = (rangeY[j] - py) * inverseRadius;
    const float qz = (rangeZ[j] - pz) * inverseRadius;
    squaredDistances[j] = qx * qx + qy * qy + qz * qz;
  }
  int keptCount = 0;
  for (int j = 0; j < length; ++j) {
    kept[keptCount] = range.begin + std::uint32_t(j);
    keptCount += squaredDistances[j] < 1.0f;
  }
  return keptCount;
}

}  // namespace

void NeighbourOffsets::gather(const ParticleCloud& cloud, std::uint32_t particle, float inverseRadius,
                              const IndexRange* ranges, int rangeCount, Compaction compaction) {
  std::size_t candidates = 0, longest = 0;
  for (int r = 0; r < rangeCount; ++r) {
    candidates += ranges[r].end - ranges[r].begin;
    longest = std::max<std::size_t>(longest, ranges[r].end - ranges[r].begin);
  }
  if (kept_.size() < candidates + 16) {
    kept_.resize(candidates + 16);
    x_.resize(candidates + 16), y_.resize(candidates + 16), z_.resize(candidates + 16);
  }
  const float px = cloud.x[particle], py = cloud.y[particle], pz = cloud.z[particle];
  if (cpuHasAvx512() && compaction == Compaction::Fastest) {
    count_ = keepWithinAvx512(cloud, ranges, rangeCount, px, py, pz, inverseRadius, kept_.data(), x_.data(),
                              y_.data(), z_.data());
    return;
  }
  if (squaredDistances_.size() < longest) squaredDistances_.resize(longest);
  int keptCount = 0;
  for (int r = 0; r < rangeCount; ++r)
    keptCount += keepWithinPortable(cloud, ranges[r], px, py, pz, inverseRadius, squaredDistances_.data(),
                                    &kept_[keptCount]);
  count_ = keptCount;
  for (int k = 0; k < keptCount; ++k) {
    x_[k] = cloud.x[kept_[k]] - px;
    y_[k] = cloud.y[kept_[k]] - py;
    z_[k] = cloud.z[kept_[k]] - pz;
  }
}

}  // namespace spindrift
