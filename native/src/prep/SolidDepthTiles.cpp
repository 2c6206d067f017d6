#include "prep/SolidDepthTiles.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <glm/glm.hpp>

namespace spindrift {
namespace {

constexpr float kInfinity = std::numeric_limits<float>::infinity();

}  // namespace

SolidDepthTiles::SolidDepthTiles(const Camera& camera)
    : camera_(camera),
      columns_((camera.width + kTileSize - 1) / kTileSize),
      rows_((camera.height + kTileSize - 1) / kTileSize),
      nearest_(std::size_t(columns_) * rows_, kInfinity) {}

void SolidDepthTiles::lower(float firstX, float firstY, float lastX, float lastY, float depth) {
  if (!(lastX >= 0.0f && lastY >= 0.0f && firstX < float(camera_.width) && firstY < float(camera_.height)))
    return;
  const int column0 = std::max(0, int(firstX) / kTileSize), row0 = std::max(0, int(firstY) / kTileSize);
  const int column1 = std::min(columns_ - 1, int(std::min(lastX, float(camera_.width - 1))) / kTileSize);
  const int row1 = std::min(rows_ - 1, int(std::min(lastY, float(camera_.height - 1))) / kTileSize);
  for (int row = row0; row <= row1; ++row)
    for (int column = column0; column <= column1; ++column) {
      float& tile = nearest_[std::size_t(row) * columns_ + column];
      tile = std::min(tile, depth);
    }
}

void SolidDepthTiles::addDepthImage(const FloatImage& eyeDepth) {
  // The farthest solids are kept where the image is the camera's size, as the impostor passes read it.
  const bool perPixel = eyeDepth.width == camera_.width && eyeDepth.height == camera_.height;
  if (perPixel) {
    farthest_.resize(std::size_t(eyeDepth.width) * eyeDepth.height);
    farthestTiles_.assign(nearest_.size(), 0.0f);
  }
  for (int y = 0; y < eyeDepth.height; ++y)
    for (int x = 0; x < eyeDepth.width; ++x) {
      const std::size_t pixel = std::size_t(y) * eyeDepth.width + x;
      const float depth = eyeDepth.pixels[pixel * eyeDepth.channels];
      // NaN counts as a solid at the camera: whatever the passes make of it, nothing is dropped there.
      if (!(depth >= kInfinity))
        lower(float(x), float(y), float(x), float(y), std::isnan(depth) ? 0.0f : depth);
      if (!perPixel) continue;
      farthest_[pixel] = depth > 0.0f ? depth : kNoSolid;  // NaN and infinity too
      float& tile = farthestTiles_[std::size_t(y / kTileSize) * columns_ + std::size_t(x / kTileSize)];
      tile = std::max(tile, farthest_[pixel]);
    }
}

void SolidDepthTiles::addTriangles(const TriangleMesh& mesh) {
  for (const glm::uvec3& triangle : mesh.triangles) {
    float nearest = kInfinity, firstX = kInfinity, firstY = kInfinity, lastX = -kInfinity, lastY = -kInfinity;
    bool crossesNearPlane = false;
    for (int k = 0; k < 3 && !crossesNearPlane; ++k) {
      const glm::vec3 pixel = camera_.pixelAndDepthFromWorld(mesh.vertices[triangle[k]]);
      crossesNearPlane = !(pixel.z > camera_.nearClip);
      nearest = std::min(nearest, pixel.z);
      firstX = std::min(firstX, pixel.x), lastX = std::max(lastX, pixel.x);
      firstY = std::min(firstY, pixel.y), lastY = std::max(lastY, pixel.y);
    }
    // A triangle that reaches behind the camera can cover any pixel: the whole frame is lowered to its
    // nearest possible depth, the near plane.
    if (crossesNearPlane)
      lower(0.0f, 0.0f, float(camera_.width), float(camera_.height), camera_.nearClip);
    else
      lower(std::floor(firstX) - 1.0f, std::floor(firstY) - 1.0f, lastX + 1.0f, lastY + 1.0f, nearest);
  }
}

bool SolidDepthTiles::tilesUnder(const glm::vec3& point, float radius, int& column0, int& row0, int& column1,
                                 int& row1) const {
  // Screen x and y are monotonic in each camera-space coordinate over the sphere's camera-space box (whose
  // depth is positive), so the box's corners bound the sphere's screen rectangle.
  float firstX = kInfinity, firstY = kInfinity, lastX = -kInfinity, lastY = -kInfinity;
  for (float z : {point.z - radius, point.z + radius})
    for (float x : {point.x - radius, point.x + radius})
      for (float y : {point.y - radius, point.y + radius}) {
        const glm::vec3 pixel = camera_.pixelAndDepthFromCamera({x, y, z});
        firstX = std::min(firstX, pixel.x), lastX = std::max(lastX, pixel.x);
        firstY = std::min(firstY, pixel.y), lastY = std::max(lastY, pixel.y);
      }
  if (!(lastX >= 0.0f && lastY >= 0.0f && firstX < float(camera_.width) && firstY < float(camera_.height)))
    return false;  // Off screen: it draws no pixel.
  column0 = std::max(0, int(firstX) / kTileSize), row0 = std::max(0, int(firstY) / kTileSize);
  column1 = std::min(columns_ - 1, int(std::min(lastX + 1.0f, float(camera_.width - 1))) / kTileSize);
  row1 = std::min(rows_ - 1, int(std::min(lastY + 1.0f, float(camera_.height - 1))) / kTileSize);
  return true;
}

bool SolidDepthTiles::solidNearerThan(const glm::vec3& centre, float radius, float farthestDepth) const {
  const glm::vec3 point = glm::vec3(camera_.cameraFromWorld() * glm::vec4(centre, 1.0f));
  int column0, row0, column1, row1;
  if (!tilesUnder(point, radius, column0, row0, column1, row1)) return false;
  for (int row = row0; row <= row1; ++row)
    for (int column = column0; column <= column1; ++column)
      if (nearest_[std::size_t(row) * columns_ + column] <= farthestDepth) return true;
  return false;
}

bool SolidDepthTiles::hidesSphere(const glm::vec3& cameraCentre, float radius) const {
  // The shaders compute a fragment's entry in float, in another order: a margin of 1e-4 of the depth.
  constexpr float kMargin = 1e-4f;
  const float nearest = -cameraCentre.z - radius;
  if (farthestTiles_.empty() || !(nearest > camera_.nearClip)) return false;
  const auto hiddenIn = [&](int column, int row) {
    return farthestTiles_[std::size_t(row) * columns_ + column] * (1.0f + kMargin) < nearest;
  };
  // Most spheres in view are not hidden, and the tile under the centre, one of those the sphere covers,
  // says so without the eight corners' projections.
  const glm::vec3 centre = camera_.pixelAndDepthFromCamera(cameraCentre);
  if (centre.x >= 0.0f && centre.y >= 0.0f && centre.x < float(camera_.width) &&
      centre.y < float(camera_.height) && !hiddenIn(int(centre.x) / kTileSize, int(centre.y) / kTileSize))
    return false;
  int column0, row0, column1, row1;
  if (!tilesUnder(cameraCentre, radius, column0, row0, column1, row1)) return false;
  for (int row = row0; row <= row1; ++row)
    for (int column = column0; column <= column1; ++column)
      if (!hiddenIn(column, row)) return false;
  return true;
}

}  // namespace spindrift
