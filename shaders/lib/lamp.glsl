// A lamp in Blender's terms, as the scene format names it (docs/scene-format.md, "Lights"): which way its
// light travels where it reaches a point, and how strong it is there. One formula for the light passes
// (lib/light_view.glsl) and the foam (lib/foam_lamps.glsl).

const int kSun = 0;
const int kSpot = 1;
const int kPoint = 2;

// The unit direction a lamp's light travels in when it reaches a world point; `direction` is a sun's or a
// spot's, `position` a spot's or a point's.
vec3 lampTravelAt(int type, vec3 direction, vec3 position, vec3 world) {
  return type == kSun ? direction : normalize(world - position);
}

// Irradiance the lamp would give a surface facing it at a world point, without the liquid (W/m^2): a sun's
// strength, or a spot's or point's power spread over the sphere (Blender's convention), zero outside a spot's
// cone (`spotCosine`, the cosine of its half angle).
float lampIrradianceAt(int type, vec3 direction, vec3 position, float strength, float spotCosine, vec3 world) {
  if (type == kSun) return strength;
  vec3 offset = world - position;
  float distanceSquared = max(dot(offset, offset), 1e-8);
  if (type == kSpot && dot(offset, direction) < spotCosine * sqrt(distanceSquared)) return 0.0;
  return strength / (12.566370614 * distanceSquared);  // 4 pi
}
