#version 450 core
// The background over each liquid pixel's footprint (docs/liquid.md, "The background's footprint").
// refraction.frag reads the background where one ray through the pixel's centre ends. Where the refraction
// shrinks the background (a ball's lens, a rim, a surface seen at a grazing angle) that is one texel of the
// many the pixel covers, and the image aliases; a path tracer averages them through its pixel filter. This pass
// averages the background over the parallelogram the pixel's neighbours' lookups span, and recombines the
// liquid from the refraction's split: liquid = reflection + transmittance * background(footprint).
//
// The background has been through the render's pixel filter already, in its own texels, so the footprint adds
// only the spread it lacks: along each axis a box of pixelFilterWidth pixels scaled by sqrt(length^2 - 1)
// (length in texels per pixel), which is nothing where the refraction does not shrink the background. Each
// axis is the shorter of the differences to the two neighbours along it, as a slope limiter takes it: across
// a discontinuity (an edge between two refracting facets, a neighbour whose ray met another solid) one of the
// two differences is the step and the other the surface's own slope.
#include "lib/frame.glsl"

// u, v (0..1, bottom left); 1 where the ray reads the background; 1 where that texel only stands in for an end
// hidden behind a solid (refraction.frag), which has no footprint on the screen.
layout(binding = 0) uniform sampler2D refractionUv;
layout(binding = 1) uniform sampler2D transmittance;  // of that background colour, to the eye
layout(binding = 2) uniform sampler2D reflection;     // every other light of the pixel
layout(binding = 3) uniform sampler2D surfaceClass;   // 1 where the first surface is a splash
layout(binding = 4) uniform sampler2D backgroundColor;
layout(binding = 5) uniform sampler2D backgroundEyeDepth;

uniform float pixelFilterWidth;  // the render's pixel filter as a box, in pixels

layout(location = 0) out vec4 outLiquid;
layout(location = 1) out vec4 outSplash;

const float kFootprintBreak = 16.0;  // texels between neighbours' lookups past which they read apart surfaces
const int kTapsPerAxis = 8;          // at most, a tap per texel of the footprint's extent

// Where the pixel's final ray reads the background, in texels; x < 0 where it reads none or a stand-in.
vec2 lookupAt(ivec2 pixel) {
  vec4 uv = texelAt(refractionUv, clamp(pixel, ivec2(0), ivec2(frame.viewportSize.xy) - 1));
  return uv.z > 0.5 && uv.w < 0.5 ? uv.xy * frame.viewportSize.xy : vec2(-1.0);
}

// One axis of the footprint: the shorter of the steps to the two neighbours along it, where both read the
// background and step the same way (within 90 degrees). Elsewhere the pixel lies at a fold of the lookups or
// at the edge of those that read the background, and no footprint is taken along the axis.
vec2 footprintAxis(vec2 centre, vec2 before, vec2 after) {
  if (before.x < 0.0 || after.x < 0.0) return vec2(0.0);
  vec2 stepBefore = centre - before, stepAfter = after - centre;
  if (dot(stepBefore, stepAfter) <= 0.0) return vec2(0.0);
  vec2 step = dot(stepBefore, stepBefore) < dot(stepAfter, stepAfter) ? stepBefore : stepAfter;
  float extent = length(step);
  if (extent <= 1.0 || extent > kFootprintBreak) return vec2(0.0);
  return step * (pixelFilterWidth * sqrt(extent * extent - 1.0) / extent);
}

void main() {
  ivec2 pixel = ivec2(gl_FragCoord.xy);
  vec2 centre = lookupAt(pixel);
  if (centre.x < 0.0) discard;
  vec2 alongX = footprintAxis(centre, lookupAt(pixel - ivec2(1, 0)), lookupAt(pixel + ivec2(1, 0)));
  vec2 alongY = footprintAxis(centre, lookupAt(pixel - ivec2(0, 1)), lookupAt(pixel + ivec2(0, 1)));
  // Nothing to add: refraction.frag's lookup at the centre stands.
  if (alongX == vec2(0.0) && alongY == vec2(0.0)) discard;
  int tapsX = int(clamp(ceil(length(alongX)), 1.0, float(kTapsPerAxis)));
  int tapsY = int(clamp(ceil(length(alongY)), 1.0, float(kTapsPerAxis)));
  // The taps read the surface the centre's ray met, not a solid beside it on the screen (bilinearOnSurface).
  float depth = texelAt(backgroundEyeDepth, ivec2(centre)).r;
  vec3 sum = vec3(0.0);
  for (int y = 0; y < tapsY; ++y)
    for (int x = 0; x < tapsX; ++x) {
      vec2 offset = (vec2(x, y) + 0.5) / vec2(tapsX, tapsY) - 0.5;
      vec2 tap = clamp(centre + offset.x * alongX + offset.y * alongY, vec2(0.0), frame.viewportSize.xy - 1.0);
      sum += bilinearOnSurface(backgroundColor, backgroundEyeDepth, tap, depth).rgb;
    }
  vec3 background = sum / float(tapsX * tapsY);
  outLiquid = vec4(texelAt(reflection, pixel).rgb + texelAt(transmittance, pixel).rgb * background, 1.0);
  outSplash = texelAt(surfaceClass, pixel).r == 1.0 ? outLiquid : vec4(0.0);
}
