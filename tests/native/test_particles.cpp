#include <gtest/gtest.h>

#include <string>

#include "spindrift/Particles.h"

namespace spindrift {
namespace {

TEST(Particles, AppendKeepsEveryArrayTheSameLength) {
  Particles particles;
  particles.append({1.0f, 2.0f, 3.0f}, 0.1f, ParticleKind::Foam, 5.0f, {0.0f, 0.0f, -1.0f});
  particles.append({4.0f, 5.0f, 6.0f}, 0.2f, ParticleKind::Liquid, 0.0f, {});
  ASSERT_EQ(particles.size(), 2u);
  EXPECT_EQ(particles.radii.size(), 2u);
  EXPECT_EQ(particles.kinds.size(), 2u);
  EXPECT_EQ(particles.life.size(), 2u);
  EXPECT_EQ(particles.velocities.size(), 2u);
  EXPECT_EQ(particles.positions[1], glm::vec3(4.0f, 5.0f, 6.0f));
  EXPECT_EQ(particles.kinds[0], ParticleKind::Foam);
  EXPECT_FLOAT_EQ(particles.life[0], 5.0f);
}

TEST(Particles, KindValuesAreMantaflowFlags) {
  // A Mantaflow `U` flag converts to a kind by a cast, so the enum values must be Mantaflow's.
  EXPECT_EQ(static_cast<int>(ParticleKind::Spray), 2);
  EXPECT_EQ(static_cast<int>(ParticleKind::Bubble), 4);
  EXPECT_EQ(static_cast<int>(ParticleKind::Foam), 8);
  EXPECT_EQ(std::string(particleKindName(ParticleKind::Liquid)), "liquid");
  EXPECT_EQ(std::string(particleKindName(ParticleKind::Spray)), "spray");
  EXPECT_EQ(std::string(particleKindName(ParticleKind::Bubble)), "bubble");
  EXPECT_EQ(std::string(particleKindName(ParticleKind::Foam)), "foam");
}

}  // namespace
}  // namespace spindrift
