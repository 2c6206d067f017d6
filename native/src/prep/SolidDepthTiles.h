#pragma once

#include <limits>
#include <vector>

#include <glm/vec3.hpp>

#include "spindrift/Camera.h"
#include "spindrift/FloatImage.h"
#include "spindrift/FrameInputs.h"

namespace spindrift {

/// A conservative picture of where the frame's solids are: for each tile of pixels, a planar eye depth that
/// no solid in the tile is nearer than (the background's depth image and the occluder triangles), and for
/// each pixel one that a solid is certainly at or nearer than (the background's depth image alone: the
/// occluders only bring the solids nearer). dropHiddenInterior keeps every ellipsoid that may reach behind a
/// solid, because the impostor passes hide particles by the solid depth pixel by pixel; the occlusion test
/// drops those the solids hide wholly.
class SolidDepthTiles {
 public:
  static constexpr int kTileSize = 8;
  static constexpr float kNoSolid = std::numeric_limits<float>::infinity();

  /// No solids: every tile and pixel is infinitely deep.
  explicit SolidDepthTiles(const Camera& camera);
  /// The background's depth image, the camera's size (the impostor passes read it texel by texel; where it
  /// is NaN or not positive there is no solid, as background.frag reads it).
  void addDepthImage(const FloatImage& eyeDepth);
  void addTriangles(const TriangleMesh& mesh);

  /// Whether a solid may lie nearer than `farthestDepth` within the screen rectangle of a world-space sphere
  /// (which must lie beyond the near plane).
  bool solidNearerThan(const glm::vec3& centre, float radius, float farthestDepth) const;
  /// The depth no solid is nearer than at a pixel (x right, y down, inside the frame): its tile's.
  float nearestAt(int x, int y) const {
    return nearest_[std::size_t(y / kTileSize) * std::size_t(columns_) + std::size_t(x / kTileSize)];
  }
  /// The depth a solid certainly lies at or nearer than at a pixel (y * width + x, x right, y down): infinite
  /// where there is none. Every fragment there whose entry lies at or beyond it is hidden.
  float farthestAt(std::size_t pixel) const { return farthest_.empty() ? kNoSolid : farthest_[pixel]; }
  /// Whether the background's depth hides a sphere (its centre in camera space) at every pixel it may cover:
  /// its nearest depth lies beyond each covered tile's farthest solid. Whatever lies inside it is then never
  /// drawn (the impostor passes discard a fragment whose entry lies at or behind the solid).
  bool hidesSphere(const glm::vec3& cameraCentre, float radius) const;

 private:
  // Lowers the tiles under a pixel rectangle (inclusive pixel coordinates, clamped to the frame) to `depth`.
  void lower(float firstX, float firstY, float lastX, float lastY, float depth);

  Camera camera_;
  int columns_ = 0;
  int rows_ = 0;
  std::vector<float> nearest_;
  std::vector<float> farthest_;       // per pixel; empty without a depth image
  std::vector<float> farthestTiles_;  // the largest of each tile's pixels
  // The tiles under the screen rectangle of a camera-space sphere in front of the eye (widened by a pixel),
  // clamped to the frame; false where it lies off the frame.
  bool tilesUnder(const glm::vec3& cameraCentre, float radius, int& column0, int& row0, int& column1,
                  int& row1) const;
};

}  // namespace spindrift
