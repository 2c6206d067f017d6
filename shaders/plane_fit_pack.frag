#version 450 core
// The plane fit's input in one texel per pixel (depth_plane_fit.frag reads a tap once instead of twice): the
// layer's eye depth, and its original world normal (ñ of the liquid paper's eq. 3), which no iteration changes.
layout(binding = 0) uniform sampler2D eyeDepth;
layout(binding = 1) uniform sampler2D originalNormal;

layout(location = 0) out vec4 outDepthAndNormal;

void main() {
  ivec2 pixel = ivec2(gl_FragCoord.xy);
  outDepthAndNormal = vec4(texelFetch(eyeDepth, pixel, 0).r, texelFetch(originalNormal, pixel, 0).xyz);
}
