#pragma once

#include <cmath>
#include <optional>

#include <glm/glm.hpp>

// Closed-form optics in double precision for the liquid tests: ray-sphere intersections, Snell refraction,
// Schlick's Fresnel with the renderer's documented cosine convention, independent of the shaders.
namespace optics {

struct Ray {
  glm::dvec3 origin;
  glm::dvec3 direction;  // unit
};

// Both roots of a ray with a sphere, or nothing.
inline std::optional<std::pair<double, double>> sphereRoots(const Ray& ray, const glm::dvec3& centre,
                                                            double radius) {
  const glm::dvec3 offset = ray.origin - centre;
  const double b = glm::dot(offset, ray.direction);
  const glm::dvec3 closest = offset - b * ray.direction;
  const double halfChordSquared = radius * radius - glm::dot(closest, closest);
  if (halfChordSquared < 0.0) return std::nullopt;
  const double halfChord = std::sqrt(halfChordSquared);
  return std::make_pair(-b - halfChord, -b + halfChord);
}

// Snell's law for a unit direction and a unit normal facing the incoming ray; nothing on total internal
// reflection. `ratio` = n_from / n_to.
inline std::optional<glm::dvec3> refract(const glm::dvec3& direction, const glm::dvec3& facingNormal,
                                         double ratio) {
  const double cosine = -glm::dot(facingNormal, direction);
  const double k = 1.0 - ratio * ratio * (1.0 - cosine * cosine);
  if (k < 0.0) return std::nullopt;
  return ratio * direction + (ratio * cosine - std::sqrt(k)) * facingNormal;
}

inline glm::dvec3 reflect(const glm::dvec3& direction, const glm::dvec3& normal) {
  return direction - 2.0 * glm::dot(direction, normal) * normal;
}

// Schlick's approximation with the cosine taken on the air side of the interface.
inline double schlick(double airSideCosine, double ior) {
  const double f0 = std::pow((ior - 1.0) / (ior + 1.0), 2.0);
  return f0 + (1.0 - f0) * std::pow(1.0 - std::clamp(airSideCosine, 0.0, 1.0), 5.0);
}

}  // namespace optics
