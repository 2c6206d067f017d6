#include "prep/ViewChords.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <glm/common.hpp>
#include <glm/geometric.hpp>

namespace spindrift::view_chords {

CameraEllipsoid cameraEllipsoid(const EllipsoidInstance& ellipsoid, const glm::dmat3& cameraFromWorld,
                                const glm::dvec3& centre) {
  CameraEllipsoid result;
  for (int k = 0; k < 3; ++k) {
    result.rows[k] = cameraFromWorld * glm::dvec3(glm::vec3(ellipsoid.inverseAxesRows[k]));
    result.scaledCentre[k] = glm::dot(result.rows[k], centre);
  }
  return result;
}

// Half the extent of an ellipsoid along each camera axis (the box about its centre that holds it): along a
// unit e it reaches |M^-T e|, and M^-T = M (M^T M)^-1 is M with each row divided by its squared length,
// the rows being orthogonal.
glm::dvec3 cameraHalfExtents(const CameraEllipsoid& ellipsoid) {
  glm::dvec3 squared(0.0);
  for (int k = 0; k < 3; ++k) {
    const glm::dvec3 axis = ellipsoid.rows[k] / glm::dot(ellipsoid.rows[k], ellipsoid.rows[k]);
    squared += axis * axis;
  }
  return glm::sqrt(squared);
}

ChordPolynomials::ChordPolynomials(const CameraEllipsoid& ellipsoid) {
  glm::dvec3 columns[3], crosses[3];
  for (int j = 0; j < 3; ++j) {
    columns[j] = glm::dvec3(ellipsoid.rows[0][j], ellipsoid.rows[1][j], ellipsoid.rows[2][j]);
    crosses[j] = glm::cross(ellipsoid.scaledCentre, columns[j]);
    along[j] = glm::dot(columns[j], ellipsoid.scaledCentre);
  }
  for (int j = 0; j < 3; ++j)
    for (int k = 0; k < 3; ++k) {
      lengths[j][k] = glm::dot(columns[j], columns[k]);
      crossed[j][k] = glm::dot(crosses[j], crosses[k]);
    }
}

ViewGrid::ViewGrid(const Camera& camera) : width(camera.width), height(camera.height) {
  focal = 1.0f / camera.pixelSizeAt(1.0f);
  columnU_.resize(std::size_t(std::max(width, 0)));
  rowV_.resize(std::size_t(std::max(height, 0)));
  for (int x = 0; x < width; ++x)
    columnU_[std::size_t(x)] = (x + 0.5 - 0.5 * width) / focal;
  for (int y = 0; y < height; ++y)
    rowV_[std::size_t(y)] = (0.5 * height - (y + 0.5)) / focal;
}

void ViewGrid::clipToBox(const DomainBox& domain, const glm::dmat4& boxFromCamera) {
  const std::size_t pixels = std::size_t(width) * std::size_t(height);
  boxEnter.assign(pixels, 0.0);
  boxLeave.assign(pixels, 0.0);
  const glm::dvec3 origin(boxFromCamera[3]), low(domain.low), high(domain.high);
  for (std::size_t pixel = 0; pixel < pixels; ++pixel) {
    const glm::dvec3 ray(columnU_[pixel % std::size_t(width)], v(int(pixel / std::size_t(width))), -1.0);
    const glm::dvec3 direction = glm::dmat3(boxFromCamera) * ray;
    double enter = -std::numeric_limits<double>::infinity(), leave = std::numeric_limits<double>::infinity();
    for (int axis = 0; axis < 3; ++axis) {
      if (direction[axis] == 0.0) {
        if (origin[axis] < low[axis] || origin[axis] > high[axis]) enter = leave = 0.0;  // misses the slab
        continue;
      }
      const double a = (low[axis] - origin[axis]) / direction[axis];
      const double b = (high[axis] - origin[axis]) / direction[axis];
      enter = std::max(enter, std::min(a, b));
      leave = std::min(leave, std::max(a, b));
    }
    boxEnter[pixel] = enter;
    boxLeave[pixel] = leave;
  }
}

glm::vec2 ViewGrid::pixelOf(const glm::vec3& point) const {
  return {0.5f * width + focal * point.x / -point.z, 0.5f * height - focal * point.y / -point.z};
}

void ViewGrid::rectangle(const glm::vec3& centre, const glm::vec3& halfExtents, glm::ivec2& low,
                         glm::ivec2& high) const {
  glm::vec2 least, most;
  const float nearZ = centre.z + halfExtents.z, farZ = centre.z - halfExtents.z;
  if (nearZ < 0.0f) {
    // Every corner in front of the eye: each extreme comes from a known corner, the same float values the
    // eight corners' projections give (their rounding is monotonic in x, y and -z). The window's x grows
    // with focal x / -z, which grows with x, and for x >= 0 falls as -z grows, for x < 0 rises.
    const float xLow = centre.x - halfExtents.x, xHigh = centre.x + halfExtents.x;
    const float yLow = centre.y - halfExtents.y, yHigh = centre.y + halfExtents.y;
    const auto nearer = [&](float along) { return focal * along >= 0.0f ? nearZ : farZ; };
    const auto farther = [&](float along) { return focal * along >= 0.0f ? farZ : nearZ; };
    least.x = pixelOf({xLow, 0.0f, farther(xLow)}).x;
    most.x = pixelOf({xHigh, 0.0f, nearer(xHigh)}).x;
    // The window's y falls as focal y / -z grows.
    least.y = pixelOf({0.0f, yHigh, nearer(yHigh)}).y;
    most.y = pixelOf({0.0f, yLow, farther(yLow)}).y;
  } else {
    least = glm::vec2(std::numeric_limits<float>::max());
    most = glm::vec2(std::numeric_limits<float>::lowest());
    for (int corner = 0; corner < 8; ++corner) {
      const glm::vec3 point =
          centre + halfExtents * glm::vec3(corner & 1 ? 1.0f : -1.0f, corner & 2 ? 1.0f : -1.0f,
                                           corner & 4 ? 1.0f : -1.0f);
      const glm::vec2 pixel = pixelOf(point);
      least = glm::min(least, pixel);
      most = glm::max(most, pixel);
    }
  }
  // Pixel centres at +0.5 inside [least, most], widened by one pixel for rounding; clamped to just outside
  // the frame first, so that a ball close to the eye plane cannot overflow the conversion to int.
  const glm::vec2 outside(-2.0f), beyond(float(width) + 2.0f, float(height) + 2.0f);
  least = glm::clamp(least, outside, beyond);
  most = glm::clamp(most, outside, beyond);
  low = glm::max(glm::ivec2(glm::floor(least - 0.5f)) - 1, glm::ivec2(0));
  high = glm::min(glm::ivec2(glm::ceil(most - 0.5f)) + 1, glm::ivec2(width - 1, height - 1));
}

}  // namespace spindrift::view_chords
