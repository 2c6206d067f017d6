// The radiance the environment sends from a world direction: the equirectangular environment map, or the
// background's flat colour where the scene has none. Requires lib/environment.glsl.

layout(binding = 5) uniform sampler2D environmentMap;

uniform bool hasEnvironment;
uniform vec3 fallbackColor;

vec3 environmentRadiance(vec3 worldDirection) {
  return hasEnvironment ? texture(environmentMap, equirectangularUvFromDirection(worldDirection)).rgb : fallbackColor;
}
