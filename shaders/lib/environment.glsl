// Equirectangular environment lookups with Blender's world convention (+Z up), the mapping of Cycles'
// direction_to_equirectangular: u = -atan(y, x) / (2 pi) + 0.5, v = atan(z, |xy|) / pi + 0.5, v up.
const float kPi = 3.14159265358979;

vec2 equirectangularUvFromDirection(vec3 direction) {
  float u = -atan(direction.y, direction.x) / (2.0 * kPi) + 0.5;
  float v = atan(direction.z, length(direction.xy)) / kPi + 0.5;
  return vec2(u, v);  // Textures are uploaded bottom row first, so v runs up as in Blender.
}

// The inverse of equirectangularUvFromDirection: the unit direction at texture coordinates (u, v).
vec3 directionFromEquirectangularUv(vec2 uv) {
  float azimuth = (0.5 - uv.x) * 2.0 * kPi;
  float elevation = (uv.y - 0.5) * kPi;
  return vec3(cos(elevation) * cos(azimuth), cos(elevation) * sin(azimuth), sin(elevation));
}
