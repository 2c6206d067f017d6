// A Mantaflow domain's box, inset to where its mesh closes against the walls (docs/mantaflow-caches.md): the
// liquid is cut flat there. Set by setDomainBoxUniforms (native/src/passes/FrameUniforms.h). Include after
// lib/frame.glsl.
uniform bool hasDomain;
uniform mat4 domainFromWorld;
uniform vec3 domainLow;
uniform vec3 domainHigh;

// A camera-space point in the box's frame.
vec3 inDomainBox(vec3 cameraPosition) {
  return (domainFromWorld * (frame.worldFromCamera * vec4(cameraPosition, 1.0))).xyz;
}
