#version 450 core
// The final image: the liquid layer over the background, and the foam over both, all premultiplied. With the
// foam's alpha iota this is the foam paper's C = (1 - iota) C_bg + iota (I_final - zeta_final), C_bg being the
// liquid over the background.

layout(binding = 0) uniform sampler2D backgroundColor;
layout(binding = 1) uniform sampler2D liquidColor;
layout(binding = 2) uniform sampler2D foamColor;

uniform bool hasLiquid;
uniform bool hasFoam;

layout(location = 0) out vec4 outComposite;

void main() {
  ivec2 pixel = ivec2(gl_FragCoord.xy);
  vec4 liquid = hasLiquid ? texelFetch(liquidColor, pixel, 0) : vec4(0.0);
  vec4 foam = hasFoam ? texelFetch(foamColor, pixel, 0) : vec4(0.0);
  vec4 background = texelFetch(backgroundColor, pixel, 0);
  outComposite = foam + (1.0 - foam.a) * (liquid + (1.0 - liquid.a) * background);
}
