// The occlusion test's rows (prep/OcclusionRows.h): AVX-512's walks, eight pixels at a time with the settled
// ones masked, must leave every bound and face owner bit-identical to the portable walks' (pixel by pixel,
// the settled ones skipped), and end with the same hidden flags. Checked on rows of a real ellipsoid's
// chords, with bounds, box faces and solids drawn around its entries and exits so that every branch is taken
// (settled and not, clipped to nothing and not, owned and not), over spans of every length from 0 to 40 at
// every start modulo the eight lanes.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <random>
#include <vector>

#include <glm/glm.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include "prep/CpuFeatures.h"
#include "prep/OcclusionRows.h"
#include "prep/ViewChords.h"

namespace spindrift {
namespace {

using occlusion_rows::kNoOwner;

// One row's arrays, owned.
struct RowArrays {
  std::vector<double> front, back, enter, leave, solid;
  std::vector<std::uint32_t> frontOwner, backOwner;

  occlusion_rows::RowBounds bounds(bool domain, bool solids) {
    occlusion_rows::RowBounds b;
    b.frontAtMost = front.data();
    b.backAtLeast = back.data();
    if (domain) {
      b.boxEnter = enter.data(), b.boxLeave = leave.data();
      b.frontFaceOwner = frontOwner.data(), b.backFaceOwner = backOwner.data();
    }
    if (solids) b.solidNearest = solid.data(), b.solidFarthest = solid.data();
    return b;
  }
};

constexpr int kWidth = 64;
constexpr double kFocal = 40.0;

// A tilted ellipsoid 3 units before the eye, seen by a camera at the origin looking down -z.
view_chords::ChordPolynomials tiltedEllipsoidChords() {
  EllipsoidInstance instance{};
  instance.centreAndBoundingRadius = glm::vec4(0.1f, -0.05f, -3.0f, 0.3f);
  const glm::mat3 axes = glm::mat3(glm::rotate(glm::mat4(1.0f), 0.6f, glm::normalize(glm::vec3(1, 2, 3))));
  const glm::vec3 inverseLengths(1.0f / 0.3f, 1.0f / 0.2f, 1.0f / 0.12f);
  for (int k = 0; k < 3; ++k)
    instance.inverseAxesRows[k] = glm::vec4(inverseLengths[k] * glm::transpose(axes)[k], 0.0f);
  const glm::dvec3 centre(instance.centreAndBoundingRadius);
  return view_chords::ChordPolynomials(view_chords::cameraEllipsoid(instance, glm::dmat3(1.0), centre));
}

// The rays' u across a row of kWidth pixels.
std::vector<double> rayColumns() {
  std::vector<double> u(kWidth);
  for (int x = 0; x < kWidth; ++x)
    u[std::size_t(x)] = (x + 0.5 - 0.5 * kWidth) / kFocal;
  return u;
}

// The ellipsoid of tiltedEllipsoidChords as both tests cover or hide it.
occlusion_rows::Cover tiltedCover() {
  occlusion_rows::Cover cover;
  cover.index = 7;
  cover.chordMargin = 0.01;
  cover.nearest = 3.0 - 0.3 - 0.02;
  cover.farthest = 3.0 + 0.3 + 0.02;
  return cover;
}

// Every case both tests walk: rows across the ellipsoid scaled by `scale`, with and without a domain box and
// solids, spans of 0 to 40 pixels from every start modulo the eight lanes.
template <typename Walk>
void forEveryRow(const view_chords::ChordPolynomials& chords, double scale, const Walk& walk) {
  for (int y = -12; y <= 12; y += 3) {
    const view_chords::RowChords row(chords, scale, y / kFocal);
    for (const bool domain : {false, true})
      for (const bool solids : {false, true})
        for (int first = 0; first < 8; ++first)
          for (int length = 0; length <= 40; ++length)
            walk(row, domain, solids, first, std::min(first + length - 1, kWidth - 1));
  }
}

template <typename T>
std::size_t differing(const std::vector<T>& a, const std::vector<T>& b) {
  std::size_t count = 0;
  for (std::size_t k = 0; k < a.size(); ++k)
    count += std::memcmp(&a[k], &b[k], sizeof(T)) != 0;
  return count;
}

TEST(OcclusionRows, AvxAndPortableWalksLeaveTheSameBoundsAndOwners) {
  if (!cpuHasAvx512()) GTEST_SKIP() << "this CPU has no AVX-512: only the portable walk runs";
  const std::vector<double> u = rayColumns();
  std::mt19937 random(11);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  occlusion_rows::Cover cover = tiltedCover();
  std::size_t rows = 0, lowered = 0, raised = 0, frontOwned = 0, backOwned = 0;
  forEveryRow(tiltedEllipsoidChords(), 0.98,
              [&](const view_chords::RowChords& row, bool domain, bool solids, int first, int last) {
                // Bounds around the chord where there is one, anything elsewhere; some infinite.
                RowArrays arrays;
                for (int x = 0; x < kWidth; ++x) {
                  double entry = 3.0, exit = 3.2;
                  row.at(u[std::size_t(x)], entry, exit);
                  const auto around = [&](double value) { return value + 0.08 * (unit(random) - 0.5); };
                  const double pick = unit(random);
                  arrays.front.push_back(pick < 0.1 ? INFINITY : around(entry));
                  arrays.back.push_back(pick > 0.9 ? -INFINITY : around(exit));
                  arrays.enter.push_back(unit(random) < 0.5 ? around(entry) : entry - 1.0);
                  arrays.leave.push_back(unit(random) < 0.5 ? around(exit) : exit + 1.0);
                  arrays.solid.push_back(unit(random) < 0.3 ? around(entry) : INFINITY);
                  arrays.frontOwner.push_back(unit(random) < 0.3 ? 3u : kNoOwner);
                  arrays.backOwner.push_back(unit(random) < 0.3 ? 4u : kNoOwner);
                }
                cover.mayOwnFront = unit(random) < 0.8;
                cover.mayOwnBack = unit(random) < 0.8;
                RowArrays portable = arrays, fastest = arrays;
                occlusion_rows::coverRow(row, u.data(), first, last, cover, portable.bounds(domain, solids),
                                         occlusion_rows::Walk::Portable);
                occlusion_rows::coverRow(row, u.data(), first, last, cover, fastest.bounds(domain, solids),
                                         occlusion_rows::Walk::Fastest);
                EXPECT_EQ(differing(portable.front, fastest.front), 0u) << first << " " << last;
                EXPECT_EQ(differing(portable.back, fastest.back), 0u) << first << " " << last;
                EXPECT_EQ(differing(portable.frontOwner, fastest.frontOwner), 0u) << first << " " << last;
                EXPECT_EQ(differing(portable.backOwner, fastest.backOwner), 0u) << first << " " << last;
                ++rows;
                lowered += differing(arrays.front, portable.front);
                raised += differing(arrays.back, portable.back);
                frontOwned += differing(arrays.frontOwner, portable.frontOwner);
                backOwned += differing(arrays.backOwner, portable.backOwner);
              });
  // Every kind of change happened, many times.
  EXPECT_GT(rows, 2000u);
  EXPECT_GT(lowered, 1000u);
  EXPECT_GT(raised, 1000u);
  EXPECT_GT(frontOwned, 100u);
  EXPECT_GT(backOwned, 100u);
}

TEST(OcclusionRows, ShownSpansEndAtTheShownPixelsAndAgreeBetweenWalks) {
  // Bounds that hide the ellipsoid at every pixel but a few (or none), each layer its own, by a random
  // spread past the margin: each layer's span ends at such pixels, holds every one of them where nothing
  // else hides the ellipsoid (no box, solid or face owner) and its ray meets it, and is the same in both
  // walks, whichever lanes they fall in.
  const std::vector<double> u = rayColumns();
  std::mt19937 random(17);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const occlusion_rows::Cover cover = tiltedCover();
  std::size_t walks = 0, shownFront = 0, shownBack = 0;
  forEveryRow(
      tiltedEllipsoidChords(), 1.02,
      [&](const view_chords::RowChords& row, bool domain, bool solids, int first, int last) {
        for (const double spread : {0.02, 0.2}) {
          // Up to two pixels of the walked span per layer (it may reach past the row's end); -1: none.
          const auto pick = [&] {
            return unit(random) < 0.2 ? -1 : first + int(unit(random) * (last - first + 1));
          };
          const int chosen[2][2] = {{pick(), pick()}, {pick(), pick()}};
          const auto isChosen = [&](int layer, int x) {
            return x == chosen[layer][0] || x == chosen[layer][1];
          };
          RowArrays arrays;
          for (int x = 0; x < kWidth; ++x) {
            double entry = 3.0, exit = 3.2;
            row.at(u[std::size_t(x)], entry, exit);
            arrays.front.push_back(isChosen(0, x) ? entry : entry - 0.011 - spread * unit(random));
            arrays.back.push_back(isChosen(1, x) ? exit : exit + 0.011 + spread * unit(random));
            arrays.enter.push_back(unit(random) < 0.5 ? entry + 0.05 * (unit(random) - 0.5) : entry - 1.0);
            arrays.leave.push_back(unit(random) < 0.5 ? exit + 0.05 * (unit(random) - 0.5) : exit + 1.0);
            arrays.solid.push_back(unit(random) < 0.05 ? cover.nearest - 0.01 : INFINITY);
            const double owner = unit(random);
            arrays.frontOwner.push_back(owner < 0.03 ? 3u : owner < 0.06 ? 7u : kNoOwner);
            arrays.backOwner.push_back(owner > 0.97 ? 4u : owner > 0.94 ? 7u : kNoOwner);
          }
          const occlusion_rows::RowBounds bounds = arrays.bounds(domain, solids);
          const bool inFront = unit(random) < 0.8, inBack = unit(random) < 0.8;
          occlusion_rows::ShownSpan front[2], back[2];
          occlusion_rows::shownRow(row, u.data(), first, last, cover, bounds, inFront, inBack, front[0],
                                   back[0], occlusion_rows::Walk::Portable);
          occlusion_rows::shownRow(row, u.data(), first, last, cover, bounds, inFront, inBack, front[1],
                                   back[1], occlusion_rows::Walk::Fastest);
          EXPECT_EQ(front[0].first, front[1].first) << first << " " << last;
          EXPECT_EQ(front[0].last, front[1].last) << first << " " << last;
          EXPECT_EQ(back[0].first, back[1].first) << first << " " << last;
          EXPECT_EQ(back[0].last, back[1].last) << first << " " << last;
          const occlusion_rows::ShownSpan* spans[2] = {&front[0], &back[0]};
          const bool inLayer[2] = {inFront, inBack};
          for (int layer = 0; layer < 2; ++layer) {
            const occlusion_rows::ShownSpan& span = *spans[layer];
            if (!inLayer[layer]) EXPECT_TRUE(span.empty());
            if (span.empty()) continue;
            EXPECT_TRUE(isChosen(layer, span.first) && isChosen(layer, span.last))
                << span.first << " " << span.last;
            for (const int x : chosen[layer]) {
              double entry, exit;
              if (domain || solids || x < 0 || x >= kWidth || !row.at(u[std::size_t(x)], entry, exit))
                continue;
              EXPECT_TRUE(span.first <= x && x <= span.last) << x;
            }
          }
          ++walks;
          shownFront += !front[0].empty();
          shownBack += !back[0].empty();
        }
      });
  // Each layer shown in some walks and not in others (most spans miss the ellipse or its clipped chord).
  EXPECT_GT(walks, 4000u);
  EXPECT_GT(shownFront, 200u);
  EXPECT_GT(shownBack, 200u);
  EXPECT_LT(shownFront, walks - 2000u);
  EXPECT_LT(shownBack, walks - 2000u);
}

TEST(OcclusionRows, AnEmptySpanChangesNothing) {
  const view_chords::ChordPolynomials chords = [] {
    EllipsoidInstance sphere{};
    sphere.centreAndBoundingRadius = glm::vec4(0.0f, 0.0f, -2.0f, 0.5f);
    for (int k = 0; k < 3; ++k)
      sphere.inverseAxesRows[k][k] = 2.0f;
    return view_chords::ChordPolynomials(
        view_chords::cameraEllipsoid(sphere, glm::dmat3(1.0), glm::dvec3(sphere.centreAndBoundingRadius)));
  }();
  const view_chords::RowChords row(chords, 1.0, 0.0);
  std::vector<double> u(16, 0.0), front(16, INFINITY), back(16, -INFINITY);
  occlusion_rows::RowBounds bounds;
  bounds.frontAtMost = front.data();
  bounds.backAtLeast = back.data();
  for (const occlusion_rows::Walk walk : {occlusion_rows::Walk::Portable, occlusion_rows::Walk::Fastest})
    occlusion_rows::coverRow(row, u.data(), 5, 4, occlusion_rows::Cover{}, bounds, walk);
  for (int x = 0; x < 16; ++x) {
    EXPECT_EQ(front[std::size_t(x)], INFINITY);
    EXPECT_EQ(back[std::size_t(x)], -INFINITY);
  }
}

}  // namespace
}  // namespace spindrift
