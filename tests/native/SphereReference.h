#pragma once

#include <cmath>
#include <optional>

#include <glm/glm.hpp>

#include "spindrift/Camera.h"

// The analytic reference for ray-cast spheres, in double precision: where the ray through a pixel centre
// meets a sphere, independent of the renderer's shaders.
struct SphereHit {
  double eyeDepth;
  glm::dvec3 worldNormal;
  double discriminantOverRadiusSquared;  // Near 0 at the silhouette, where coverage is ambiguous.
};

inline std::optional<SphereHit> raySphere(const spindrift::Camera& camera, int column, int row,
                                          const glm::dvec3& worldCentre, double radius) {
  const double tanHalfY = std::tan(glm::radians(double(camera.fovYDegrees)) * 0.5);
  const double tanHalfX = tanHalfY * double(camera.width) / double(camera.height);
  const double ndcX = (column + 0.5) / camera.width * 2.0 - 1.0;
  const double ndcY = 1.0 - (row + 0.5) / camera.height * 2.0;
  // A ray with z = -1, so its parameter at the hit is the planar eye depth.
  const glm::dvec3 ray(ndcX * tanHalfX, ndcY * tanHalfY, -1.0);
  const glm::dmat4 cameraFromWorld = glm::inverse(glm::dmat4(camera.worldFromCamera));
  const glm::dvec3 centre = glm::dvec3(cameraFromWorld * glm::dvec4(worldCentre, 1.0));
  const double a = glm::dot(ray, ray), b = glm::dot(ray, centre),
               c = glm::dot(centre, centre) - radius * radius;
  const double discriminant = b * b - a * c;
  if (discriminant < 0.0) return std::nullopt;
  const double depth = (b - std::sqrt(discriminant)) / a;
  const glm::dvec3 normal = (ray * depth - centre) / radius;
  return SphereHit{depth, glm::normalize(glm::dmat3(camera.worldFromCamera) * normal),
                   discriminant / (a * radius * radius)};
}
