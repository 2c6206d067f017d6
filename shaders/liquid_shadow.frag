#version 450 core
// The liquid's shadow on the background from one light (lib/liquid_shadow.glsl), at each background point
// rebuilt from the background's depth. Output, added up over the lights: (weight x shadow, weight), weight the
// light's irradiance at the point, and the diffuse direct light the light gives the point without the liquid.
// With one light whose caustics are on and the sky occlusion's samples, the lit background finds the shadow
// itself instead (lit_background.frag, SHADOW_IN_PLACE) and this pass does not run.
#include "lib/frame.glsl"
#include "lib/depth_layer.glsl"
#include "lib/optics.glsl"
#include "lib/light_view.glsl"
#include "lib/background_normal.glsl"

layout(binding = 0) uniform sampler2D backgroundEyeDepth;
layout(binding = 1) uniform sampler2D lightFrontDepth;
layout(binding = 2) uniform sampler2D lightBackDepth;
layout(binding = 3) uniform sampler2D lightFrontNormal;

#include "lib/light_column.glsl"

#ifdef TRANSMIT_STRAIGHT
uniform float indexOfRefraction;
uniform vec3 absorptionPerUnitLength;
#endif

#include "lib/liquid_shadow.glsl"

layout(location = 0) out vec4 outShadow;
layout(location = 1) out vec4 outLampDiffuse;  // irradiance x cos / pi x colour, added up

void main() {
  float eyeDepth = texelFetch(backgroundEyeDepth, ivec2(gl_FragCoord.xy), 0).r;
  outShadow = vec4(0.0);
  outLampDiffuse = vec4(0.0);
  if (eyeDepth >= kNoSurfaceDepth * 0.5) return;  // Nothing there to shadow.
  vec3 world = worldPositionFromFragCoord(gl_FragCoord.xy, eyeDepth);
  float weight = lightWeightAt(world);
  outLampDiffuse = vec4(lampDiffuseAt(world, backgroundNormal(backgroundEyeDepth, ivec2(gl_FragCoord.xy), eyeDepth)), 0.0);
  outShadow = vec4(weight * liquidShadowAt(world), weight);
}
