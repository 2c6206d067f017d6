#version 450 core
// The background lit as the liquid lets it be: every light's shadow and caustics (the sums of
// liquid_shadow.frag and caustic_splat.frag, weighted by each light's irradiance) scale the lamps' direct
// light, and the sky light a submerged point keeps scales the rest. With Cycles' light passes:
// Combined - direct (s (1 - shadow - caustics) + (1 - s)(1 - sky)) - indirect (1 - sky), where "direct" is
// Cycles' direct diffuse and glossy light and s the lamps' share of it. Cycles counts the world's light as
// direct too (the sky is sampled like a lamp), so s is the lamps' diffuse light at the point without the
// liquid (liquid_shadow.frag) over DiffDir, at most 1; the glossy light takes the diffuse share (caustics
// add diffuse light only). Without the passes, `directFraction` of the background is taken as the lamps'.
layout(binding = 0) uniform sampler2D backgroundColor;
layout(binding = 1) uniform sampler2D shadowSum;    // (sum of weight x shadow, sum of weight)
layout(binding = 2) uniform sampler2D causticSum;   // sum of weight x caustic
layout(binding = 3) uniform sampler2D skyKept;
layout(binding = 4) uniform sampler2D directDiffuse;  // DiffCol x DiffDir; alpha: DiffDir
layout(binding = 5) uniform sampler2D directGlossy;   // GlossCol x GlossDir
layout(binding = 6) uniform sampler2D indirectLight;  // DiffCol x DiffInd + GlossCol x GlossInd
layout(binding = 7) uniform sampler2D lampDiffuse;    // the lamps' diffuse light without the liquid

uniform bool hasLightPasses;
uniform float directFraction;

layout(location = 0) out vec4 outColor;
layout(location = 1) out vec4 outShadow;
layout(location = 2) out vec4 outCaustics;
layout(location = 3) out vec4 outSky;

void main() {
  ivec2 pixel = ivec2(gl_FragCoord.xy);
  vec4 background = texelFetch(backgroundColor, pixel, 0);
  vec4 shadowWeighted = texelFetch(shadowSum, pixel, 0);
  bool lit = shadowWeighted.a > 0.0;
  vec3 shadow = lit ? shadowWeighted.rgb / shadowWeighted.a : vec3(1.0);
  vec3 caustics = lit ? texelFetch(causticSum, pixel, 0).rgb / shadowWeighted.a : vec3(0.0);
  vec3 sky = texelFetch(skyKept, pixel, 0).rgb;
  vec3 colour;
  if (hasLightPasses) {
    vec4 diffuse = texelFetch(directDiffuse, pixel, 0);
    float lamps = dot(texelFetch(lampDiffuse, pixel, 0).rgb, vec3(1.0 / 3.0));
    float share = diffuse.a > 0.0 ? clamp(lamps / diffuse.a, 0.0, 1.0) : 1.0;
    vec3 skyLost = (1.0 - share) * (1.0 - sky);
    colour = background.rgb - diffuse.rgb * (share * (1.0 - shadow - caustics) + skyLost) -
             texelFetch(directGlossy, pixel, 0).rgb * (share * (1.0 - shadow) + skyLost) -
             texelFetch(indirectLight, pixel, 0).rgb * (1.0 - sky);
    colour = max(colour, vec3(0.0));
  } else {
    colour = background.rgb * (directFraction * (shadow + caustics) + (1.0 - directFraction) * sky);
  }
  outColor = vec4(colour, background.a);
  outShadow = vec4(shadow, 1.0);
  outCaustics = vec4(caustics, 1.0);
  outSky = vec4(sky, 1.0);
}
