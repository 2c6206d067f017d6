#pragma once

#include <glm/mat4x4.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

namespace spindrift {

/// A pinhole camera with Blender's convention: it looks down its local -Z with +Y up, `worldFromCamera` is
/// exactly Blender's camera `matrix_world`, and `fovYDegrees` is the vertical field of view (Blender's
/// `angle_y` with `sensor_fit = 'VERTICAL'`). Depth is planar eye depth along the view axis, as in Blender's
/// Depth pass.
struct Camera {
  int width = 0;
  int height = 0;
  float fovYDegrees = 50.0f;
  float nearClip = 0.01f;
  float farClip = 1000.0f;
  glm::mat4 worldFromCamera{1.0f};

  static Camera lookAt(int width, int height, float fovYDegrees, const glm::vec3& position,
                       const glm::vec3& target, const glm::vec3& up);

  float aspect() const { return float(width) / float(height); }
  glm::mat4 cameraFromWorld() const;
  /// OpenGL clip space (-1..1 depth) from camera space.
  glm::mat4 clipFromCamera() const;
  glm::mat4 clipFromWorld() const { return clipFromCamera() * cameraFromWorld(); }
  glm::vec3 position() const { return glm::vec3(worldFromCamera[3]); }

  /// Pixel coordinates (x right, y down, pixel centres at +0.5) and planar eye depth of a world point.
  glm::vec3 pixelAndDepthFromWorld(const glm::vec3& world) const;
  /// The same for a point in camera space.
  glm::vec3 pixelAndDepthFromCamera(const glm::vec3& eye) const;
  /// The world size of a pixel's side at a planar eye depth.
  float pixelSizeAt(float eyeDepth) const;
  /// The world point seen at pixel coordinates (x right, y down) at a planar eye depth.
  glm::vec3 worldFromPixelAndDepth(const glm::vec2& pixel, float eyeDepth) const;
};

}  // namespace spindrift
