// orderForDomainClip (prep/DomainClipOrder): the impostor pass draws with the clip to a Mantaflow domain's
// box only the ellipsoids that reach its faces. Each layer must still draw exactly the ellipsoids LayerSplit
// gave it, every ellipsoid the box cuts or leaves out must be drawn with the clip, and only those.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <set>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>

#include "prep/DomainClipOrder.h"

namespace spindrift {
namespace {

// A sphere named by `name`, kept in inverseAxesRows[0].w (unused by the shaders), so a test can follow it
// through the reordering.
EllipsoidInstance sphere(const glm::vec3& centre, float radius, int name) {
  EllipsoidInstance ellipsoid{};
  ellipsoid.centreAndBoundingRadius = glm::vec4(centre, radius);
  for (int row = 0; row < 3; ++row)
    ellipsoid.inverseAxesRows[row][row] = 1.0f / radius;
  ellipsoid.inverseAxesRows[0].w = float(name);
  return ellipsoid;
}

int nameOf(const EllipsoidInstance& ellipsoid) {
  return int(ellipsoid.inverseAxesRows[0].w);
}

// The exact test: does the sphere leave the box's inside (in the box's frame)?
bool reachesTheBox(const EllipsoidInstance& ellipsoid, const DomainBox& box) {
  const glm::vec3 centre = glm::vec3(glm::inverse(box.worldFromBox) *
                                     glm::vec4(glm::vec3(ellipsoid.centreAndBoundingRadius), 1.0f));
  const float radius = ellipsoid.centreAndBoundingRadius.w;
  return glm::any(glm::lessThan(centre - radius, box.low)) ||
         glm::any(glm::greaterThan(centre + radius, box.high));
}

// The names of the ellipsoids a layer's draws cover, and of those drawn with the clip.
struct Covered {
  std::multiset<int> all, clipped;
};
Covered covered(const std::vector<EllipsoidInstance>& list, const std::vector<ImpostorDraw>& draws) {
  Covered result;
  for (const ImpostorDraw& draw : draws) {
    EXPECT_GT(draw.count, 0) << "an empty draw";
    for (int i = draw.first; i < draw.first + draw.count; ++i) {
      result.all.insert(nameOf(list[std::size_t(i)]));
      if (draw.clip) result.clipped.insert(nameOf(list[std::size_t(i)]));
    }
  }
  return result;
}

void checkOrder(const DomainBox& box, std::mt19937& random) {
  std::uniform_real_distribution<float> coordinate(-0.5f, 2.5f), size(0.01f, 0.4f);
  std::vector<EllipsoidInstance> list;
  for (int i = 0; i < 600; ++i)
    list.push_back(sphere({coordinate(random), coordinate(random), coordinate(random)}, size(random), i));
  const LayerSplit split{150, 170};
  const std::vector<EllipsoidInstance> original = list;
  std::multiset<int> wantFront, wantBack, wantClipped;
  for (std::size_t i = 0; i < original.size(); ++i) {
    const int name = nameOf(original[i]);
    if (i < original.size() - split.backOnly) wantFront.insert(name);
    if (i >= split.frontOnly) wantBack.insert(name);
    if (reachesTheBox(original[i], box)) wantClipped.insert(name);
  }

  const ImpostorDraws draws = orderForDomainClip(list, split, box);
  EXPECT_LE(draws.front.size(), 3u);
  EXPECT_LE(draws.back.size(), 3u);
  const Covered front = covered(list, draws.front), back = covered(list, draws.back);
  EXPECT_EQ(front.all, wantFront) << "the front layer draws other ellipsoids than LayerSplit gave it";
  EXPECT_EQ(back.all, wantBack) << "the back layer draws other ellipsoids than LayerSplit gave it";
  std::multiset<int> clipped = front.clipped;
  clipped.insert(back.clipped.begin(), back.clipped.end());
  for (int name : wantClipped)
    EXPECT_GT(clipped.count(name), 0u) << "an ellipsoid the box cuts is drawn without the clip";
  std::multiset<int> drawnAtAll = front.all;
  drawnAtAll.insert(back.all.begin(), back.all.end());
  std::size_t freeButClipped = 0;
  for (int name : std::set<int>(clipped.begin(), clipped.end()))
    freeButClipped += wantClipped.count(name) == 0;
  // The margin (1e-4 of the box's diagonal) may send a sphere that all but touches a face to the clip.
  EXPECT_LE(freeButClipped, 2u) << "ellipsoids well inside the box are drawn with the clip";
  int countClipped = 0;
  for (int name : wantClipped)
    countClipped += drawnAtAll.count(name) > 0;
  EXPECT_NEAR(draws.clipped, countClipped, 2);
  EXPECT_EQ(list.size(), original.size());
}

TEST(DomainClipOrder, EachLayerDrawsItsEllipsoidsAndOnlyThoseTheBoxCutsWithTheClip) {
  std::mt19937 random(7);
  checkOrder(DomainBox{glm::mat4(1.0f), glm::vec3(0.0f), glm::vec3(2.0f)}, random);
}

TEST(DomainClipOrder, ARotatedAndMovedBoxIsTestedInItsOwnFrame) {
  std::mt19937 random(11);
  const glm::mat4 worldFromBox = glm::rotate(glm::translate(glm::mat4(1.0f), glm::vec3(0.3f, -0.2f, 0.1f)),
                                             0.6f, glm::normalize(glm::vec3(1.0f, 2.0f, 3.0f)));
  checkOrder(DomainBox{worldFromBox, glm::vec3(0.0f), glm::vec3(2.0f)}, random);
}

TEST(DomainClipOrder, WithoutADomainEachLayerIsOneDrawOfItsRange) {
  const ImpostorDraws draws = unclippedDraws(100, LayerSplit{10, 20});
  ASSERT_EQ(draws.front.size(), 1u);
  ASSERT_EQ(draws.back.size(), 1u);
  EXPECT_EQ(draws.front[0].first, 0);
  EXPECT_EQ(draws.front[0].count, 80);
  EXPECT_EQ(draws.back[0].first, 10);
  EXPECT_EQ(draws.back[0].count, 90);
  EXPECT_FALSE(draws.front[0].clip || draws.back[0].clip);
  EXPECT_TRUE(unclippedDraws(0, LayerSplit{}).front.empty()) << "an empty list draws nothing";
}

}  // namespace
}  // namespace spindrift
