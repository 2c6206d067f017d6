// Screen-space ray marching in camera space: a ray o + t d (unit d) is followed over the screen, sampling
// depth textures at the pixel it projects to, with steps of about `stepPixels` pixels at the ray's depth.
// Requires lib/frame.glsl.

uniform float stepPixels;   // screen distance per march step
uniform int maxSteps;       // march steps before a search gives up
uniform float minimumStep;  // world units: the smallest step, so rays along the view axis still advance

float rayEyeDepth(vec3 origin, vec3 direction, float t) { return -(origin.z + t * direction.z); }

// The world size of one pixel at an eye depth.
float pixelSizeAt(float eyeDepth) { return 2.0 * frame.tanHalfFov.y * eyeDepth * frame.viewportSize.w; }

float marchStep(float eyeDepth) { return max(stepPixels * pixelSizeAt(max(eyeDepth, getNearClip())), minimumStep); }
