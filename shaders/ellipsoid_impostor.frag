#version 450 core
// Exact ray-ellipsoid intersection per pixel (lib/ellipsoid_ray.glsl): the planar eye depth, gl_FragDepth and
// the index of the ellipsoid that holds the nearest front-facing surface (backFaces = false, depth test LESS)
// or the farthest back-facing surface (backFaces = true, depth test GREATER). The normal is not computed here:
// on llvmpipe every fragment pays for all of its shader, and a layer's pixels are won by one fragment in
// tens, so the normal resolve (ellipsoid_normals.frag) computes it for the winner alone. Ellipsoids whose
// front lies behind the background's solids are hidden; a visible one keeps its back surface even where a
// solid cuts it, and the refraction pass clips the path at the solid. Compiled with and without the domain clip
// (lib/ellipsoid_ray.glsl) and, for the lights' views, without solids (NO_SOLIDS): llvmpipe pays for every
// line of a program whether a branch takes it or not.
#include "lib/frame.glsl"
#include "lib/ellipsoid_ray.glsl"

layout(binding = 0) uniform sampler2D backgroundEyeDepth;

flat in vec3 vUnitSphereCamera;
flat in vec3 vUnitRayAtOrigin;
flat in vec3 vUnitRayPerPixelX;
flat in vec3 vUnitRayPerPixelY;
flat in uint vEllipsoid;

#ifdef DEPTH_RANGE
// Both layers' depths in one draw, for a view that needs depth alone (the sky's): blending keeps the nearest
// entry (GL_MIN) and the farthest exit (GL_MAX); no depth test, no winner. Cast with backFaces set, so that
// eyeDepth is the exit and nearDepth the entry, each computed as the two-draw layers compute it.
layout(location = 0) out float outEntry;
layout(location = 1) out float outExit;
#else
layout(location = 0) out float outEyeDepth;
layout(location = 1) out uint outEllipsoid;  // the ellipsoid's index + 1; 0 where the layer is empty
#endif

void main() {
  EllipsoidCast surface;
  bool hit = castEllipsoid(gl_FragCoord.xy, vUnitSphereCamera,
                           PixelRays(vUnitRayAtOrigin, vUnitRayPerPixelX, vUnitRayPerPixelY), surface);
  float eyeDepth = surface.eyeDepth, nearDepth = surface.nearDepth;
#ifndef NO_SOLIDS  // a light's view has no background
  hit = hit && nearDepth < texelFetch(backgroundEyeDepth, ivec2(gl_FragCoord.xy), 0).r;
#endif
  if (!hit) discard;
#ifdef DEPTH_RANGE
  outEntry = nearDepth;
  outExit = eyeDepth;
#else
  outEyeDepth = eyeDepth;
  outEllipsoid = vEllipsoid + 1u;
  // Every ellipsoid the domain box cuts at this pixel puts the same face at the same depth, and one whose own
  // surface ends there to the last bit would win or lose by the drawing order: the face takes such ties (its
  // depth buffer value a step nearer, or farther for the back layer), so the layer is the face wherever one
  // ellipsoid reaches past it, whichever others are drawn (prep/OccludedAggregates.cpp relies on it).
  float bufferDepth = depthBufferFromEyeDepth(eyeDepth);
  uint bufferBits = floatBitsToUint(bufferDepth);
  if (clipToDomain && surface.onDomainFace)
    bufferDepth = uintBitsToFloat(backFaces ? bufferBits + 1u : bufferBits - 1u);
  gl_FragDepth = bufferDepth;
#endif
}
