#version 450 core
// The four depth layers the refraction's marches read at every sample (the splash and aggregate front and back
// eye depths), packed into one texel per pixel, so that a sample fetches once what it fetched from up to four
// textures (refraction.frag's frontDepth and backDepth); and the four layers' normals copied into the layers
// of one array texture (refraction.frag's normalTexel), which a lookup indexes by body and side where it
// chose among four textures: on llvmpipe both sides of each choice were fetched.
layout(binding = 0) uniform sampler2D splashFrontDepth;
layout(binding = 1) uniform sampler2D splashBackDepth;
layout(binding = 2) uniform sampler2D aggregateFrontDepth;
layout(binding = 3) uniform sampler2D aggregateBackDepth;
layout(binding = 4) uniform sampler2D splashFrontNormal;
layout(binding = 5) uniform sampler2D splashBackNormal;
layout(binding = 6) uniform sampler2D aggregateFrontNormal;
layout(binding = 7) uniform sampler2D aggregateBackNormal;

layout(location = 0) out vec4 outDepths;  // splash front, splash back, aggregate front, aggregate back
layout(location = 1) out vec4 outSplashFrontNormal;  // layers 0-3 of the normals' array texture
layout(location = 2) out vec4 outSplashBackNormal;
layout(location = 3) out vec4 outAggregateFrontNormal;
layout(location = 4) out vec4 outAggregateBackNormal;

void main() {
  ivec2 pixel = ivec2(gl_FragCoord.xy);
  outDepths = vec4(texelFetch(splashFrontDepth, pixel, 0).r, texelFetch(splashBackDepth, pixel, 0).r,
                   texelFetch(aggregateFrontDepth, pixel, 0).r, texelFetch(aggregateBackDepth, pixel, 0).r);
  outSplashFrontNormal = texelFetch(splashFrontNormal, pixel, 0);
  outSplashBackNormal = texelFetch(splashBackNormal, pixel, 0);
  outAggregateFrontNormal = texelFetch(aggregateFrontNormal, pixel, 0);
  outAggregateBackNormal = texelFetch(aggregateBackNormal, pixel, 0);
}
