// The foam paper's scalar functions as the shaders evaluate them (lib/foam_functions.glsl, run by a small
// compute shader on the GL thread) against the formulas computed here, and the CPU preparation of foam.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "TempDirectory.h"
#include "gl/GlThread.h"
#include "gl/ShaderLibrary.h"
#include "prep/FoamPreparation.h"

using namespace spindrift;

namespace {

// f(x, b, n, m) of equation 1.
double falloff(double x, double b, double n, double m) {
  const double ratio = x / b;
  if (ratio < 0.0 || ratio > 1.0) return 0.0;
  return std::pow(1.0 - std::pow(ratio, n), m);
}

// iota(rho, rho_mod, rho_exp) of section 2.3.
double sigmoid(double rho, double rhoMod, double rhoExp) {
  return std::pow(rho, rhoExp) / (rhoMod + std::pow(rho, rhoExp));
}

double radicalInverse(unsigned index, unsigned base) {
  double result = 0.0, weight = 1.0 / base;
  for (; index > 0; index /= base, weight /= base)
    result += weight * (index % base);
  return result;
}

// Evaluates each input row (x, b, n, m) as falloff, sigmoid (x, b, n unused) and Halton sample (index x) in a
// compute shader that includes the library's GLSL, and returns vec4(falloff, sigmoid, halton xy) and
// vec4(halton z, ...) per row.
const char* kEvaluator = R"(#version 450 core
#include "lib/foam_functions.glsl"
layout(local_size_x = 1) in;
layout(std430, binding = 0) readonly buffer Inputs { vec4 inputs[]; };
layout(std430, binding = 1) writeonly buffer Outputs { vec4 outputs[]; };
void main() {
  uint i = gl_GlobalInvocationID.x;
  vec4 row = inputs[i];
  vec3 halton = haltonCubeSample(uint(row.x));
  outputs[2u * i] = vec4(foamFalloff(row.x, row.y, row.z, row.w), foamIntensity(row.x, row.y, row.z), halton.xy);
  outputs[2u * i + 1u] = vec4(halton.z, 0.0, 0.0, 0.0);
}
)";

std::vector<float> evaluateOnGpu(const std::vector<float>& rows) {
  TempDirectory directory;
  std::filesystem::copy(findShaderDirectory() / "lib", directory.path() / "lib");
  directory.write("evaluate.comp", kEvaluator);
  GlThread thread;
  return thread.run([&] {
    const ShaderLibrary library(directory.path());
    const ProgramObject program = library.program({"evaluate.comp"});
    const std::size_t count = rows.size() / 4;
    BufferObject inputs = createBuffer(), outputs = createBuffer();
    glNamedBufferStorage(inputs.id(), GLsizeiptr(rows.size() * sizeof(float)), rows.data(), 0);
    glNamedBufferStorage(outputs.id(), GLsizeiptr(count * 8 * sizeof(float)), nullptr,
                         GL_DYNAMIC_STORAGE_BIT);
    glUseProgram(program.id());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, inputs.id());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, outputs.id());
    glDispatchCompute(GLuint(count), 1, 1);
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    std::vector<float> results(count * 8);
    glGetNamedBufferSubData(outputs.id(), 0, GLsizeiptr(results.size() * sizeof(float)), results.data());
    checkGlError("evaluating the foam functions");
    return results;
  });
}

}  // namespace

TEST(GLFoamFunctions, FalloffMatchesEquationOne) {
  // The paper's shapes (spray, surface foam, bubble before 1 - f, lifetime), another b, and x beyond b.
  const double shapes[][3] = {{1.0, 1.5, 1.0}, {1.0, 2.25, 1.0}, {1.0, 2.0, 1.0},
                              {1.0, 2.0, 0.4}, {0.3, 1.0, 2.0},  {2.5, 3.0, 0.5}};
  std::vector<float> rows;
  for (const auto& shape : shapes)
    for (double x = 0.0; x <= 1.2 * shape[0]; x += shape[0] / 20.0)
      rows.insert(rows.end(), {float(x), float(shape[0]), float(shape[1]), float(shape[2])});
  const std::vector<float> results = evaluateOnGpu(rows);
  for (std::size_t i = 0; i < rows.size() / 4; ++i) {
    const double expected = falloff(rows[4 * i], rows[4 * i + 1], rows[4 * i + 2], rows[4 * i + 3]);
    ASSERT_TRUE(std::isfinite(results[8 * i]));
    EXPECT_NEAR(results[8 * i], expected, 2e-6) << "f(" << rows[4 * i] << ", " << rows[4 * i + 1] << ", "
                                                << rows[4 * i + 2] << ", " << rows[4 * i + 3] << ")";
  }
}

TEST(GLFoamFunctions, SigmoidMatchesFormula) {
  std::vector<float> rows;
  for (double rhoMod : {3.0, 1.0, 5.0})
    for (double rhoExp : {1.25, 1.0, 2.0})
      for (double rho : {0.0, 0.01, 0.5, 1.0, 2.0, 4.0, 10.0, 100.0})
        rows.insert(rows.end(), {float(rho), float(rhoMod), float(rhoExp), 1.0f});
  const std::vector<float> results = evaluateOnGpu(rows);
  for (std::size_t i = 0; i < rows.size() / 4; ++i) {
    const double expected = sigmoid(rows[4 * i], rows[4 * i + 1], rows[4 * i + 2]);
    ASSERT_TRUE(std::isfinite(results[8 * i + 1]));
    EXPECT_NEAR(results[8 * i + 1], expected, 2e-6)
        << "iota(" << rows[4 * i] << ", " << rows[4 * i + 1] << ", " << rows[4 * i + 2] << ")";
  }
  // The paper's default iota(rho, 3, 1.25): one full particle gives 1/4.
  EXPECT_NEAR(sigmoid(1.0, 3.0, 1.25), 0.25, 1e-12);
}

TEST(GLFoamFunctions, HaltonSamplesAreRadicalInversesInBases235) {
  std::vector<float> rows;
  for (unsigned i = 0; i < 512; ++i)
    rows.insert(rows.end(), {float(i), 1.0f, 1.0f, 1.0f});
  const std::vector<float> results = evaluateOnGpu(rows);
  int insideSphere = 0;
  for (unsigned i = 0; i < 512; ++i) {
    const double expected[3] = {2 * radicalInverse(i + 1, 2) - 1, 2 * radicalInverse(i + 1, 3) - 1,
                                2 * radicalInverse(i + 1, 5) - 1};
    const float got[3] = {results[8 * i + 2], results[8 * i + 3], results[8 * i + 4]};
    for (int axis = 0; axis < 3; ++axis)
      EXPECT_NEAR(got[axis], expected[axis], 1e-6) << i << " " << axis;
    insideSphere += expected[0] * expected[0] + expected[1] * expected[1] + expected[2] * expected[2] <= 1.0;
  }
  // Low discrepancy: the share inside the unit sphere is close to its volume's share of the cube, pi / 6.
  EXPECT_NEAR(insideSphere / 512.0, M_PI / 6.0, 0.02);
}

TEST(FoamPreparation, RadiusPerTypeWithIrregularity) {
  const FoamParameters defaults;
  for (std::size_t i = 0; i < 12; ++i) {
    EXPECT_FLOAT_EQ(foamDrawnRadius(1.0f, ParticleKind::Foam, i, defaults), 1.0f / float(i % 5 + 1));
    EXPECT_FLOAT_EQ(foamDrawnRadius(1.0f, ParticleKind::Spray, i, defaults), 1.0f / float(i % 5 + 1));
    EXPECT_FLOAT_EQ(foamDrawnRadius(1.0f, ParticleKind::Bubble, i, defaults), 0.5f / float(i % 5 + 1));
  }
}

TEST(FoamPreparation, NormalisedAgeFromRemainingLife) {
  FoamParameters parameters;
  parameters.lifetime_frames = 16.0f;
  EXPECT_FLOAT_EQ(foamNormalisedAge(16.0f, parameters), 0.0f);
  EXPECT_FLOAT_EQ(foamNormalisedAge(4.0f, parameters), 0.75f);
  EXPECT_FLOAT_EQ(foamNormalisedAge(40.0f, parameters), 0.0f);
  EXPECT_FLOAT_EQ(foamNormalisedAge(0.0f, parameters), 0.0f);  // no life attribute: never fades
  parameters.lifetime_frames = 0.0f;
  EXPECT_FLOAT_EQ(foamNormalisedAge(4.0f, parameters), 0.0f);
}

TEST(FoamPreparation, CullsToTheViewAndCountsTypes) {
  const Camera camera = Camera::lookAt(64, 32, 40.0f, {0, 0, 5}, {0, 0, 0}, {0, 1, 0});
  Particles particles;
  particles.append({0, 0, 0}, 0.1f, ParticleKind::Liquid, 0.0f, glm::vec3(0));
  particles.append({0, 0, 0}, 0.1f, ParticleKind::Spray, 0.0f, glm::vec3(0));
  particles.append({0.5f, 0, 0}, 0.1f, ParticleKind::Bubble, 8.0f, glm::vec3(0));
  particles.append({0, 0.5f, 0}, 0.1f, ParticleKind::Foam, 0.0f, glm::vec3(0));
  particles.append({0, 0, 10}, 0.1f, ParticleKind::Foam, 0.0f, glm::vec3(0));   // behind the camera
  particles.append({50, 0, 0}, 0.1f, ParticleKind::Spray, 0.0f, glm::vec3(0));  // beside the view
  FoamParameters parameters;
  parameters.lifetime_frames = 16.0f;
  parameters.cull_sub_pixel = false;  // at 64 x 32 pixels these sprites are a pixel across or less
  const FoamPreparation foam = prepareFoam(particles, camera, parameters);
  EXPECT_EQ(foam.spray, 1u);
  EXPECT_EQ(foam.bubble, 1u);
  EXPECT_EQ(foam.surface, 1u);
  EXPECT_EQ(foam.culled, 2u);
  ASSERT_EQ(foam.instances.size(), 3u);
  // Foam indices count foam particles only: the bubble is the second, so its radius is 0.1 * 0.5 / 2.
  EXPECT_FLOAT_EQ(foam.instances[1].centreAndRadius.w, 0.025f);
  EXPECT_EQ(int(foam.instances[1].typeAndAge.x), int(FoamType::Bubble));
  EXPECT_FLOAT_EQ(foam.instances[1].typeAndAge.y, 0.5f);
}
