#version 450 core
// One explicit Euler step of screen-space mean curvature flow (van der Laan, Green and Sainz, "Screen Space
// Fluid Rendering with Curvature Flow", I3D 2009): the mean curvature H of the surface that the depth map
// describes, from finite differences in pixels, moves each depth along the view axis.
#include "lib/frame.glsl"
#include "lib/depth_layer.glsl"

layout(binding = 0) uniform sampler2D sourceEyeDepth;

uniform float timeStep;  // diffusion number: liquid.curvature_flow_time_step

layout(location = 0) out float outEyeDepth;

void main() {
  ivec2 pixel = ivec2(gl_FragCoord.xy);
  float centreDepth = texelFetch(sourceEyeDepth, pixel, 0).r;
  outEyeDepth = kNoSurfaceDepth;
  if (!hasSurface(centreDepth)) return;
  outEyeDepth = centreDepth;

  // Depths relative to the centre: H is unchanged by scaling every depth, and values near 1 keep the
  // products below in float range from eye depth 1e-3 to 1e4.
  float neighbourhood[9];  // 3 × 3, row by row from (-1, -1)
  bool complete[9];
  for (int index = 0; index < 9; ++index) {
    float depth = layerDepthAt(sourceEyeDepth, pixel + ivec2(index % 3 - 1, index / 3 - 1));
    complete[index] = hasSurface(depth);
    neighbourhood[index] = depth / centreDepth;
  }
  float z = 1.0;
  // The paper's edge handling: derivatives that would reach a pixel without a surface are zero, so the
  // flow never pulls a silhouette towards the background.
  bool alongX = complete[3] && complete[5], alongY = complete[1] && complete[7];
  bool diagonal = complete[0] && complete[2] && complete[6] && complete[8];
  float zx = alongX ? 0.5 * (neighbourhood[5] - neighbourhood[3]) : 0.0;
  float zy = alongY ? 0.5 * (neighbourhood[7] - neighbourhood[1]) : 0.0;
  float zxx = alongX ? neighbourhood[5] + neighbourhood[3] - 2.0 * z : 0.0;
  float zyy = alongY ? neighbourhood[7] + neighbourhood[1] - 2.0 * z : 0.0;
  float zxy = diagonal ? 0.25 * (neighbourhood[8] + neighbourhood[0] - neighbourhood[2] - neighbourhood[6]) : 0.0;

  // C_x = 2 / (V_x F_x), with V the viewport size in pixels and F the projection's focal scale 1 / tan(fov/2).
  float cx = 2.0 * frame.tanHalfFov.x * frame.viewportSize.z;
  float cy = 2.0 * frame.tanHalfFov.y * frame.viewportSize.w;
  float d = cy * cy * zx * zx + cx * cx * zy * zy + cx * cx * cy * cy * z * z;
  float dx = 2.0 * (cy * cy * zx * zxx + cx * cx * zy * zxy + cx * cx * cy * cy * z * zx);
  float dy = 2.0 * (cy * cy * zx * zxy + cx * cx * zy * zyy + cx * cx * cy * cy * z * zy);
  float ex = 0.5 * zx * dx - zxx * d;
  float ey = 0.5 * zy * dy - zyy * d;
  float meanCurvature = (cy * ex + cx * ey) / (2.0 * d * sqrt(d));

  // At a flat extremum the flow is a diffusion with coefficient F_px / (2 z) for the focal length F_px in
  // pixels, so the step ε = λ · 2z / F_px makes λ the diffusion number (explicit Euler is stable for λ <= 1/4)
  // at every depth. With positive C_x, C_y and depths the flow towards the smoothed surface is -H.
  float focalLengthInPixels = frame.viewportSize.y / (2.0 * frame.tanHalfFov.y);
  float step = timeStep * 2.0 * z / focalLengthInPixels;
  float smoothed = centreDepth * (z - step * meanCurvature);
  if (hasSurface(smoothed) && !isinf(smoothed)) outEyeDepth = smoothed;
}
