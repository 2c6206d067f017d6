#version 450 core
// Marks the 16 × 16 pixel tiles (framedata/PixelTiles.h) where the lights change the background: a pixel in
// a light's shadow or caustics, or one whose sky light the liquid takes (lit_background.frag). In every other
// tile lit_background.frag would write the background as it is, a shadow of 1, no caustics and all of the
// sky light; LitBackgroundPass clears those targets so and its PLAIN variant writes the colour, without
// looking anything up. On a far camera's frame the lit tiles were 5 % of the screen (docs/frame-cost.md,
// session 53).
//
// A tile is lit when any sky occlusion sample its pixels upsample keeps less (or more) than all of the sky
// light, or a caustic splat landed in it, or any of its pixels has liquid in one of the four light columns its
// shadow blends (SHADOW_IN_PLACE) or a shadow sum that is not 1 (else). Each test is the lit background's own
// condition for a pixel to differ from the background, so the two variants together write every pixel as
// the full pass would. One invocation per tile, which stops at its first lit pixel (pixel_tiles.comp).
layout(local_size_x = 8, local_size_y = 8) in;
#include "lib/frame.glsl"
#include "lib/depth_layer.glsl"
#include "lib/optics.glsl"
#include "lib/light_view.glsl"

// The lit background's texture units (LitBackgroundPass).
layout(binding = 2) uniform usampler2D causticTiles;  // 1 where a caustic splat landed (caustic_splat.frag)
layout(binding = 3) uniform sampler2D backgroundEyeDepth;
layout(binding = 10) uniform sampler2D skyOcclusion;  // sky_occlusion.frag's samples
uniform int skyOcclusionScale;                        // pixels per sample along each axis

#ifdef SHADOW_IN_PLACE
// The one light's view, bound at binding 2 as lightView.
layout(binding = 8) uniform sampler2D lightFrontDepth;
layout(binding = 9) uniform sampler2D lightBackDepth;
#include "lib/light_column.glsl"
#else
layout(binding = 1) uniform sampler2D shadowSum;  // (sum of weight x shadow, sum of weight)
#endif

layout(binding = 0, r8ui) uniform writeonly uimage2D litTiles;
layout(binding = 1, r8ui) uniform writeonly uimage2D plainTiles;  // the others
layout(std430, binding = 1) buffer TileCounter { uint litTileCount; };

// Whether a sample that a pixel in [first, last) upsamples (lit_background.frag's skyKeptAt: the four around
// (pixel - scale / 2) / scale, clamped) holds a surface that keeps other than all of its sky light.
bool skyLightTaken(ivec2 first, ivec2 last) {
  int scale = skyOcclusionScale;
  ivec2 lastSample = textureSize(skyOcclusion, 0) - 1;
  ivec2 low = clamp(ivec2(floor(vec2(first - scale / 2) / float(scale))), ivec2(0), lastSample);
  ivec2 high = clamp(ivec2(floor(vec2(last - 1 - scale / 2) / float(scale))) + 1, ivec2(0), lastSample);
  for (int y = low.y; y <= high.y; ++y)
    for (int x = low.x; x <= high.x; ++x) {
      vec4 kept = texelFetch(skyOcclusion, ivec2(x, y), 0);
      // NaN is "not equal": such a tile is shaded, as it would have been.
      if (hasSurface(kept.a) && any(notEqual(kept.rgb, vec3(1.0)))) return true;
    }
  return false;
}

#ifdef SHADOW_IN_PLACE
// Whether liquid may shadow a solid point of the tile [first, last). The tile's points lie in the hull of its
// pixel rays between its nearest and farthest solid (a point is its depth times an affine function of its
// pixel), so the hull's corners bound where the points fall in the light's view and how far along it they lie.
// A point outside the view keeps its light, and one in a column whose liquid does not begin before the point
// is not in its shadow (liquidInColumn). On a far camera's frame most tiles are settled by their corners, and
// most of a pool's surroundings by the few columns they fall in.
bool shadowPossible(ivec2 first, ivec2 last) {
  float nearest = kNoSurfaceDepth, farthest = 0.0;
  for (int y = first.y; y < last.y; ++y)
    for (int x = first.x; x < last.x; ++x) {
      float eyeDepth = texelFetch(backgroundEyeDepth, ivec2(x, y), 0).r;
      if (!hasSurface(eyeDepth)) continue;
      nearest = min(nearest, eyeDepth);
      farthest = max(farthest, eyeDepth);
    }
  if (!(nearest <= farthest)) return false;  // no solid in the tile: nothing to shadow
  vec2 low = vec2(1e30), high = vec2(-1e30);
  float farthestFromLight = 0.0;
  for (int corner = 0; corner < 8; ++corner) {
    vec2 fragCoord = vec2((corner & 1) != 0 ? float(last.x) - 0.5 : float(first.x) + 0.5,
                          (corner & 2) != 0 ? float(last.y) - 0.5 : float(first.y) + 0.5);
    vec3 world = worldPositionFromFragCoord(fragCoord, (corner & 4) != 0 ? farthest : nearest);
    float lightDepth = lightEyeDepthOf(world);
    if (!(lightDepth > 0.0)) return true;  // reaches behind the light: no bound from the corners
    vec2 texel = lightTexelFromWorld(world);
    low = min(low, texel);
    high = max(high, texel);
    farthestFromLight = max(farthestFromLight, lightDepth);
  }
  vec2 size = lightView.viewportSize.xy;
  if (!(all(lessThan(low, size)) && all(greaterThanEqual(high, vec2(0.0))))) return false;
  // The columns the points can blend (lightFootprint: the texel below and the one after, clamped).
  ivec2 lowColumn = ivec2(floor(clamp(low - 0.5, vec2(0.0), size - 1.001)));
  ivec2 highColumn = min(ivec2(floor(clamp(high - 0.5, vec2(0.0), size - 1.001))) + 1, ivec2(size) - 1);
  ivec2 columns = highColumn - lowColumn + 1;
  if (columns.x * columns.y > 256) return true;  // more columns than pixels: each pixel is tested instead
  for (int y = lowColumn.y; y <= highColumn.y; ++y)
    for (int x = lowColumn.x; x <= highColumn.x; ++x)
      if (texelFetch(lightFrontDepth, ivec2(x, y), 0).r < farthestFromLight) return true;
  return false;
}
#endif

// Whether a light's shadow changes the pixel.
bool lampLightChanged(ivec2 pixel) {
#ifdef SHADOW_IN_PLACE
  float eyeDepth = texelFetch(backgroundEyeDepth, pixel, 0).r;
  if (!hasSurface(eyeDepth)) return false;  // no point to shadow: the lit background leaves it unlit
  ivec2 base;
  vec2 blend;
  float depth, front, back, texelSize;
  // The same point and columns as the lit background's liquidShadowAt; outside them its shadow is 1.
  if (!columnsAround(worldPositionFromFragCoord(vec2(pixel) + 0.5, eyeDepth), base, blend, depth)) return false;
  return liquidInColumn(base, depth, front, back, texelSize) ||
         liquidInColumn(base + ivec2(1, 0), depth, front, back, texelSize) ||
         liquidInColumn(base + ivec2(0, 1), depth, front, back, texelSize) ||
         liquidInColumn(base + ivec2(1, 1), depth, front, back, texelSize);
#else
  vec4 sums = texelFetch(shadowSum, pixel, 0);
  return sums.a > 0.0 && any(notEqual(sums.rgb, vec3(sums.a)));
#endif
}

void main() {
  ivec2 tile = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(tile, imageSize(litTiles)))) return;
  int tileSize = int(frame.pixelTiles.x);
  ivec2 first = tile * tileSize;
  ivec2 last = min(first + tileSize, ivec2(frame.viewportSize.xy));
  bool lit = texelFetch(causticTiles, tile, 0).r != 0u || skyLightTaken(first, last);
#ifdef SHADOW_IN_PLACE
  bool mayBeShadowed = !lit && shadowPossible(first, last);
#else
  bool mayBeShadowed = !lit;
#endif
  for (int y = first.y; y < last.y && mayBeShadowed && !lit; ++y)
    for (int x = first.x; x < last.x && !lit; ++x)
      lit = lampLightChanged(ivec2(x, y));
  imageStore(litTiles, tile, uvec4(lit ? 1u : 0u));
  imageStore(plainTiles, tile, uvec4(lit ? 0u : 1u));
  if (lit) atomicAdd(litTileCount, 1u);
}
