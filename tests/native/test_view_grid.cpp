// The occlusion test's pixel rectangles (view_chords::ViewGrid::rectangle): where every corner of a box lies
// in front of the eye it projects only the four corners that hold the extremes, which must give exactly the
// rectangle that projecting all eight corners gives (the reference below, the method it replaced). Checked on
// random boxes either side of the view's centre, boxes straddling the axes, tiny and huge ones, and boxes
// reaching behind the eye (where the rectangle projects all eight).
#include <gtest/gtest.h>

#include <algorithm>
#include <limits>
#include <random>

#include <glm/glm.hpp>

#include "prep/ViewChords.h"

namespace spindrift {
namespace {

using view_chords::ViewGrid;

// The rectangle from all eight corners' projections, as ViewGrid::rectangle computed it until session 43.
void eightCorners(const ViewGrid& grid, const glm::vec3& centre, const glm::vec3& halfExtents,
                  glm::ivec2& low, glm::ivec2& high) {
  glm::vec2 least(std::numeric_limits<float>::max()), most(std::numeric_limits<float>::lowest());
  for (int corner = 0; corner < 8; ++corner) {
    const glm::vec3 point =
        centre + halfExtents * glm::vec3(corner & 1 ? 1.0f : -1.0f, corner & 2 ? 1.0f : -1.0f,
                                         corner & 4 ? 1.0f : -1.0f);
    const glm::vec2 pixel = grid.pixelOf(point);
    least = glm::min(least, pixel);
    most = glm::max(most, pixel);
  }
  const glm::vec2 outside(-2.0f), beyond(float(grid.width) + 2.0f, float(grid.height) + 2.0f);
  least = glm::clamp(least, outside, beyond);
  most = glm::clamp(most, outside, beyond);
  low = glm::max(glm::ivec2(glm::floor(least - 0.5f)) - 1, glm::ivec2(0));
  high = glm::min(glm::ivec2(glm::ceil(most - 0.5f)) + 1, glm::ivec2(grid.width - 1, grid.height - 1));
}

TEST(ViewGrid, RectangleFromFourCornersIsTheEightCornersOne) {
  const ViewGrid grid(Camera::lookAt(480, 270, 40.0f, {0.0f, -5.0f, 2.0f}, {0.0f, 0.0f, 0.0f}, {0, 0, 1}));
  std::mt19937 random(23);
  std::uniform_real_distribution<float> across(-4.0f, 4.0f), depth(-12.0f, 0.5f), logSize(-4.0f, 0.5f);
  int compared = 0, behind = 0;
  for (int trial = 0; trial < 200000; ++trial) {
    glm::vec3 centre(across(random), across(random), depth(random));
    if (trial % 10 == 0) centre.x = 0.0f;  // straddling the view's axes
    if (trial % 10 == 1) centre.y = 0.0f;
    const glm::vec3 halfExtents(std::pow(10.0f, logSize(random)), std::pow(10.0f, logSize(random)),
                                std::pow(10.0f, logSize(random)));
    glm::ivec2 low, high, expectedLow, expectedHigh;
    grid.rectangle(centre, halfExtents, low, high);
    eightCorners(grid, centre, halfExtents, expectedLow, expectedHigh);
    ASSERT_EQ(low, expectedLow) << trial;
    ASSERT_EQ(high, expectedHigh) << trial;
    ++compared;
    behind += centre.z + halfExtents.z >= 0.0f;
  }
  EXPECT_GT(behind, 1000) << "boxes reaching behind the eye are compared too";
  EXPECT_EQ(compared, 200000);
}

}  // namespace
}  // namespace spindrift
