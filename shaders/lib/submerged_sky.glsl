// The sky and bounced light a point keeps below the liquid's surface: sky light enters the surface above the
// point and travels down to it. Shared by the sky occlusion's samples (sky_occlusion.frag), which multiply it
// into what a point keeps past other liquid, and the lit background where the sky occlusion does not run
// (lit_background.frag). Requires lib/depth_layer.glsl, lib/light_view.glsl and lib/light_column.glsl with
// the sky's view (binding 2) and its layers, and the uniforms absorptionPerUnitLength and
// submergedTolerance (how far below the liquid's drawn bottom a point still lies in it).

const float kHemisphericalFresnel = 0.066;  // water's Fresnel reflectance averaged over a cosine-weighted sky
const float kDiffusePathFactor = 1.194;     // mean 1 / cos of cosine-weighted sky light refracted into water

// How far down in one texel's column of the sky's view a point lies below the liquid's surface; negative where
// it is not in that column's liquid: where the column holds none, or past the liquid's bottom (the point is
// under the liquid but not in it).
float depthInColumn(ivec2 texel, float pointDepth) {
  float front, back, texelSize;
  if (!liquidInColumn(texel, pointDepth, front, back, texelSize)) return -1.0;
  // The drawn bottom undulates by about a particle radius; a floor the liquid rests on lies within that.
  if (pointDepth > back + max(2.0 * texelSize, submergedTolerance)) return -1.0;
  return pathInColumn(texel, front, back, pointDepth);
}

// The sky light that reaches a point through one texel's column of the sky's view.
vec3 skyThroughTexel(ivec2 texel, float pointDepth) {
  float depth = depthInColumn(texel, pointDepth);
  if (depth < 0.0) return vec3(1.0);
  return (1.0 - kHemisphericalFresnel) * exp(-absorptionPerUnitLength * depth * kDiffusePathFactor);
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

// How far below the liquid's surface a world point lies (0 where it is not in the liquid), from the same four
// columns, blended alike.
float depthBelowSurface(vec3 world) {
  ivec2 base;
  vec2 blend;
  float depth;
  if (!columnsAround(world, base, blend, depth)) return 0.0;
  vec4 depths = max(vec4(depthInColumn(base, depth), depthInColumn(base + ivec2(1, 0), depth),
                         depthInColumn(base + ivec2(0, 1), depth), depthInColumn(base + ivec2(1, 1), depth)),
                    0.0);
  return blendColumns(vec3(depths.x), vec3(depths.y), vec3(depths.z), vec3(depths.w), blend).x;
}
