#pragma once

#include <algorithm>
#include <cmath>
#include <deque>
#include <random>
#include <vector>

#include <glm/glm.hpp>

#include "spindrift/Camera.h"

// CPU references for the depth smoothing tests, in double precision: depth layers of analytic scenes as the
// sphere impostor pass would produce them (planar eye depth, 1e10 where empty; world normal and coverage).
struct CpuDepthLayer {
  int width = 0;
  int height = 0;
  std::vector<float> eyeDepth;  // top row first
  std::vector<float> normal;    // RGBA, top row first
  CpuDepthLayer(int w, int h)
      : width(w), height(h), eyeDepth(std::size_t(w) * h, 1e10f), normal(std::size_t(w) * h * 4, 0.0f) {}

  std::size_t index(int column, int row) const { return std::size_t(row) * width + column; }
  bool covered(int column, int row) const { return eyeDepth[index(column, row)] < 1e9f; }
  glm::dvec3 normalAt(int column, int row) const {
    const float* n = &normal[4 * index(column, row)];
    return {n[0], n[1], n[2]};
  }
  void set(int column, int row, double depth, const glm::dvec3& worldNormal) {
    eyeDepth[index(column, row)] = float(depth);
    float* n = &normal[4 * index(column, row)];
    n[0] = float(worldNormal.x), n[1] = float(worldNormal.y), n[2] = float(worldNormal.z), n[3] = 1.0f;
  }
};

// The camera-space ray through a pixel centre (column right, row down), scaled so that its z is -1.
inline glm::dvec3 cameraRayThroughPixel(const spindrift::Camera& camera, int column, int row) {
  const double tanHalfY = std::tan(glm::radians(double(camera.fovYDegrees)) * 0.5);
  const double tanHalfX = tanHalfY * double(camera.width) / double(camera.height);
  return {((column + 0.5) / camera.width * 2.0 - 1.0) * tanHalfX,
          (1.0 - (row + 0.5) / camera.height * 2.0) * tanHalfY, -1.0};
}

// A plane in world space: normal·x = offset, the normal facing the camera.
struct WorldPlane {
  glm::dvec3 normal;
  double offset;

  // Eye depth where the pixel's ray meets the plane, or a negative value when it does not (in front).
  double eyeDepthAt(const spindrift::Camera& camera, int column, int row) const {
    const glm::dmat4 worldFromCamera(camera.worldFromCamera);
    const glm::dvec3 origin(worldFromCamera[3]);
    const glm::dvec3 direction = glm::dmat3(worldFromCamera) * cameraRayThroughPixel(camera, column, row);
    const double along = glm::dot(normal, direction);
    if (std::abs(along) < 1e-12) return -1.0;
    return (offset - glm::dot(normal, origin)) / along;
  }
};

// A sheet of spheres of radius r whose centres lie on a plane, on a square grid of spacing `spacing` inside a
// disc, each jittered along and across the plane: a bumpy sampled plane. The sheet's front surface is close
// to `frontPlane()`, the centre plane moved r towards the camera.
struct BumpySheet {
  WorldPlane centrePlane;
  double radius;
  std::vector<glm::dvec3> centres;

  WorldPlane frontPlane() const { return {centrePlane.normal, centrePlane.offset + radius}; }
  WorldPlane backPlane() const { return {centrePlane.normal, centrePlane.offset - radius}; }
};

inline BumpySheet makeBumpySheet(const glm::dvec3& centre, const glm::dvec3& normal, double discRadius,
                                 double radius, double spacing, double jitter, unsigned seed) {
  BumpySheet sheet{{glm::normalize(normal), glm::dot(glm::normalize(normal), centre)}, radius, {}};
  const glm::dvec3 n = sheet.centrePlane.normal;
  const glm::dvec3 u =
      glm::normalize(glm::cross(n, std::abs(n.z) < 0.9 ? glm::dvec3(0, 0, 1) : glm::dvec3(1, 0, 0)));
  const glm::dvec3 v = glm::cross(n, u);
  std::mt19937 random(seed);
  std::uniform_real_distribution<double> offset(-jitter, jitter);
  const int steps = int(std::ceil(discRadius / spacing));
  for (int i = -steps; i <= steps; ++i)
    for (int j = -steps; j <= steps; ++j) {
      if (std::hypot(i * spacing, j * spacing) > discRadius) continue;
      sheet.centres.push_back(centre + u * (i * spacing + offset(random)) +
                              v * (j * spacing + offset(random)) + n * offset(random));
    }
  return sheet;
}

// The front (nearest) or back (farthest) surface of a sheet's spheres per pixel, each sphere drawn over the
// pixels its projected bounding square covers.
inline CpuDepthLayer renderSheet(const BumpySheet& sheet, const spindrift::Camera& camera, bool backLayer) {
  CpuDepthLayer layer(camera.width, camera.height);
  const glm::dmat4 worldFromCamera(camera.worldFromCamera);
  const glm::dmat4 cameraFromWorld = glm::inverse(worldFromCamera);
  const double focalPixels = camera.height / (2.0 * std::tan(glm::radians(double(camera.fovYDegrees)) * 0.5));
  std::vector<double> best(layer.eyeDepth.size(), backLayer ? -1.0 : 1e300);
  for (const glm::dvec3& worldCentre : sheet.centres) {
    const glm::dvec3 c = glm::dvec3(cameraFromWorld * glm::dvec4(worldCentre, 1.0));
    if (-c.z <= 2.0 * sheet.radius) continue;
    const glm::vec3 projected = camera.pixelAndDepthFromWorld(glm::vec3(worldCentre));
    const int reach = int(std::ceil(2.0 * sheet.radius * focalPixels / (-c.z - sheet.radius))) + 2;
    for (int row = std::max(0, int(projected.y) - reach);
         row <= std::min(camera.height - 1, int(projected.y) + reach); ++row)
      for (int column = std::max(0, int(projected.x) - reach);
           column <= std::min(camera.width - 1, int(projected.x) + reach); ++column) {
        const glm::dvec3 ray = cameraRayThroughPixel(camera, column, row);
        const double a = glm::dot(ray, ray), b = glm::dot(ray, c),
                     cc = glm::dot(c, c) - sheet.radius * sheet.radius;
        const double discriminant = b * b - a * cc;
        if (discriminant < 0.0) continue;
        const double depth = (backLayer ? b + std::sqrt(discriminant) : b - std::sqrt(discriminant)) / a;
        double& kept = best[layer.index(column, row)];
        if (backLayer ? depth <= kept : depth >= kept) continue;
        kept = depth;
        layer.set(column, row, depth,
                  glm::normalize(glm::dmat3(worldFromCamera) * ((ray * depth - c) / sheet.radius)));
      }
  }
  return layer;
}

// A flat plane over every pixel whose ray meets it in front of the camera, nearer than `farthest`.
inline CpuDepthLayer renderPlane(const WorldPlane& plane, const spindrift::Camera& camera, double farthest) {
  CpuDepthLayer layer(camera.width, camera.height);
  for (int row = 0; row < camera.height; ++row)
    for (int column = 0; column < camera.width; ++column) {
      const double depth = plane.eyeDepthAt(camera, column, row);
      if (depth > 0.0 && depth < farthest) layer.set(column, row, depth, plane.normal);
    }
  return layer;
}

// Chessboard distance in pixels from each covered pixel to the nearest empty pixel or the image border.
inline std::vector<int> distanceToEdge(const CpuDepthLayer& layer) {
  std::vector<int> distance(layer.eyeDepth.size(), -1);
  std::deque<std::pair<int, int>> queue;
  for (int row = 0; row < layer.height; ++row)
    for (int column = 0; column < layer.width; ++column)
      if (!layer.covered(column, row) || row == 0 || column == 0 || row == layer.height - 1 ||
          column == layer.width - 1) {
        distance[layer.index(column, row)] = layer.covered(column, row) ? 1 : 0;
        queue.emplace_back(column, row);
      }
  while (!queue.empty()) {
    const auto [column, row] = queue.front();
    queue.pop_front();
    for (int dy = -1; dy <= 1; ++dy)
      for (int dx = -1; dx <= 1; ++dx) {
        const int x = column + dx, y = row + dy;
        if (x < 0 || y < 0 || x >= layer.width || y >= layer.height || distance[layer.index(x, y)] >= 0)
          continue;
        distance[layer.index(x, y)] = distance[layer.index(column, row)] + 1;
        queue.emplace_back(x, y);
      }
  }
  return distance;
}

// The value below which `fraction` of `values` lie.
inline double percentile(std::vector<double> values, double fraction) {
  if (values.empty()) return 0.0;
  const std::size_t at = std::min(values.size() - 1, std::size_t(fraction * double(values.size())));
  std::nth_element(values.begin(), values.begin() + std::ptrdiff_t(at), values.end());
  return values[at];
}
