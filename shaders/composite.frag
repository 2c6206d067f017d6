#version 450 core
// The final image: the liquid layer over the background, both premultiplied.

layout(binding = 0) uniform sampler2D backgroundColor;
layout(binding = 1) uniform sampler2D liquidColor;

uniform bool hasLiquid;

layout(location = 0) out vec4 outComposite;

void main() {
  ivec2 pixel = ivec2(gl_FragCoord.xy);
  vec4 liquid = hasLiquid ? texelFetch(liquidColor, pixel, 0) : vec4(0.0);
  vec4 background = texelFetch(backgroundColor, pixel, 0);
  outComposite = liquid + (1.0 - liquid.a) * background;
}
