#include "prep/DomainClipOrder.h"

#include <algorithm>

#include <glm/matrix.hpp>

namespace spindrift {
namespace {

// Whether an ellipsoid's bounding sphere reaches a face of the box (or lies outside it). The sphere is
// mapped into the box's frame with its radius grown by the frame's largest scale, and kept away from the
// faces by a relative margin that covers the shader's rounding.
bool reachesBox(const EllipsoidInstance& ellipsoid, const DomainBox& domain, const glm::mat4& boxFromWorld,
                float radiusScale) {
  const glm::vec3 centre =
      glm::vec3(boxFromWorld * glm::vec4(glm::vec3(ellipsoid.centreAndBoundingRadius), 1.0f));
  const float margin = 1e-4f * std::max(glm::length(domain.high - domain.low), 1e-6f);
  const float radius = ellipsoid.centreAndBoundingRadius.w * radiusScale + margin;
  return glm::any(glm::lessThan(centre - radius, domain.low)) ||
         glm::any(glm::greaterThan(centre + radius, domain.high));
}

// Adds a draw unless it is empty.
void addDraw(std::vector<ImpostorDraw>& draws, int first, int count, bool clip) {
  if (count > 0) draws.push_back({first, count, clip});
}

}  // namespace

ImpostorDraws unclippedDraws(std::size_t count, const LayerSplit& split) {
  ImpostorDraws draws;
  addDraw(draws.front, 0, int(count - split.backOnly), false);
  addDraw(draws.back, int(split.frontOnly), int(count - split.frontOnly), false);
  return draws;
}

ImpostorDraws orderForDomainClip(std::vector<EllipsoidInstance>& ellipsoids, const LayerSplit& split,
                                 const DomainBox& domain) {
  const int all = int(ellipsoids.size());
  const int frontOnly = int(split.frontOnly), backOnly = int(split.backOnly);
  const int bothEnd = all - backOnly;  // the groups are [0, frontOnly), [frontOnly, bothEnd), [bothEnd, all)
  ImpostorDraws draws;
  const glm::mat4 boxFromWorld = glm::inverse(domain.worldFromBox);
  const glm::mat3 linear(boxFromWorld);
  const float radiusScale =
      std::max({glm::length(linear[0]), glm::length(linear[1]), glm::length(linear[2])});
  const auto clipped = [&](const EllipsoidInstance& ellipsoid) {
    return reachesBox(ellipsoid, domain, boxFromWorld, radiusScale);
  };
  const auto free = [&](const EllipsoidInstance& ellipsoid) { return !clipped(ellipsoid); };
  const auto begin = ellipsoids.begin();
  // Each group's split point: where its first part ends.
  const int frontClippedEnd = int(std::stable_partition(begin, begin + frontOnly, clipped) - begin);
  const int bothFreeEnd = int(std::stable_partition(begin + frontOnly, begin + bothEnd, free) - begin);
  const int backClippedEnd = int(std::stable_partition(begin + bothEnd, ellipsoids.end(), clipped) - begin);
  draws.clipped = frontClippedEnd + (bothEnd - bothFreeEnd) + (backClippedEnd - bothEnd);
  // Front: [front only, clipped] [front only, free + both, free] [both, clipped].
  addDraw(draws.front, 0, frontClippedEnd, true);
  addDraw(draws.front, frontClippedEnd, bothFreeEnd - frontClippedEnd, false);
  addDraw(draws.front, bothFreeEnd, bothEnd - bothFreeEnd, true);
  // Back: [both, free] [both, clipped + back only, clipped] [back only, free].
  addDraw(draws.back, frontOnly, bothFreeEnd - frontOnly, false);
  addDraw(draws.back, bothFreeEnd, backClippedEnd - bothFreeEnd, true);
  addDraw(draws.back, backClippedEnd, all - backClippedEnd, false);
  return draws;
}

}  // namespace spindrift
