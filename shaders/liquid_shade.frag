#version 450 core
// The foundation's lit material for the liquid surface: ambient light from the environment (or background
// colour) plus a Lambert and Blinn-Phong key light. Premultiplied RGBA over transparent.
#include "lib/frame.glsl"
#include "lib/environment.glsl"

layout(binding = 0) uniform sampler2D surfaceEyeDepth;
layout(binding = 1) uniform sampler2D surfaceNormal;
layout(binding = 2) uniform sampler2D environmentMap;

uniform bool hasEnvironment;
uniform vec3 backgroundColor;
uniform vec3 baseColor;
uniform float ambient;
uniform float specular;
uniform float shininess;
uniform vec3 lightDirection;  // world space, normalised

layout(location = 0) out vec4 outLiquid;

void main() {
  ivec2 pixel = ivec2(gl_FragCoord.xy);
  vec4 normalAndCoverage = texelFetch(surfaceNormal, pixel, 0);
  if (normalAndCoverage.w == 0.0) {
    outLiquid = vec4(0.0);
    return;
  }
  vec3 normal = normalize(normalAndCoverage.xyz);
  vec3 position = worldPositionFromFragCoord(gl_FragCoord.xy, texelFetch(surfaceEyeDepth, pixel, 0).r);
  vec3 towardsCamera = normalize(getCameraWorldPosition() - position);
  vec3 ambientLight = hasEnvironment ? texture(environmentMap, equirectangularUvFromDirection(normal)).rgb
                                     : backgroundColor;
  float diffuse = max(dot(normal, lightDirection), 0.0);
  float highlight = pow(max(dot(normal, normalize(lightDirection + towardsCamera)), 0.0), shininess);
  vec3 color = baseColor * (ambient * ambientLight + diffuse) + specular * highlight * step(0.0, diffuse);
  outLiquid = vec4(color, 1.0);
}
