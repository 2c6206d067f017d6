// The liquid pipeline against closed-form optics: GL tests on llvmpipe, references computed here.
#include <gtest/gtest.h>

#include "BackgroundFiles.h"
#include "LiquidTestScenes.h"
#include "OpticsReference.h"
#include "TempDirectory.h"

using namespace spindrift;
using namespace liquid_test;

namespace {

constexpr int kWidth = 160, kHeight = 120;
constexpr double kPlaneDepth = 8.0;

// The camera at the origin looking down -Z; a plane at eye depth 8 behind everything, coloured by its own
// coordinates (R from x, G from y), so a pixel's colour says where on the plane its ray landed.
Scene rampScene(const TempDirectory& directory) {
  Scene scene;
  scene.camera.width = kWidth;
  scene.camera.height = kHeight;
  scene.camera.fovYDegrees = 40.0f;
  scene.background.color = glm::vec3(0.0f);  // Rays that leave the screen see black.
  const Camera camera = scene.camera;
  auto planeColor = [camera](int column, int row) {
    const glm::vec3 world = camera.worldFromPixelAndDepth({column + 0.5f, row + 0.5f}, float(kPlaneDepth));
    return glm::vec3((world.x + 4.0f) / 8.0f, (world.y + 3.0f) / 6.0f, 0.25f);
  };
  scene.background.image = directory.path() / "plane.exr";
  writeBackgroundExr(scene.background.image, kWidth, kHeight, planeColor,
                     [](int, int) { return float(kPlaneDepth); });
  return scene;
}

// b(.) of the reference: where a ray meets the plane, if that is on screen; else black.
glm::dvec3 planeAlong(const Camera& camera, const optics::Ray& ray, glm::dvec2* planePoint = nullptr) {
  if (ray.direction.z >= 0.0) return glm::dvec3(0.0);
  const double t = (-kPlaneDepth - ray.origin.z) / ray.direction.z;
  if (t <= 0.0) return glm::dvec3(0.0);
  const glm::dvec3 hit = ray.origin + t * ray.direction;
  const glm::vec3 pixel = camera.pixelAndDepthFromWorld(glm::vec3(hit));
  if (pixel.x < 0 || pixel.y < 0 || pixel.x >= camera.width || pixel.y >= camera.height)
    return glm::dvec3(0.0);
  if (planePoint) *planePoint = glm::dvec2(hit);
  return glm::dvec3((hit.x + 4.0) / 8.0, (hit.y + 3.0) / 6.0, 0.25);
}

}  // namespace

// One water sphere in front of the plane, two refractions, against a closed-form ray trace of the sphere:
// the error of where the refracted ray lands on the plane, in pixels, and of the colour.
TEST(GLLiquidAccuracy, TwoRefractionsThroughASphereMatchTheClosedForm) {
  TempDirectory directory;
  Scene scene = rampScene(directory);
  scene.parameters.liquid.max_refractions = 2;
  scene.parameters.liquid.absorption = 0.0f;
  const glm::dvec3 centre(0.0, 0.0, -5.0);
  const double radius = 1.0, ior = scene.parameters.liquid.ior;
  const RenderResult result =
      renderer().renderParticles(scene, particlesOf({glm::vec3(centre)}, float(radius)), 1);
  expectAllChannelsFinite(result);
  const ImageLayer& liquid = *result.layer("liquid");

  double positionErrorSum = 0.0, colourErrorSum = 0.0, worstPositionError = 0.0;
  int compared = 0;
  const double planePixelSize = 2.0 * std::tan(glm::radians(20.0)) * kPlaneDepth / kHeight;
  for (int row = 0; row < kHeight; ++row)
    for (int column = 0; column < kWidth; ++column) {
      const glm::dvec3 through =
          glm::dvec3(scene.camera.worldFromPixelAndDepth({column + 0.5f, row + 0.5f}, 1.0f));
      const optics::Ray view{glm::dvec3(0.0), glm::normalize(through)};
      const auto entry = optics::sphereRoots(view, centre, radius);
      // Skip the silhouette's outer ring, where a pixel's footprint straddles the edge.
      if (!entry || entry->second - entry->first < 0.35 * radius) continue;
      const glm::dvec3 p1 = view.direction * entry->first, n1 = (p1 - centre) / radius;
      const double f1 = optics::schlick(-glm::dot(view.direction, n1), ior);
      const glm::dvec3 t1 = *optics::refract(view.direction, n1, 1.0 / ior);
      const glm::dvec3 p2 = p1 + t1 * optics::sphereRoots({p1, t1}, centre, radius)->second;
      const glm::dvec3 n2 = (p2 - centre) / radius;
      const auto t2 = optics::refract(t1, -n2, ior);
      ASSERT_TRUE(t2) << "a sphere never reflects totally";
      const double f2 = optics::schlick(glm::dot(*t2, n2), ior);
      glm::dvec2 expectedPoint(0.0);
      const glm::dvec3 transmitted = planeAlong(scene.camera, {p2, *t2}, &expectedPoint);
      const glm::dvec3 reflected1 = planeAlong(scene.camera, {p1, optics::reflect(view.direction, n1)});
      const glm::dvec3 reflected2 = planeAlong(scene.camera, {p2, optics::reflect(t1, -n2)});
      const glm::dvec3 expected = f1 * reflected1 + (1 - f1) * (f2 * reflected2 + (1 - f2) * transmitted);
      const glm::dvec3 rendered(at(liquid, kWidth, column, row, 0), at(liquid, kWidth, column, row, 1),
                                at(liquid, kWidth, column, row, 2));
      if (transmitted == glm::dvec3(0.0)) continue;  // The refracted ray left the screen.
      // Undo the reflected terms to read the plane coordinates the renderer's transmitted ray landed on.
      const glm::dvec3 renderedTransmitted =
          (rendered - f1 * reflected1 - (1 - f1) * f2 * reflected2) / ((1 - f1) * (1 - f2));
      const glm::dvec2 renderedPoint(renderedTransmitted.r * 8.0 - 4.0, renderedTransmitted.g * 6.0 - 3.0);
      const double positionError = glm::length(renderedPoint - expectedPoint) / planePixelSize;
      positionErrorSum += positionError;
      worstPositionError = std::max(worstPositionError, positionError);
      colourErrorSum += (std::abs(rendered.r - expected.r) + std::abs(rendered.g - expected.g) +
                         std::abs(rendered.b - expected.b)) /
                        3.0;
      ++compared;
    }
  ASSERT_GT(compared, 1500);
  const double meanPositionError = positionErrorSum / compared, meanColourError = colourErrorSum / compared;
  RecordProperty("mean_position_error_px", std::to_string(meanPositionError));
  RecordProperty("mean_colour_error", std::to_string(meanColourError));
  std::printf(
      "sphere: %d pixels, refracted position error mean %.3f px (worst %.2f px), colour error mean %.4f\n",
      compared, meanPositionError, worstPositionError, meanColourError);
  EXPECT_LT(meanPositionError, 1.0);
  EXPECT_LT(meanColourError, 0.01);
}

// Beer-Lambert along the sphere's axis: the centre ray crosses the sphere straight (normal incidence), so the
// colour there is (1 - F0)^2 exp(-a c_a 2r) times the plane behind.
TEST(GLLiquidAccuracy, BeerLambertThroughTheSphereCentre) {
  TempDirectory directory;
  Scene scene = rampScene(directory);
  scene.parameters.liquid.max_refractions = 2;
  scene.parameters.liquid.absorption = 1.0f;
  scene.parameters.liquid.absorption_rgb = {0.2f, 0.5f, 1.5f};
  const double radius = 1.0, ior = scene.parameters.liquid.ior;
  // The sphere's centre on the ray through the middle of pixel (80, 60) exactly.
  const glm::vec3 centre = scene.camera.worldFromPixelAndDepth({80.5f, 60.5f}, 5.0f);
  const RenderResult result = renderer().renderParticles(scene, particlesOf({centre}, float(radius)), 1);
  expectAllChannelsFinite(result);
  const double f0 = optics::schlick(1.0, ior);
  const glm::dvec3 behind = planeAlong(scene.camera, {glm::dvec3(0.0), glm::normalize(glm::dvec3(centre))});
  for (int channel = 0; channel < 3; ++channel) {
    const double expected = (1 - f0) * (1 - f0) *
                            std::exp(-scene.parameters.liquid.absorption_rgb[channel] * 2.0 * radius) *
                            behind[channel];
    EXPECT_NEAR(at(*result.layer("liquid"), kWidth, 80, 60, channel), expected, 0.01 * expected + 2e-3)
        << "channel " << channel;
  }
  EXPECT_NEAR(at(*result.layer("thickness"), kWidth, 80, 60, 0), 2.0 * radius, 0.02 * radius);
}
