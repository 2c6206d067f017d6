#version 450 core
// One camera-facing triangle per foam particle around the paper's point sprite, a disc of radius r_i in the
// plane of the particle's centre (a triangle, so that its size has no implementation limit): the equilateral
// triangle around the unit circle, scaled by r_i. Three vertices per particle (gl_VertexID / 3 names it), drawn
// as plain arrays: llvmpipe pays per instance. On the drop example's 115,000 foam particles the instanced
// quads they replaced took 62-64 ms in the depth pass and 66-67 in the thickness pass, the triangles 18-23 and
// 21-23 (docs/frame-cost.md).
#include "lib/around_unit_circle.glsl"
#include "lib/frame.glsl"

struct FoamParticle {
  vec4 centreAndRadius;  // world centre, drawn radius
  vec4 typeAndAge;       // type (0 spray, 1 surface, 2 bubble), normalised age
};

layout(std430, binding = 0) readonly buffer FoamParticles {
  FoamParticle particles[];
};

out vec2 vSpriteCoord;
flat out vec3 vCameraCentre;
flat out float vRadius;
flat out int vFoamType;
flat out float vAge;
flat out float vSearchRadius;

void main() {
  FoamParticle particle = particles[gl_VertexID / 3];
  vec3 centre = (frame.cameraFromWorld * vec4(particle.centreAndRadius.xyz, 1.0)).xyz;
  float radius = particle.centreAndRadius.w;
  vec2 corner = kAroundUnitCircle[gl_VertexID % 3];
  vSpriteCoord = corner;
  vCameraCentre = centre;
  vRadius = radius;
  vFoamType = int(particle.typeAndAge.x);
  vAge = particle.typeAndAge.y;
  // The search radius as a fraction of half the screen's height (section 2.1).
  vSearchRadius = radius / (frame.tanHalfFov.y * max(-centre.z, getNearClip()));
  // The CPU culls particles behind the near plane; this keeps a triangle that straddles it off the screen.
  gl_Position = -centre.z > getNearClip() ? frame.clipFromCamera * vec4(centre + vec3(corner * radius, 0.0), 1.0)
                                          : vec4(2.0, 2.0, 2.0, 1.0);
}
