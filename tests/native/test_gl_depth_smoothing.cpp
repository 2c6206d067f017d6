// GL tests of depth smoothing: they run on whatever EGL gives (Mesa's llvmpipe in CI) and fail, not skip,
// without OpenGL. Inputs are analytic depth layers made on the CPU (DepthLayerReference.h); results are
// compared with the analytic plane the spheres sample.
#include <gtest/gtest.h>

#include <iostream>
#include <memory>
#include <numeric>

#include "DepthLayerReference.h"
#include "Readback.h"
#include "gl/GlThread.h"
#include "gl/PassTimer.h"
#include "gl/ShaderLibrary.h"
#include "passes/DepthSmoothingPass.h"
#include "passes/FrameUniforms.h"
#include "passes/PlaneFitPass.h"

using namespace spindrift;

namespace {

const std::vector<std::string> kMethods = {"plane_fit", "bilateral", "curvature_flow", "narrow_range",
                                           "none"};

LiquidParameters withMethod(const std::string& method) {
  LiquidParameters parameters;
  parameters.smoothing = method;
  return parameters;
}

// The part of a frame pipeline that depth smoothing needs, on a GL thread of its own; one for the suite,
// since making contexts and compiling shaders is the slow part on llvmpipe.
class SmoothingHarness {
 public:
  static SmoothingHarness& instance() {
    static SmoothingHarness harness;
    return harness;
  }
  ~SmoothingHarness() {
    glThread_.run([this] { pipeline_.reset(); });
  }

  // Uploads `input`, smooths it and reads the result back; `gpuMilliseconds` receives the GPU time of the
  // DepthSmoothingPass run (smoothing and normals).
  CpuDepthLayer smooth(const CpuDepthLayer& input, const Camera& camera, double radius, bool backLayer,
                       const LiquidParameters& parameters, double* gpuMilliseconds = nullptr) {
    CpuDepthLayer output(input.width, input.height);
    glThread_.run([&] {
      Pipeline& pipeline = *pipeline_;
      pipeline.frameUniforms.update(camera);
      uploadTexture(pipeline.depth, GL_R32F, input.width, input.height, 1, input.eyeDepth.data(), false);
      uploadTexture(pipeline.normal, GL_RGBA16F, input.width, input.height, 4, input.normal.data(), false);
      pipeline.timer.begin("depth_smoothing");
      const DepthLayer smoothed =
          pipeline.smoothing.run({pipeline.depth, pipeline.normal}, float(radius), backLayer, parameters,
                                 nullptr, input.width, input.height);
      pipeline.timer.end();
      const std::vector<PassTiming> timings = pipeline.timer.collect();
      if (gpuMilliseconds) *gpuMilliseconds = timings.front().gpuMilliseconds;
      output.eyeDepth = readLayer(smoothed.eyeDepth, "depth", {"Z"}).pixels;
      output.normal = readLayer(smoothed.normal, "normal", {"X", "Y", "Z", "W"}).pixels;
    });
    return output;
  }

 private:
  struct Pipeline {
    ShaderLibrary shaders{findShaderDirectory()};
    FrameUniformBuffer frameUniforms;
    PassTimer timer;
    DepthSmoothingPass smoothing{shaders};
    Texture2D depth;
    Texture2D normal;
  };

  SmoothingHarness() {
    glThread_.run([this] { pipeline_ = std::make_unique<Pipeline>(); });
  }

  GlThread glThread_;
  std::unique_ptr<Pipeline> pipeline_;  // lives on glThread_
};

// The test scene: a disc of spheres (radius r, 3 to 4 pixels on screen) on a plane tilted 31 degrees away
// from facing the camera.
struct SheetScene {
  Camera camera;
  BumpySheet sheet;
};

SheetScene sheetScene(int width, int height, double scale = 1.0) {
  SheetScene scene;
  scene.camera =
      Camera::lookAt(width, height, 40.0f, glm::vec3(0.0, -5.0 * scale, 0.0), {0, 0, 0}, {0, 0, 1});
  scene.camera.nearClip = float(1e-3 * scale);
  scene.camera.farClip = float(1e3 * scale);
  const double radius = 0.06 * scale * 256.0 / width;
  scene.sheet =
      makeBumpySheet({0, 0, 0}, {0.0, -1.0, 0.6}, 1.3 * scale, radius, 0.7 * radius, 0.15 * radius, 7);
  return scene;
}

struct ErrorStatistics {
  double bias = 0.0;             // median signed error
  double medianDeviation = 0.0;  // median |error - bias|
  double deviation95 = 0.0;      // 95th percentile of |error - bias|
};

ErrorStatistics statisticsOf(const std::vector<double>& errors) {
  ErrorStatistics statistics;
  statistics.bias = percentile(errors, 0.5);
  std::vector<double> deviations;
  for (double error : errors)
    deviations.push_back(std::abs(error - statistics.bias));
  statistics.medianDeviation = percentile(deviations, 0.5);
  statistics.deviation95 = percentile(deviations, 0.95);
  return statistics;
}

std::ostream& operator<<(std::ostream& out, const ErrorStatistics& statistics) {
  return out << "bias " << statistics.bias << ", median " << statistics.medianDeviation
             << ", 95th percentile " << statistics.deviation95;
}

struct PlaneErrors {
  ErrorStatistics depthInRadii;  // signed: positive is farther from the camera than the plane
  double normalMedianDegrees = 0.0;
  double normal95Degrees = 0.0;
};

// Depth and normal errors against `plane` over pixels at least `margin` pixels inside the layer.
PlaneErrors planeErrors(const CpuDepthLayer& layer, const CpuDepthLayer& input, const Camera& camera,
                        const WorldPlane& plane, double radius, int margin) {
  const std::vector<int> inside = distanceToEdge(input);
  std::vector<double> depthErrors, angleErrors;
  for (int row = 0; row < layer.height; ++row)
    for (int column = 0; column < layer.width; ++column) {
      if (inside[layer.index(column, row)] < margin) continue;
      depthErrors.push_back(
          (layer.eyeDepth[layer.index(column, row)] - plane.eyeDepthAt(camera, column, row)) / radius);
      const double cosine = glm::dot(glm::normalize(layer.normalAt(column, row)), plane.normal);
      angleErrors.push_back(glm::degrees(std::acos(std::clamp(cosine, -1.0, 1.0))));
    }
  return {statisticsOf(depthErrors), percentile(angleErrors, 0.5), percentile(angleErrors, 0.95)};
}

// Mean signed depth change (output - input, in radii) over pixels within `band` pixels of the layer's edge;
// negative is towards the camera.
double meanSilhouetteDepthChange(const CpuDepthLayer& output, const CpuDepthLayer& input, double radius,
                                 int band) {
  const std::vector<int> inside = distanceToEdge(input);
  double sum = 0.0;
  int count = 0;
  for (std::size_t i = 0; i < input.eyeDepth.size(); ++i)
    if (inside[i] >= 1 && inside[i] <= band) {
      sum += (double(output.eyeDepth[i]) - double(input.eyeDepth[i])) / radius;
      ++count;
    }
  EXPECT_GT(count, 100);
  return sum / std::max(count, 1);
}

// Coverage is unchanged, depths and normals are finite, normals are unit length where covered and zero
// elsewhere.
void expectSameCoverageAndFinite(const CpuDepthLayer& output, const CpuDepthLayer& input) {
  int createdOrLost = 0, nonFinite = 0, badNormals = 0;
  for (int row = 0; row < input.height; ++row)
    for (int column = 0; column < input.width; ++column) {
      const std::size_t i = input.index(column, row);
      createdOrLost += output.covered(column, row) != input.covered(column, row);
      const float* normal = &output.normal[4 * i];
      nonFinite += !std::isfinite(output.eyeDepth[i]);
      for (int c = 0; c < 4; ++c)
        nonFinite += !std::isfinite(normal[c]);
      const double length = glm::length(output.normalAt(column, row));
      if (input.covered(column, row))
        badNormals += std::abs(length - 1.0) > 2e-3 || normal[3] != 1.0f;
      else
        badNormals += length != 0.0 || normal[3] != 0.0f;
    }
  EXPECT_EQ(createdOrLost, 0) << "pixels whose coverage changed";
  EXPECT_EQ(nonFinite, 0) << "non-finite depth or normal values";
  EXPECT_EQ(badNormals, 0) << "normals that are not unit length on the surface or zero off it";
}

}  // namespace

TEST(GLDepthSmoothing, PlaneFitReconstructsATiltedPlane) {
  const SheetScene scene = sheetScene(256, 192);
  const double radius = scene.sheet.radius;
  const CpuDepthLayer input = renderSheet(scene.sheet, scene.camera, false);
  const CpuDepthLayer output =
      SmoothingHarness::instance().smooth(input, scene.camera, radius, false, withMethod("plane_fit"));
  // 3 iterations of a 9 × 9 window reach 12 pixels; beyond that the edge plays no part.
  const int margin = 14;
  const PlaneErrors before =
      planeErrors(input, input, scene.camera, scene.sheet.frontPlane(), radius, margin);
  const PlaneErrors after =
      planeErrors(output, input, scene.camera, scene.sheet.frontPlane(), radius, margin);
  std::cout << "input depth error / r: " << before.depthInRadii << "\n"
            << "plane_fit depth error / r: " << after.depthInRadii << "\n"
            << "normal error (degrees), median and 95th percentile: input " << before.normalMedianDegrees
            << ", " << before.normal95Degrees << "; plane_fit " << after.normalMedianDegrees << ", "
            << after.normal95Degrees << "\n";
  // The spheres' tops lie on the front plane and the gaps between them behind it, so the smoothed surface
  // sits a fraction of a radius behind the plane; around that offset it must be far flatter than the input.
  EXPECT_GT(after.depthInRadii.bias, 0.0);
  EXPECT_LT(after.depthInRadii.bias, 0.25);
  EXPECT_LT(after.depthInRadii.medianDeviation, 0.02);
  EXPECT_LT(after.depthInRadii.deviation95, 0.06);
  EXPECT_LT(after.depthInRadii.deviation95, before.depthInRadii.deviation95 / 3.0);
  EXPECT_LT(after.normalMedianDegrees, 1.5);
  EXPECT_LT(after.normal95Degrees, 3.0);
  EXPECT_LT(after.normal95Degrees, before.normalMedianDegrees / 5.0);
}

// Rounds run in one pass hand each pixel's depth and original normal to the next round packed in one
// texture (PlaneFitPass); a pass of one round packs the layer and writes depth. n chained rounds must give
// what n passes of one round give, each fed the last one's depth and the original normals: 2 rounds (no
// middle round), 3 (the default) and 5.
TEST(GLDepthSmoothing, PlaneFitRoundsChainedMatchRoundsRunOneAtATime) {
  const SheetScene scene = sheetScene(160, 120);
  const double radius = scene.sheet.radius;
  const CpuDepthLayer input = renderSheet(scene.sheet, scene.camera, false);
  LiquidParameters oneRound = withMethod("plane_fit");
  oneRound.smoothing_iterations = 1;
  CpuDepthLayer stepped = input;
  for (int rounds = 1; rounds <= 5; ++rounds) {
    const CpuDepthLayer next =
        SmoothingHarness::instance().smooth(stepped, scene.camera, radius, false, oneRound);
    stepped.eyeDepth = next.eyeDepth;  // the normals stay the layer's originals
    if (rounds != 2 && rounds != 3 && rounds != 5) continue;
    LiquidParameters chained = withMethod("plane_fit");
    chained.smoothing_iterations = rounds;
    const CpuDepthLayer output =
        SmoothingHarness::instance().smooth(input, scene.camera, radius, false, chained);
    double largest = 0.0;
    int covered = 0;
    for (std::size_t i = 0; i < input.eyeDepth.size(); ++i) {
      ASSERT_EQ(input.covered(int(i % input.width), int(i / input.width)),
                output.covered(int(i % input.width), int(i / input.width)));
      if (!input.covered(int(i % input.width), int(i / input.width))) continue;
      ++covered;
      largest =
          std::max(largest, std::abs(double(output.eyeDepth[i]) - double(stepped.eyeDepth[i])) / radius);
    }
    EXPECT_GT(covered, 1000);
    EXPECT_LE(largest, 1e-4) << rounds << " rounds: the largest difference, in radii";
  }
}

// The same sheet rendered at twice the resolution covers twice the pixels per particle: a plane fit whose
// window is fixed in pixels spans half the sheet it spans in the preview and leaves the bumps in. With
// liquid.plane_fit_reference_height at the preview's height the taps spread two pixels apart, and the large
// frame is smoothed as the preview was.
TEST(GLDepthSmoothing, PlaneFitSmoothsAFrameAlikeAtTwiceItsResolution) {
  const SheetScene preview = sheetScene(256, 192);
  SheetScene large = preview;
  large.camera = Camera::lookAt(512, 384, 40.0f, glm::vec3(0.0, -5.0, 0.0), {0, 0, 0}, {0, 0, 1});
  large.camera.nearClip = preview.camera.nearClip;
  large.camera.farClip = preview.camera.farClip;
  const double radius = preview.sheet.radius;
  LiquidParameters atPreview = withMethod("plane_fit");
  atPreview.plane_fit_reference_height = 192;
  LiquidParameters inPixels = atPreview;
  inPixels.plane_fit_reference_height = 0;
  const auto errors = [&](const SheetScene& scene, const LiquidParameters& parameters, int margin) {
    const CpuDepthLayer input = renderSheet(scene.sheet, scene.camera, false);
    const CpuDepthLayer output =
        SmoothingHarness::instance().smooth(input, scene.camera, radius, false, parameters);
    expectSameCoverageAndFinite(output, input);
    return planeErrors(output, input, scene.camera, scene.sheet.frontPlane(), radius, margin);
  };
  const PlaneErrors small = errors(preview, atPreview, 14);
  const PlaneErrors spread = errors(large, atPreview, 28), fixed = errors(large, inPixels, 28);
  std::cout << "normal error (degrees), median and 95th percentile: 256x192 " << small.normalMedianDegrees
            << ", " << small.normal95Degrees << "; 512x384, taps 2 px apart " << spread.normalMedianDegrees
            << ", " << spread.normal95Degrees << "; 512x384, window in pixels " << fixed.normalMedianDegrees
            << ", " << fixed.normal95Degrees << "\n"
            << "depth error / r: " << small.depthInRadii << "; " << spread.depthInRadii << "; "
            << fixed.depthInRadii << "\n";
  // Measured: normals 0.38 / 0.85 degrees in the preview, 0.48 / 1.13 spread, 1.26 / 2.81 in pixels.
  EXPECT_LT(spread.normal95Degrees, 1.5 * small.normal95Degrees);
  EXPECT_LT(spread.normal95Degrees, 0.5 * fixed.normal95Degrees);
  EXPECT_LT(spread.depthInRadii.deviation95, 1.2 * small.depthInRadii.deviation95);
  EXPECT_LT(spread.depthInRadii.deviation95, 0.7 * fixed.depthInRadii.deviation95);
}

TEST(PlaneFitTapSpacing, IsTheImageHeightOverTheReferenceRoundedAndAtLeastOne) {
  LiquidParameters parameters;
  EXPECT_EQ(planeFitTapSpacing(2160, parameters), 1) << "off by default";
  parameters.plane_fit_reference_height = 270;
  EXPECT_EQ(planeFitTapSpacing(270, parameters), 1);
  EXPECT_EQ(planeFitTapSpacing(200, parameters), 1);
  EXPECT_EQ(planeFitTapSpacing(540, parameters), 2);
  EXPECT_EQ(planeFitTapSpacing(1080, parameters), 4);
  EXPECT_EQ(planeFitTapSpacing(2160, parameters), 8);
  EXPECT_EQ(planeFitTapSpacing(405, parameters), 2);  // 1.5 rounds up
  EXPECT_EQ(planeFitTapSpacing(0, parameters), 1);
  parameters.plane_fit_reference_height = 0;
  EXPECT_EQ(planeFitTapSpacing(2160, parameters), 1);
}

// Every method flattens the bumps of the sampled plane (curvature flow's sign, the filters' weights),
// measured like the plane-fit test; `none` leaves them.
TEST(GLDepthSmoothing, EveryMethodFlattensTheBumps) {
  const SheetScene scene = sheetScene(512, 384);
  const double radius = scene.sheet.radius;
  const CpuDepthLayer input = renderSheet(scene.sheet, scene.camera, false);
  const int kMargin = 60;
  const double bumps = planeErrors(input, input, scene.camera, scene.sheet.frontPlane(), radius, kMargin)
                           .depthInRadii.deviation95;
  for (const std::string& method : kMethods) {
    const CpuDepthLayer output =
        SmoothingHarness::instance().smooth(input, scene.camera, radius, false, withMethod(method));
    const PlaneErrors errors =
        planeErrors(output, input, scene.camera, scene.sheet.frontPlane(), radius, kMargin);
    std::cout << method << " depth error / r: " << errors.depthInRadii << "; normal error (degrees) median "
              << errors.normalMedianDegrees << ", 95th percentile " << errors.normal95Degrees << "\n";
    if (method == "none")
      EXPECT_EQ(errors.depthInRadii.deviation95, bumps);
    else
      EXPECT_LT(errors.depthInRadii.deviation95, bumps / 2.0) << method;
  }
}

// The liquid paper's Problem 2 (its Figure 3): a filter averages only the inner side of a silhouette, whose
// depths are nearer than the edge's, so the edge warps towards the camera and a round body looks flattened.
// Measured on a smooth round body (one sphere of 17 particle radii, the exact depth to keep) as the mean
// signed depth change within 3 pixels of its silhouette.
double silhouetteDepthChange(const std::string& method) {
  const SheetScene scene = sheetScene(256, 192);
  const double particleRadius = scene.sheet.radius;
  const BumpySheet body{{{0, -1, 0}, 0.0}, 17.0 * particleRadius, {{0.0, 0.0, 0.0}}};
  const CpuDepthLayer input = renderSheet(body, scene.camera, false);
  const CpuDepthLayer output =
      SmoothingHarness::instance().smooth(input, scene.camera, particleRadius, false, withMethod(method));
  const double change = meanSilhouetteDepthChange(output, input, particleRadius, 3);
  std::cout << method << ": mean depth change within 3 px of the silhouette: " << change << " r\n";
  return change;
}

// Plane fitting does not pull the silhouette forward. It moves it back a little (about half a radius): the
// plane through a convex patch's weighted centroid lies just inside the surface, and near the silhouette the
// ray meets it at a grazing angle, which stretches that small offset along the ray.
TEST(GLDepthSmoothing, PlaneFitDoesNotWarpSilhouettes) {
  const double change = silhouetteDepthChange("plane_fit");
  EXPECT_GT(change, -0.1);
  EXPECT_LT(change, 1.0);
}

TEST(GLDepthSmoothing, BilateralWarpsSilhouettes) {
  EXPECT_LT(silhouetteDepthChange("bilateral"), -2.0);
}

TEST(GLDepthSmoothing, EveryMethodKeepsEmptyPixelsEmptyAndStaysFinite) {
  struct Case {
    std::string name;
    Camera camera;
    double radius;
    CpuDepthLayer layer;
  };
  std::vector<Case> cases;
  const SheetScene sheet = sheetScene(128, 96);
  cases.push_back(
      {"bumpy sheet", sheet.camera, sheet.sheet.radius, renderSheet(sheet.sheet, sheet.camera, false)});
  cases.push_back({"empty layer", sheet.camera, sheet.sheet.radius, CpuDepthLayer(128, 96)});
  CpuDepthLayer speck(128, 96);
  speck.set(40, 30, 5.0, {0.0, -1.0, 0.0});
  cases.push_back({"single pixel", sheet.camera, sheet.sheet.radius, speck});
  // The ground plane z = 0 seen from 5 cm above it: depth runs from 5 to 1000 within a few rows.
  Camera grazing = Camera::lookAt(128, 96, 40.0f, {0, -5, 0.05f}, {0, 0, 0}, {0, 0, 1});
  cases.push_back({"grazing plane", grazing, 0.05, renderPlane({{0, 0, 1}, 0.0}, grazing, 999.0)});
  for (double scale : {1e-3 / 5.0, 1e4 / 5.0}) {
    const SheetScene scaled = sheetScene(128, 96, scale);
    cases.push_back({"sheet at depth " + std::to_string(5.0 * scale), scaled.camera, scaled.sheet.radius,
                     renderSheet(scaled.sheet, scaled.camera, false)});
  }
  for (const Case& test : cases)
    for (const std::string& method : kMethods)
      for (bool backLayer : {false, true}) {
        SCOPED_TRACE(test.name + ", " + method + (backLayer ? ", back layer" : ", front layer"));
        const CpuDepthLayer output = SmoothingHarness::instance().smooth(test.layer, test.camera, test.radius,
                                                                         backLayer, withMethod(method));
        expectSameCoverageAndFinite(output, test.layer);
      }
}

TEST(GLDepthSmoothing, FrontNormalsFaceTheCameraAndBackNormalsFaceAway) {
  const SheetScene scene = sheetScene(256, 192);
  const glm::dmat4 worldFromCamera(scene.camera.worldFromCamera);
  for (bool backLayer : {false, true}) {
    const CpuDepthLayer input = renderSheet(scene.sheet, scene.camera, backLayer);
    for (const std::string& method : kMethods) {
      SCOPED_TRACE(method + (backLayer ? ", back layer" : ", front layer"));
      const CpuDepthLayer output = SmoothingHarness::instance().smooth(
          input, scene.camera, scene.sheet.radius, backLayer, withMethod(method));
      int wrongWay = 0, covered = 0;
      for (int row = 0; row < input.height; ++row)
        for (int column = 0; column < input.width; ++column) {
          if (!input.covered(column, row)) continue;
          ++covered;
          const glm::dvec3 view =
              glm::dmat3(worldFromCamera) * cameraRayThroughPixel(scene.camera, column, row);
          const bool facesAway = glm::dot(output.normalAt(column, row), view) > 0.0;
          wrongWay += facesAway != backLayer;
        }
      EXPECT_GT(covered, 5000);
      EXPECT_EQ(wrongWay, 0);
    }
  }
}

// Not a check of correctness: prints each method's GPU time at 960 × 540 (smoothing plus the normals pass) so
// the numbers in docs/liquid.md can be reproduced. PassTimer brackets the pass with timestamp queries.
TEST(GLDepthSmoothing, ReportsGpuTimesAt960x540) {
  const SheetScene scene = sheetScene(960, 540);
  const CpuDepthLayer input = renderSheet(scene.sheet, scene.camera, false);
  SmoothingHarness& harness = SmoothingHarness::instance();
  LiquidParameters normalsOnly = withMethod("plane_fit");
  normalsOnly.smoothing_iterations = 0;
  std::vector<std::pair<std::string, LiquidParameters>> runs = {
      {"normals only (copy + normals)", normalsOnly}};
  for (const std::string& method : kMethods)
    runs.emplace_back(method, withMethod(method));
  for (const auto& [name, parameters] : runs) {
    double milliseconds = 0.0;
    harness.smooth(input, scene.camera, scene.sheet.radius, false,
                   parameters);  // warm-up: shader variants, caches
    harness.smooth(input, scene.camera, scene.sheet.radius, false, parameters, &milliseconds);
    std::cout << name << ": " << milliseconds << " ms GPU\n";
    ::testing::Test::RecordProperty(name, std::to_string(milliseconds));
    EXPECT_GT(milliseconds, 0.0) << name;
  }
}
