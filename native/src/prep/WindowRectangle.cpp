#include "prep/WindowRectangle.h"

#include <algorithm>
#include <cmath>

#include <glm/common.hpp>
#include <glm/mat4x4.hpp>

namespace spindrift {

WindowRectangle windowRectangleOfSpheres(const std::vector<EllipsoidInstance>& ellipsoids,
                                         const Camera& view) {
  const WindowRectangle whole{0, 0, view.width, view.height};
  if (ellipsoids.empty()) return {};
  const glm::mat4 cameraFromWorld = view.cameraFromWorld();
  glm::vec3 low(INFINITY), high(-INFINITY);
  for (const EllipsoidInstance& ellipsoid : ellipsoids) {
    const glm::vec3 centre(cameraFromWorld * glm::vec4(glm::vec3(ellipsoid.centreAndBoundingRadius), 1.0f));
    const float radius = ellipsoid.centreAndBoundingRadius.w;
    // glm::min would pass over NaN, and what GL rasterises from a NaN vertex is undefined.
    if (!std::isfinite(centre.x + centre.y + centre.z + radius)) return whole;
    low = glm::min(low, centre - radius);
    high = glm::max(high, centre + radius);
  }
  // The box lies wholly in front of the near plane (the camera looks along -z), so it projects into the hull
  // of its corners' projections.
  if (!(high.z < -view.nearClip)) return whole;
  const glm::mat4 clipFromCamera = view.clipFromCamera();
  glm::vec2 windowLow(INFINITY), windowHigh(-INFINITY);
  for (int corner = 0; corner < 8; ++corner) {
    const glm::vec3 point((corner & 1) ? high.x : low.x, (corner & 2) ? high.y : low.y,
                          (corner & 4) ? high.z : low.z);
    const glm::vec4 clip = clipFromCamera * glm::vec4(point, 1.0f);
    const glm::vec2 window = (glm::vec2(clip) / clip.w * 0.5f + 0.5f) * glm::vec2(view.width, view.height);
    windowLow = glm::min(windowLow, window);
    windowHigh = glm::max(windowHigh, window);
  }
  if (!std::isfinite(windowLow.x + windowLow.y + windowHigh.x + windowHigh.y)) return whole;
  const int x0 = std::clamp(int(std::floor(windowLow.x)) - 1, 0, view.width);
  const int y0 = std::clamp(int(std::floor(windowLow.y)) - 1, 0, view.height);
  const int x1 = std::clamp(int(std::ceil(windowHigh.x)) + 1, 0, view.width);
  const int y1 = std::clamp(int(std::ceil(windowHigh.y)) + 1, 0, view.height);
  return {x0, y0, x1 - x0, y1 - y0};
}

}  // namespace spindrift
