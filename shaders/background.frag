#version 450 core
// Resolves what lies behind the liquid at every pixel: the background image over the environment (or the
// flat colour where there is none), and the planar eye depth of the background's solids.
#include "lib/frame.glsl"
#include "lib/environment.glsl"

layout(binding = 0) uniform sampler2D backgroundImage;
layout(binding = 1) uniform sampler2D backgroundEyeDepth;
layout(binding = 2) uniform sampler2D environmentMap;

uniform bool hasImage;
uniform bool hasDepth;
uniform bool hasEnvironment;
uniform vec3 backgroundColor;

layout(location = 0) out vec4 outColor;
layout(location = 1) out float outEyeDepth;

void main() {
  ivec2 pixel = ivec2(gl_FragCoord.xy);
  vec3 behind = backgroundColor;
  if (hasEnvironment)
    behind = texture(environmentMap, equirectangularUvFromDirection(worldDirectionFromFragCoord(gl_FragCoord.xy))).rgb;
  vec4 image = hasImage ? texelFetch(backgroundImage, pixel, 0) : vec4(0.0);
  // The image is premultiplied (a transparent film render), so what shows through is weighted by 1 - alpha.
  outColor = vec4(image.rgb + (1.0 - image.a) * behind, 1.0);
  float depth = hasDepth ? texelFetch(backgroundEyeDepth, pixel, 0).r : kNoSurfaceDepth;
  outEyeDepth = (isnan(depth) || depth <= 0.0) ? kNoSurfaceDepth : depth;
}
