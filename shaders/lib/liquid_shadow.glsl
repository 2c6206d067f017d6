// One light's shadow of the liquid on a background point, and the diffuse light it gives that point without
// the liquid: shared by the shadow pass (liquid_shadow.frag, any number of lights) and the lit background,
// which finds the one light's shadow itself (lit_background.frag, SHADOW_IN_PLACE). Requires lib/frame.glsl,
// lib/depth_layer.glsl, lib/optics.glsl, lib/light_view.glsl and lib/light_column.glsl with the light's view
// (binding 2) and its layers, a sampler lightFrontNormal with its front layer's normals, and with
// TRANSMIT_STRAIGHT the uniforms indexOfRefraction and absorptionPerUnitLength.
//
// A point behind the liquid's front surface, as the light sees it, is in its shadow. With caustics on, the
// light that goes through the liquid is splatted by the caustic pass and the shadow is the light that does
// not meet the liquid (0 behind it); without (TRANSMIT_STRAIGHT), the shadow keeps the light that crosses the
// liquid straight, with Fresnel at both surfaces and Beer-Lambert over the path. Four texels are blended
// bilinearly, so the edge is soft over one texel. The two modes are compiled as variants, not switched by a
// uniform: llvmpipe runs both sides of a branch with masks, so each mode would pay for the other's work
// (measured: 9.2 against 3.8 ms at 480x270; docs/frame-cost.md).

// What reaches a point from the light through one light texel's column of liquid.
vec3 shadowThroughTexel(ivec2 texel, vec3 world, float pointDepth) {
  float front, back, texelSize;
  if (!liquidInColumn(texel, pointDepth, front, back, texelSize)) return vec3(1.0);
#ifdef TRANSMIT_STRAIGHT
  float pathLength = pathInColumn(texel, front, back, pointDepth);
  vec4 normal = texelFetch(lightFrontNormal, texel, 0);
  vec3 travel = lightTravelAt(world);
  float cosine = normal.w > 0.0 ? abs(dot(normalize(normal.xyz), travel)) : 1.0;
  float fresnel = schlickFresnel(cosine, indexOfRefraction);
  // Leaving through the back surface costs about as much again; a submerged point sees one surface only.
  float exits = pointDepth > back ? 1.0 - fresnel : 1.0;
  return (1.0 - fresnel) * exits * exp(-absorptionPerUnitLength * pathLength);
#else
  return vec3(0.0);
#endif
}

// What a world point keeps of the light's direct light past the liquid (1: all of it).
vec3 liquidShadowAt(vec3 world) {
  ivec2 base;
  vec2 blend;
  float depth;
  if (!columnsAround(world, base, blend, depth)) return vec3(1.0);
  return blendColumns(shadowThroughTexel(base, world, depth), shadowThroughTexel(base + ivec2(1, 0), world, depth),
                      shadowThroughTexel(base + ivec2(0, 1), world, depth),
                      shadowThroughTexel(base + ivec2(1, 1), world, depth), blend);
}

// The diffuse direct light the light gives a point without the liquid, in the units of Cycles' DiffDir pass
// (irradiance x cos / pi x colour), so that the lit background can tell the lamps' share of the direct light
// from the sky's. `worldNormal`: the point's, or zero where it has none.
vec3 lampDiffuseAt(vec3 world, vec3 worldNormal) {
  float cosine = max(dot(worldNormal, -lightTravelAt(world)), 0.0);
  return lightIrradianceAt(world) * cosine / 3.14159265358979 * lightColor;
}
