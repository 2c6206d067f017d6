// The foam SSAO's samples kept inside the unit sphere (FoamOcclusionPass): named cases, and for every sample
// count of a random sequence, a loop over the kept points adds the same terms in the same order as a loop
// over the whole sequence that skips the points outside, as foam_occlusion.frag did before the points were
// kept apart.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include "passes/FoamOcclusionPass.h"

namespace spindrift {
namespace {

glm::vec4 pointWithLength(float length) {
  return {length, 0.0f, 0.0f, length};
}

TEST(FoamSamples, NoSamplesKeepNone) {
  const SamplesInsideSphere kept = samplesInsideUnitSphere({});
  EXPECT_TRUE(kept.inside.empty());
  ASSERT_EQ(kept.insideAmongFirst.size(), 1u);
  EXPECT_EQ(kept.insideAmongFirst[0], 0u);
}

TEST(FoamSamples, TheSphereItselfIsInsideAndItsCentreIsNot) {
  // Length 1 lies on the sphere (kept); length 0 is the centre, which has no direction (skipped), as are
  // lengths above 1; NaN is not above 1, so it is kept as the shader kept it.
  const std::vector<glm::vec4> cube = {pointWithLength(1.0f),
                                       pointWithLength(0.0f),
                                       pointWithLength(std::nextafter(1.0f, 2.0f)),
                                       pointWithLength(0.5f),
                                       pointWithLength(std::numeric_limits<float>::quiet_NaN()),
                                       pointWithLength(std::numeric_limits<float>::infinity())};
  const SamplesInsideSphere kept = samplesInsideUnitSphere(cube);
  ASSERT_EQ(kept.inside.size(), 3u);
  EXPECT_EQ(kept.inside[0].w, 1.0f);
  EXPECT_EQ(kept.inside[1].w, 0.5f);
  EXPECT_TRUE(std::isnan(kept.inside[2].w));
  EXPECT_EQ(kept.insideAmongFirst, (std::vector<std::uint32_t>{0, 1, 1, 1, 2, 3, 3}));
}

TEST(FoamSamples, EveryCountSumsTheSameTermsInTheSameOrder) {
  std::mt19937 random(7);
  std::uniform_real_distribution<float> coordinate(-1.0f, 1.0f);
  std::vector<glm::vec4> cube(1000);
  for (glm::vec4& point : cube) {
    const glm::vec3 position(coordinate(random), coordinate(random), coordinate(random));
    point = glm::vec4(position, glm::length(position));
  }
  const SamplesInsideSphere kept = samplesInsideUnitSphere(cube);
  ASSERT_EQ(kept.insideAmongFirst.size(), cube.size() + 1);
  // About half the cube lies in the sphere (its volume is pi / 6 of the cube's).
  EXPECT_NEAR(double(kept.inside.size()) / double(cube.size()), 3.14159265 / 6.0, 0.05);
  for (std::size_t count = 0; count <= cube.size(); ++count) {
    float skipping = 0.0f, overKept = 0.0f;
    for (std::size_t i = 0; i < count; ++i) {
      if (cube[i].w > 1.0f || cube[i].w == 0.0f) continue;
      skipping = skipping * 0.75f + cube[i].x * cube[i].w;  // order-sensitive on purpose
    }
    for (std::uint32_t i = 0; i < kept.insideAmongFirst[count]; ++i)
      overKept = overKept * 0.75f + kept.inside[i].x * kept.inside[i].w;
    ASSERT_EQ(skipping, overKept) << "after " << count << " samples";
  }
}

}  // namespace
}  // namespace spindrift
