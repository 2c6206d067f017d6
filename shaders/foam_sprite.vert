#version 450 core
// One camera-facing square per foam particle (the paper's point sprite, as an instanced quad so its size has
// no implementation limit), of half-size r_i in the plane of the particle's centre. Four vertices as a
// triangle strip per instance.
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
  FoamParticle particle = particles[gl_InstanceID];
  vec3 centre = (frame.cameraFromWorld * vec4(particle.centreAndRadius.xyz, 1.0)).xyz;
  float radius = particle.centreAndRadius.w;
  vec2 corner = vec2(gl_VertexID & 1, gl_VertexID >> 1) * 2.0 - 1.0;
  vSpriteCoord = corner;
  vCameraCentre = centre;
  vRadius = radius;
  vFoamType = int(particle.typeAndAge.x);
  vAge = particle.typeAndAge.y;
  // The search radius as a fraction of half the screen's height (section 2.1).
  vSearchRadius = radius / (frame.tanHalfFov.y * max(-centre.z, getNearClip()));
  // The CPU culls particles behind the near plane; this keeps a quad that straddles it off the screen.
  gl_Position = -centre.z > getNearClip() ? frame.clipFromCamera * vec4(centre + vec3(corner * radius, 0.0), 1.0)
                                          : vec4(2.0, 2.0, 2.0, 1.0);
}
