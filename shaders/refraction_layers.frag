#version 450 core
// The four depth layers the refraction's marches read at every sample (the splash and aggregate front and back
// eye depths), packed into one texel per pixel, so that a sample fetches once what it fetched from up to four
// textures (refraction.frag's frontDepth and backDepth).
layout(binding = 0) uniform sampler2D splashFrontDepth;
layout(binding = 1) uniform sampler2D splashBackDepth;
layout(binding = 2) uniform sampler2D aggregateFrontDepth;
layout(binding = 3) uniform sampler2D aggregateBackDepth;

layout(location = 0) out vec4 outDepths;  // splash front, splash back, aggregate front, aggregate back

void main() {
  ivec2 pixel = ivec2(gl_FragCoord.xy);
  outDepths = vec4(texelFetch(splashFrontDepth, pixel, 0).r, texelFetch(splashBackDepth, pixel, 0).r,
                   texelFetch(aggregateFrontDepth, pixel, 0).r, texelFetch(aggregateBackDepth, pixel, 0).r);
}
