// One texel's column of liquid in a light's view (the sun's, a lamp's or the sky's), met by a point that the
// light reaches through it: shared by the liquid's shadow (liquid_shadow.frag) and the sky light a submerged
// point keeps (lit_background.frag). Requires lib/depth_layer.glsl and lib/light_view.glsl, and samplers
// lightFrontDepth and lightBackDepth holding that view's layers.

// Whether the column holds liquid in front of a point at `pointDepth` along the light's view: false where it
// holds none, or where the point lies in front of its front surface or within two texels of it (the front
// surface's own texels). `texelSize`: the texel's world size at the front surface.
bool liquidInColumn(ivec2 texel, float pointDepth, out float front, out float back, out float texelSize) {
  front = texelFetch(lightFrontDepth, texel, 0).r;
  texelSize = 2.0 * lightView.tanHalfFov.y * front * lightView.viewportSize.w;
  back = kNoSurfaceDepth;
  if (front >= kNoSurfaceDepth * 0.5 || pointDepth <= front + 2.0 * texelSize) return false;
  back = texelFetch(lightBackDepth, texel, 0).r;
  return true;
}

// The light's path through the column's liquid: from its front surface to its back surface, or to the point
// itself when the point is submerged.
float pathInColumn(ivec2 texel, float front, float back, float pointDepth) {
  return abs(min(back, pointDepth) - front) * lightRayLengthPerDepth(vec2(texel) + 0.5);
}

// The four texels whose columns a point at light texel position `texel` blends bilinearly (so that a shadow's
// edge is soft over one texel): the lower left one and the blend towards the others.
void lightFootprint(vec2 texel, out ivec2 base, out vec2 blend) {
  vec2 footprint = clamp(texel - 0.5, vec2(0.0), lightView.viewportSize.xy - 1.001);
  base = ivec2(floor(footprint));
  blend = footprint - vec2(base);
}

// The four columns a world point blends, as lightFootprint gives them, and its depth along the light's view;
// false where the point lies outside the view or behind the light.
bool columnsAround(vec3 world, out ivec2 base, out vec2 blend, out float pointDepth) {
  vec2 texel = lightTexelFromWorld(world);
  pointDepth = lightEyeDepthOf(world);
  base = ivec2(0);
  blend = vec2(0.0);
  if (!insideLightView(texel) || !(pointDepth > 0.0)) return false;
  lightFootprint(texel, base, blend);
  return true;
}

// The bilinear blend of what four columns give (s00 at `base`, s10 one texel along x, s01 along y).
vec3 blendColumns(vec3 s00, vec3 s10, vec3 s01, vec3 s11, vec2 blend) {
  return mix(mix(s00, s10, blend.x), mix(s01, s11, blend.x), blend.y);
}
