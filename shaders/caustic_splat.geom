#version 450 core
// Caustics, step 2: each triangle of light carries the light that fell on its source triangle in the light's
// view; spread over the receiver triangle, its irradiance relative to the light's own is the ratio of the two
// areas as the light sees them (exact for a sun, and for a point light to first order). Triangles with a vertex
// whose light was lost, that span a jump in the background's depth, or whose three receivers lie hidden behind
// what the camera sees, are dropped.
#include "lib/frame.glsl"

layout(triangles) in;
layout(triangle_strip, max_vertices = 3) out;

in VertexPath {
  vec4 cameraPosition;  // w: 0 lost, 1 reached, 2 reached but hidden (caustic_paths.comp)
  vec3 carried;
  vec2 receiverTexel;
  vec2 sourceTexel;
} path[];

uniform float maxConcentration;

out vec3 gCarried;
out float gEyeDepth;
flat out float gConcentration;

float triangleArea(vec2 a, vec2 b, vec2 c) { return 0.5 * abs((b.x - a.x) * (c.y - a.y) - (c.x - a.x) * (b.y - a.y)); }

void main() {
  if (path[0].cameraPosition.w * path[1].cameraPosition.w * path[2].cameraPosition.w == 0.0) return;
  // Every fragment of such a triangle lies behind the visible surface where that surface is one solid's (a
  // triangle is convex, so it lies within any convex region holding its corners), and the splat would discard
  // it: the pool from the side's light, landing on the floor behind its tank's near wall, took 4 ms of the
  // splat's rasterising for 36 fragments kept (docs/frame-cost.md, session 61).
  if (path[0].cameraPosition.w == 2.0 && path[1].cameraPosition.w == 2.0 && path[2].cameraPosition.w == 2.0) return;
  float nearest = min(-path[0].cameraPosition.z, min(-path[1].cameraPosition.z, -path[2].cameraPosition.z));
  float farthest = max(-path[0].cameraPosition.z, max(-path[1].cameraPosition.z, -path[2].cameraPosition.z));
  if (farthest > 1.2 * nearest) return;
  float source = triangleArea(path[0].sourceTexel, path[1].sourceTexel, path[2].sourceTexel);
  float receiver = triangleArea(path[0].receiverTexel, path[1].receiverTexel, path[2].receiverTexel);
  float concentration = min(source / max(receiver, 1e-12), maxConcentration);
  for (int i = 0; i < 3; ++i) {
    gl_Position = frame.clipFromCamera * vec4(path[i].cameraPosition.xyz, 1.0);
    gCarried = path[i].carried;
    gEyeDepth = -path[i].cameraPosition.z;
    gConcentration = concentration;
    EmitVertex();
  }
  EndPrimitive();
}
