#include "prep/OcclusionRows.h"

#include <algorithm>

#include <immintrin.h>

#include "prep/CpuFeatures.h"

namespace spindrift::occlusion_rows {
namespace {

// Pixel by pixel. A pixel both of whose bounds are settled (the ellipsoid can neither lower the front's nor
// raise the back's, nor take a face it cannot reach) is passed over without its chord.
void coverRowPortable(const view_chords::RowChords& row, const double* u, int firstX, int lastX,
                      const Cover& cover, const RowBounds& bounds) {
  const bool domain = bounds.boxEnter != nullptr;
  for (int x = firstX; x <= lastX; ++x) {
    const bool frontSettled =
        domain ? bounds.frontFaceOwner[x] != kNoOwner ||
                     (bounds.frontAtMost[x] <= cover.nearest && cover.nearest >= bounds.boxEnter[x])
               : bounds.frontAtMost[x] <= cover.nearest;
    const bool backSettled =
        domain ? bounds.backFaceOwner[x] != kNoOwner ||
                     (bounds.backAtLeast[x] >= cover.farthest && cover.farthest <= bounds.boxLeave[x])
               : bounds.backAtLeast[x] >= cover.farthest;
    if (frontSettled && backSettled) continue;
    double entry, exit;
    if (!row.at(u[x], entry, exit)) continue;
    // Where a domain box cuts it, its surfaces are the clipped chord's ends, if any are left (as the impostor
    // pass clips them, lib/ellipsoid_ray.glsl).
    const double unclippedEntry = entry, unclippedExit = exit;
    if (domain) {
      entry = std::max(entry, bounds.boxEnter[x]);
      exit = std::min(exit, bounds.boxLeave[x]);
    }
    const bool clipped = entry != unclippedEntry || exit != unclippedExit;
    if (clipped && !(entry < exit - 2.0 * cover.chordMargin)) continue;
    // It covers the back layer only where its front lies before the solids (the impostor pass hides it
    // where its entry lies behind one).
    const bool coversBack = !bounds.solidNearest || entry + cover.chordMargin < bounds.solidNearest[x];
    bounds.frontAtMost[x] = std::min(bounds.frontAtMost[x], entry + cover.chordMargin);
    if (coversBack) bounds.backAtLeast[x] = std::max(bounds.backAtLeast[x], exit - cover.chordMargin);
    if (!domain) continue;
    if (cover.mayOwnFront && bounds.frontFaceOwner[x] == kNoOwner &&
        unclippedEntry < bounds.boxEnter[x] - 2.0 * cover.chordMargin)
      bounds.frontFaceOwner[x] = cover.index;
    if (coversBack && cover.mayOwnBack && bounds.backFaceOwner[x] == kNoOwner &&
        unclippedExit > bounds.boxLeave[x] + 2.0 * cover.chordMargin)
      bounds.backFaceOwner[x] = cover.index;
  }
}

// RowChords::at for eight rays at once, each lane computed as it computes one: the same operations in the
// same order, no fused multiply-adds.
struct VectorRowChords {
  __m512d lengths2, lengths1, lengths0, cone2, cone1, cone0, alongSlope, alongOffset;

  __attribute__((target("avx512f"))) explicit VectorRowChords(const view_chords::RowChords& row)
      : lengths2(_mm512_set1_pd(row.lengths.q2)),
        lengths1(_mm512_set1_pd(row.lengths.q1)),
        lengths0(_mm512_set1_pd(row.lengths.q0)),
        cone2(_mm512_set1_pd(row.cone.q2)),
        cone1(_mm512_set1_pd(row.cone.q1)),
        cone0(_mm512_set1_pd(row.cone.q0)),
        alongSlope(_mm512_set1_pd(row.alongSlope)),
        alongOffset(_mm512_set1_pd(row.alongOffset)) {}

  // The lanes of `active` whose rays (u, v, -1) meet the ellipsoid, with their entries and exits.
  __attribute__((target("avx512f"))) __mmask8 at(__m512d u, __mmask8 active, __m512d& entry,
                                                 __m512d& exit) const {
    const __m512d zero = _mm512_setzero_pd();
    const __m512d lengthSquared =
        _mm512_add_pd(_mm512_mul_pd(_mm512_add_pd(_mm512_mul_pd(lengths2, u), lengths1), u), lengths0);
    const __m512d missing =
        _mm512_add_pd(_mm512_mul_pd(_mm512_add_pd(_mm512_mul_pd(cone2, u), cone1), u), cone0);
    active &=
        _mm512_cmp_pd_mask(missing, zero, _CMP_GE_OQ) & _mm512_cmp_pd_mask(lengthSquared, zero, _CMP_GT_OQ);
    const __m512d along = _mm512_add_pd(_mm512_mul_pd(alongSlope, u), alongOffset);
    // Only the active lanes: the others may be negative or zero.
    const __m512d half = _mm512_maskz_sqrt_pd(active, missing);
    const __m512d inverseLength = _mm512_maskz_div_pd(active, _mm512_set1_pd(1.0), lengthSquared);
    entry = _mm512_mul_pd(_mm512_sub_pd(along, half), inverseLength);
    exit = _mm512_mul_pd(_mm512_add_pd(along, half), inverseLength);
    return active;
  }
};

// Eight pixels at a time, each lane as the portable walk computes it (the same operations in the same order,
// no fused multiply-adds, std::min and std::max as blends on the same comparisons), the settled lanes
// masked: on the dam break nearly every pixel's back is unsettled in the nearest-first order, so its chord
// is needed anyway, and eight cost about what one does.
__attribute__((target("avx512f"))) void coverRowAvx512(const view_chords::RowChords& row, const double* u,
                                                       int firstX, int lastX, const Cover& cover,
                                                       const RowBounds& bounds) {
  const bool domain = bounds.boxEnter != nullptr;
  const VectorRowChords chords(row);
  const __m512d zero = _mm512_setzero_pd();
  const __m512d margin = _mm512_set1_pd(cover.chordMargin),
                twoMargins = _mm512_set1_pd(2.0 * cover.chordMargin);
  const __m512d nearest = _mm512_set1_pd(cover.nearest), farthest = _mm512_set1_pd(cover.farthest);
  const __m512i noOwner = _mm512_set1_epi32(int(kNoOwner)), index = _mm512_set1_epi32(int(cover.index));
  for (int x = firstX; x <= lastX; x += 8) {
    const int left = lastX - x + 1;
    const __mmask8 lanes = left >= 8 ? __mmask8(0xff) : __mmask8((1u << left) - 1u);
    const __m512d front = _mm512_maskz_loadu_pd(lanes, bounds.frontAtMost + x);
    const __m512d back = _mm512_maskz_loadu_pd(lanes, bounds.backAtLeast + x);
    __m512d boxEnter = zero, boxLeave = zero;
    __mmask8 frontOwned = 0, backOwned = 0, frontUnowned = 0, backUnowned = 0;
    __mmask8 frontSettled, backSettled;
    if (domain) {
      boxEnter = _mm512_maskz_loadu_pd(lanes, bounds.boxEnter + x);
      boxLeave = _mm512_maskz_loadu_pd(lanes, bounds.boxLeave + x);
      const __mmask16 lanes16 = lanes;
      const __mmask16 frontFree = _mm512_mask_cmpeq_epi32_mask(
          lanes16, _mm512_maskz_loadu_epi32(lanes16, bounds.frontFaceOwner + x), noOwner);
      const __mmask16 backFree = _mm512_mask_cmpeq_epi32_mask(
          lanes16, _mm512_maskz_loadu_epi32(lanes16, bounds.backFaceOwner + x), noOwner);
      frontUnowned = __mmask8(frontFree), backUnowned = __mmask8(backFree);
      frontOwned = lanes & ~frontUnowned, backOwned = lanes & ~backUnowned;
      frontSettled = frontOwned | (_mm512_cmp_pd_mask(front, nearest, _CMP_LE_OQ) &
                                   _mm512_cmp_pd_mask(nearest, boxEnter, _CMP_GE_OQ));
      backSettled = backOwned | (_mm512_cmp_pd_mask(back, farthest, _CMP_GE_OQ) &
                                 _mm512_cmp_pd_mask(farthest, boxLeave, _CMP_LE_OQ));
    } else {
      frontSettled = _mm512_cmp_pd_mask(front, nearest, _CMP_LE_OQ);
      backSettled = _mm512_cmp_pd_mask(back, farthest, _CMP_GE_OQ);
    }
    __mmask8 active = lanes & ~(frontSettled & backSettled);
    if (!active) continue;
    __m512d unclippedEntry, unclippedExit;
    active = chords.at(_mm512_maskz_loadu_pd(lanes, u + x), active, unclippedEntry, unclippedExit);
    if (!active) continue;
    __m512d entry = unclippedEntry, exit = unclippedExit;
    if (domain) {
      // std::max(entry, enter) is enter where entry < enter; std::min(exit, leave) is leave where leave <
      // exit.
      entry = _mm512_mask_blend_pd(_mm512_cmp_pd_mask(entry, boxEnter, _CMP_LT_OQ), entry, boxEnter);
      exit = _mm512_mask_blend_pd(_mm512_cmp_pd_mask(boxLeave, exit, _CMP_LT_OQ), exit, boxLeave);
      const __mmask8 clipped = _mm512_cmp_pd_mask(entry, unclippedEntry, _CMP_NEQ_UQ) |
                               _mm512_cmp_pd_mask(exit, unclippedExit, _CMP_NEQ_UQ);
      const __mmask8 leftOver = _mm512_cmp_pd_mask(entry, _mm512_sub_pd(exit, twoMargins), _CMP_LT_OQ);
      active &= ~(clipped & ~leftOver);
      if (!active) continue;
    }
    const __m512d frontCandidate = _mm512_add_pd(entry, margin);
    __mmask8 coversBack = active;
    if (bounds.solidNearest)
      coversBack &= _mm512_cmp_pd_mask(frontCandidate, _mm512_maskz_loadu_pd(lanes, bounds.solidNearest + x),
                                       _CMP_LT_OQ);
    // std::min(front, candidate) is the candidate where candidate < front; std::max likewise.
    _mm512_mask_storeu_pd(bounds.frontAtMost + x,
                          active & _mm512_cmp_pd_mask(frontCandidate, front, _CMP_LT_OQ), frontCandidate);
    const __m512d backCandidate = _mm512_sub_pd(exit, margin);
    _mm512_mask_storeu_pd(bounds.backAtLeast + x,
                          coversBack & _mm512_cmp_pd_mask(back, backCandidate, _CMP_LT_OQ), backCandidate);
    if (!domain) continue;
    if (cover.mayOwnFront) {
      const __mmask8 owns =
          active & frontUnowned &
          _mm512_cmp_pd_mask(unclippedEntry, _mm512_sub_pd(boxEnter, twoMargins), _CMP_LT_OQ);
      _mm512_mask_storeu_epi32(bounds.frontFaceOwner + x, __mmask16(owns), index);
    }
    if (cover.mayOwnBack) {
      const __mmask8 owns =
          coversBack & backUnowned &
          _mm512_cmp_pd_mask(unclippedExit, _mm512_add_pd(boxLeave, twoMargins), _CMP_GT_OQ);
      _mm512_mask_storeu_epi32(bounds.backFaceOwner + x, __mmask16(owns), index);
    }
  }
}

// Pixel by pixel. A pixel a solid hides, or whose bounds settle both layers (the ellipsoid is in neither, or
// another surface lies certainly nearer than its bounding sphere, or farther), needs no chord.
void shownRowPortable(const view_chords::RowChords& row, const double* u, int firstX, int lastX,
                      const Cover& cover, const RowBounds& bounds, bool inFront, bool inBack,
                      ShownSpan& front, ShownSpan& back) {
  const bool domain = bounds.boxEnter != nullptr;
  for (int x = firstX; x <= lastX; ++x) {
    if (bounds.solidFarthest && cover.nearest >= bounds.solidFarthest[x]) continue;
    const bool frontTie =
        domain && bounds.frontFaceOwner[x] != kNoOwner && bounds.frontFaceOwner[x] != cover.index;
    const bool backTie =
        domain && bounds.backFaceOwner[x] != kNoOwner && bounds.backFaceOwner[x] != cover.index;
    const bool frontSettled = !inFront || frontTie || bounds.frontAtMost[x] < cover.nearest;
    const bool backSettled = !inBack || backTie || bounds.backAtLeast[x] > cover.farthest;
    if (frontSettled && backSettled) continue;
    double entry, exit;
    if (!row.at(u[x], entry, exit)) continue;
    if (domain) {
      entry = std::max(entry, bounds.boxEnter[x]);
      exit = std::min(exit, bounds.boxLeave[x]);
    }
    if (entry > exit + 2.0 * cover.chordMargin) continue;
    if (inFront && !frontTie && !(bounds.frontAtMost[x] < entry - cover.chordMargin)) front.add(x);
    if (inBack && !backTie && !(bounds.backAtLeast[x] > exit + cover.chordMargin)) back.add(x);
  }
}

// Eight pixels at a time, each lane computed as the portable walk computes it.
__attribute__((target("avx512f"))) void shownRowAvx512(const view_chords::RowChords& row, const double* u,
                                                       int firstX, int lastX, const Cover& cover,
                                                       const RowBounds& bounds, bool inFront, bool inBack,
                                                       ShownSpan& front, ShownSpan& back) {
  const bool domain = bounds.boxEnter != nullptr;
  const VectorRowChords chords(row);
  const __m512d margin = _mm512_set1_pd(cover.chordMargin),
                twoMargins = _mm512_set1_pd(2.0 * cover.chordMargin);
  const __m512d nearest = _mm512_set1_pd(cover.nearest), farthest = _mm512_set1_pd(cover.farthest);
  const __m512i noOwner = _mm512_set1_epi32(int(kNoOwner)), index = _mm512_set1_epi32(int(cover.index));
  const __mmask8 frontLayer = inFront ? __mmask8(0xff) : __mmask8(0),
                 backLayer = inBack ? __mmask8(0xff) : __mmask8(0);
  // Widens a span by the lanes of `shown`, lane k being pixel x + k.
  const auto widen = [](ShownSpan& span, int x, __mmask8 shown) {
    if (!shown) return;
    span.add(x + __builtin_ctz(unsigned(shown)));
    span.add(x + 31 - __builtin_clz(unsigned(shown)));
  };
  for (int x = firstX; x <= lastX; x += 8) {
    const int left = lastX - x + 1;
    const __mmask8 lanes = left >= 8 ? __mmask8(0xff) : __mmask8((1u << left) - 1u);
    __mmask8 active = lanes;
    if (bounds.solidFarthest)
      active &=
          ~_mm512_cmp_pd_mask(nearest, _mm512_maskz_loadu_pd(lanes, bounds.solidFarthest + x), _CMP_GE_OQ);
    __mmask8 frontTie = 0, backTie = 0;
    if (domain) {
      const __mmask16 lanes16 = lanes;
      const __m512i frontOwner = _mm512_maskz_loadu_epi32(lanes16, bounds.frontFaceOwner + x);
      const __m512i backOwner = _mm512_maskz_loadu_epi32(lanes16, bounds.backFaceOwner + x);
      frontTie = __mmask8(_mm512_mask_cmpneq_epi32_mask(lanes16, frontOwner, noOwner) &
                          _mm512_mask_cmpneq_epi32_mask(lanes16, frontOwner, index));
      backTie = __mmask8(_mm512_mask_cmpneq_epi32_mask(lanes16, backOwner, noOwner) &
                         _mm512_mask_cmpneq_epi32_mask(lanes16, backOwner, index));
    }
    const __m512d frontBound = _mm512_maskz_loadu_pd(lanes, bounds.frontAtMost + x);
    const __m512d backBound = _mm512_maskz_loadu_pd(lanes, bounds.backAtLeast + x);
    const __mmask8 frontSettled =
        __mmask8(~frontLayer) | frontTie | _mm512_cmp_pd_mask(frontBound, nearest, _CMP_LT_OQ);
    const __mmask8 backSettled =
        __mmask8(~backLayer) | backTie | _mm512_cmp_pd_mask(backBound, farthest, _CMP_GT_OQ);
    active &= ~(frontSettled & backSettled);
    if (!active) continue;
    __m512d entry, exit;
    active = chords.at(_mm512_maskz_loadu_pd(lanes, u + x), active, entry, exit);
    if (!active) continue;
    if (domain) {
      const __m512d boxEnter = _mm512_maskz_loadu_pd(lanes, bounds.boxEnter + x);
      const __m512d boxLeave = _mm512_maskz_loadu_pd(lanes, bounds.boxLeave + x);
      entry = _mm512_mask_blend_pd(_mm512_cmp_pd_mask(entry, boxEnter, _CMP_LT_OQ), entry, boxEnter);
      exit = _mm512_mask_blend_pd(_mm512_cmp_pd_mask(boxLeave, exit, _CMP_LT_OQ), exit, boxLeave);
    }
    active &= ~_mm512_cmp_pd_mask(entry, _mm512_add_pd(exit, twoMargins), _CMP_GT_OQ);
    widen(front, x,
          active & frontLayer & ~frontTie &
              ~_mm512_cmp_pd_mask(frontBound, _mm512_sub_pd(entry, margin), _CMP_LT_OQ));
    widen(back, x,
          active & backLayer & ~backTie &
              ~_mm512_cmp_pd_mask(backBound, _mm512_add_pd(exit, margin), _CMP_GT_OQ));
  }
}

// A row of one pixel costs the vector walk its set-up for one lane: the benchmark's bigger bake (150,000
// particles, an ellipsoid or two pixels each) took its hide pass from 11.7 to 12.5 ms with every row
// vectorised.
constexpr int kShortestVectorRow = 2;

}  // namespace

void coverRow(const view_chords::RowChords& row, const double* u, int firstX, int lastX, const Cover& cover,
              const RowBounds& bounds, Walk walk) {
  if (walk == Walk::Fastest && cpuHasAvx512() && lastX - firstX + 1 >= kShortestVectorRow)
    coverRowAvx512(row, u, firstX, lastX, cover, bounds);
  else
    coverRowPortable(row, u, firstX, lastX, cover, bounds);
}

void shownRow(const view_chords::RowChords& row, const double* u, int firstX, int lastX, const Cover& cover,
              const RowBounds& bounds, bool inFront, bool inBack, ShownSpan& front, ShownSpan& back,
              Walk walk) {
  if (walk == Walk::Fastest && cpuHasAvx512() && lastX - firstX + 1 >= kShortestVectorRow)
    shownRowAvx512(row, u, firstX, lastX, cover, bounds, inFront, inBack, front, back);
  else
    shownRowPortable(row, u, firstX, lastX, cover, bounds, inFront, inBack, front, back);
}

}  // namespace spindrift::occlusion_rows
