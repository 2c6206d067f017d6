// The scene's lights as they light foam (FoamOcclusionPass uploads them; docs/foam.md, "Lit by the scene's
// lights"): each adds its direct irradiance on the foam fragment's normal, in the normalisation of the
// environment's term, so that foam.irradiance_scale's 2 turns both into a white diffuse surface's radiance.
// Nothing shadows a light here; the SSAO's zeta darkens foam as the paper darkens it.
#include "lib/lamp.glsl"

struct FoamLamp {
  vec4 directionAndType;     // the way the light travels (sun, spot); the type (kSun, kSpot, kPoint)
  vec4 positionAndStrength;  // spot and point: world position; sun: W/m^2, spot and point: W (Blender's)
  vec4 colorAndSpotCosine;   // linear RGB; the cosine of a spot's cone half angle
};

layout(std430, binding = 3) readonly buffer FoamLamps {
  FoamLamp foamLamps[];
};
uniform int foamLampCount;  // the buffer holds one entry at least, as a buffer may not be empty

// (1 / 2 pi) E max(0, n . l) summed over the lights, E the irradiance each gives a surface facing it and l the
// way to it: for a uniform environment L the environment's term is L / 2, the same share of a white diffuse
// surface's radiance L.
vec3 foamLampIrradiance(vec3 worldPosition, vec3 worldNormal) {
  vec3 sum = vec3(0.0);
  for (int i = 0; i < foamLampCount; ++i) {
    FoamLamp lamp = foamLamps[i];
    int type = int(lamp.directionAndType.w);
    vec3 direction = lamp.directionAndType.xyz, position = lamp.positionAndStrength.xyz;
    float irradiance = lampIrradianceAt(type, direction, position, lamp.positionAndStrength.w,
                                        lamp.colorAndSpotCosine.w, worldPosition);
    vec3 travel = lampTravelAt(type, direction, position, worldPosition);
    sum += lamp.colorAndSpotCosine.rgb * (irradiance * max(dot(worldNormal, -travel), 0.0) * 0.15915494309);  // 1 / (2 pi)
  }
  return sum;
}
