// The sky and bounced light a point keeps below the liquid's surface: sky light enters the surface above the
// point and travels down to it. Shared by the sky occlusion's samples (sky_occlusion.frag), which multiply it
// into what a point keeps past other liquid, and the lit background where the sky occlusion does not run
// (lit_background.frag). Requires lib/depth_layer.glsl, lib/light_view.glsl and lib/light_column.glsl with
// the sky's view (binding 2) and its layers, and the uniforms absorptionPerUnitLength and
// submergedTolerance (how far below the liquid's drawn bottom a point still lies in it).

const float kHemisphericalFresnel = 0.066;  // water's Fresnel reflectance averaged over a cosine-weighted sky
const float kDiffusePathFactor = 1.194;     // mean 1 / cos of cosine-weighted sky light refracted into water

// The sky light that reaches a point through one texel's column of the sky's view; light past the liquid's
// bottom is unaffected (that point is under the liquid but not in it).
vec3 skyThroughTexel(ivec2 texel, float pointDepth) {
  float front, back, texelSize;
  if (!liquidInColumn(texel, pointDepth, front, back, texelSize)) return vec3(1.0);
  // The drawn bottom undulates by about a particle radius; a floor the liquid rests on lies within that.
  if (pointDepth > back + max(2.0 * texelSize, submergedTolerance)) return vec3(1.0);
  float pathLength = pathInColumn(texel, front, back, pointDepth);
  return (1.0 - kHemisphericalFresnel) * exp(-absorptionPerUnitLength * pathLength * kDiffusePathFactor);
}

// The same at a world point, from the four texels around it, blended bilinearly.
vec3 submergedSkyKept(vec3 world) {
  ivec2 base;
  vec2 blend;
  float depth;
  if (!columnsAround(world, base, blend, depth)) return vec3(1.0);
  return blendColumns(skyThroughTexel(base, depth), skyThroughTexel(base + ivec2(1, 0), depth),
                      skyThroughTexel(base + ivec2(0, 1), depth), skyThroughTexel(base + ivec2(1, 1), depth), blend);
}
