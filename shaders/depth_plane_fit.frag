#version 450 core
// One iteration of iterative local plane fitting (liquid paper 4.3, eqs. 1-5). Each pixel with a surface fits
// a plane to the camera-space positions of the neighbours in its s × s window (taps `tapSpacing` pixels apart)
// that have a surface, weighted by their eye-depth difference (eq. 2), with the weighted mean of the original
// normals as the plane's normal (eq. 3) through the weighted mean position (eq. 4), and moves to where its
// view ray meets that plane (eq. 5).
//
// Each tap's depth and original normal come from one RGBA32F texture (xyz the normal, w the depth) that
// depth_plane_fit_pack.frag or the round before wrote: one fetch a tap instead of two, which llvmpipe pays
// for per tap (PlaneFitPass). PACKED_OUTPUT writes the same for the next round; the last round writes the
// depth alone.
#include "lib/frame.glsl"
#include "lib/depth_layer.glsl"

layout(binding = 0) uniform sampler2D currentSurface;  // xyz: ñ_j in eq. 3; w: this iteration's depth, p_j

// (s - 1) / 2, a constant of each program (PlaneFitPass): llvmpipe unrolls the window's loops, which took the
// dam break's smoothing from 34-37 to 31-32.5 ms (docs/frame-cost.md, session 42).
const int halfWindow = HALF_WINDOW;
uniform int tapSpacing;  // pixels between taps: the window's taps spread over a taller image (PlaneFitPass.h)
uniform float sigma;     // world units: liquid.plane_fit_sigma × r

#if PACKED_OUTPUT
layout(location = 0) out vec4 outSurface;  // the pixel's original normal and its new depth
#else
layout(location = 0) out float outEyeDepth;
#endif

// Below this |n·v| the fitted plane is within about half a degree of containing the view ray, and the
// intersection of eq. 5 runs off towards infinity: the pixel keeps its depth instead.
const float kMinimumRayPlaneCosine = 1e-2;
// A normal sum shorter than this fraction of the weight sum means the neighbours' normals cancel out (e.g. the
// two sides of a thin sheet): there is no plane to fit.
const float kMinimumNormalAgreement = 1e-4;

// A pixel's original normal (xyz) and current depth (w); outside the image, no surface: the packed textures'
// border (PlaneFitPass), which took the test of every tap's position out of the window's 81 taps.
vec4 surfaceAt(ivec2 pixel) { return texelAt(currentSurface, pixel); }

// The centre pixel's depth after this iteration (its own where no plane can be fitted).
float smoothedDepth(ivec2 pixel, float centreDepth) {
  vec3 centrePosition = cameraPositionAtPixel(pixel, centreDepth);
  vec3 normalSum = vec3(0.0);  // Σ w_ij ñ_j in world space: turned into camera space once, after the sum
  vec3 offsetSum = vec3(0.0);  // Σ w_ij (p_j - p_i): eq. 4 relative to p_i, which keeps float precision
  float weightSum = 0.0;
  for (int dy = -halfWindow; dy <= halfWindow; ++dy)
    for (int dx = -halfWindow; dx <= halfWindow; ++dx) {
      ivec2 neighbour = pixel + ivec2(dx, dy) * tapSpacing;
      vec4 surface = surfaceAt(neighbour);
      float depth = surface.w;
      if (!hasSurface(depth)) continue;
      float depthDifference = (depth - centreDepth) / sigma;
      float weight = exp(-depthDifference * depthDifference);
      normalSum += weight * surface.xyz;
      offsetSum += weight * (cameraPositionAtPixel(neighbour, depth) - centrePosition);
      weightSum += weight;
    }

  // The centre pixel always counts with weight 1, so weightSum >= 1 unless the input held NaN; every test is
  // written so that NaN fails it and leaves the depth as it was.
  normalSum = mat3(frame.cameraFromWorld) * normalSum;
  float normalLength = length(normalSum);
  if (!(weightSum >= 1.0) || !(normalLength > kMinimumNormalAgreement * weightSum)) return centreDepth;
  vec3 planeNormal = normalSum / normalLength;
  vec3 ray = cameraRayFromFragCoord(vec2(pixel) + 0.5);  // z = -1: its parameter along the ray is eye depth
  float rayDotNormal = dot(planeNormal, ray);
  if (!(abs(rayDotNormal) > kMinimumRayPlaneCosine * length(ray))) return centreDepth;
  // Eq. 5 with d_i = n_i·p̄_i, written as the step from p_i = z_i·ray to the plane along the ray.
  float smoothed = centreDepth + dot(planeNormal, offsetSum / weightSum) / rayDotNormal;
  return hasSurface(smoothed) && !isinf(smoothed) ? smoothed : centreDepth;
}

void main() {
  ivec2 pixel = ivec2(gl_FragCoord.xy);
  vec4 centre = surfaceAt(pixel);
  // Smoothing never creates a surface: an empty pixel stays empty.
  float depth = hasSurface(centre.w) ? smoothedDepth(pixel, centre.w) : kNoSurfaceDepth;
#if PACKED_OUTPUT
  outSurface = vec4(centre.xyz, depth);
#else
  outEyeDepth = depth;
#endif
}
