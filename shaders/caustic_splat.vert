#version 450 core
// Caustics, step 2: the grid of light paths as triangles, two per cell, each vertex where its light meets the
// background (caustic_paths.comp). No vertex buffer: gl_VertexID names the cell and the corner.
layout(binding = 0) uniform sampler2D receiverPosition;
layout(binding = 1) uniform sampler2D receiverLight;
layout(binding = 2) uniform sampler2D receiverLightTexel;

uniform int gridStep;

out VertexPath {
  vec4 cameraPosition;  // w: 0 lost, 1 reached, 2 reached but hidden (caustic_paths.comp)
  vec3 carried;
  vec2 receiverTexel;   // where the receiver lies in the light's view
  vec2 sourceTexel;     // where the light entered, in the light's view
} path;

const ivec2 kCorners[6] = ivec2[6](ivec2(0, 0), ivec2(1, 0), ivec2(0, 1), ivec2(1, 0), ivec2(1, 1), ivec2(0, 1));

void main() {
  ivec2 gridSize = textureSize(receiverPosition, 0);
  int cell = gl_VertexID / 6;
  ivec2 vertex = ivec2(cell % (gridSize.x - 1), cell / (gridSize.x - 1)) + kCorners[gl_VertexID % 6];
  path.cameraPosition = texelFetch(receiverPosition, vertex, 0);
  path.carried = texelFetch(receiverLight, vertex, 0).rgb;
  path.receiverTexel = texelFetch(receiverLightTexel, vertex, 0).xy;
  path.sourceTexel = vec2(vertex * gridStep);
  gl_Position = vec4(0.0);
}
