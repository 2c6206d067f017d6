#version 450 core
// Caustics, step 2: adds a triangle of refracted light to the background points it lands on (those whose depth
// matches the triangle's), weighted like the light's shadow (liquid_shadow.frag).
#include "lib/frame.glsl"
#include "lib/optics.glsl"
#include "lib/light_view.glsl"

layout(binding = 3) uniform sampler2D backgroundEyeDepth;

in vec3 gCarried;
in float gEyeDepth;
flat in float gConcentration;

layout(location = 0) out vec4 outCaustic;

void main() {
  float eyeDepth = texelFetch(backgroundEyeDepth, ivec2(gl_FragCoord.xy), 0).r;
  float pixelSize = 2.0 * frame.tanHalfFov.y * eyeDepth * frame.viewportSize.w;
  if (eyeDepth >= kNoSurfaceDepth * 0.5 || abs(gEyeDepth - eyeDepth) > 0.02 * eyeDepth + 3.0 * pixelSize) discard;
  vec3 world = worldPositionFromFragCoord(gl_FragCoord.xy, eyeDepth);
  outCaustic = vec4(lightWeightAt(world) * gCarried * gConcentration, 0.0);
}
