// Screen-space ray marching in camera space: a ray o + t d (unit d) is followed over the screen, sampling
// depth textures at the pixel it projects to, with steps of about `stepPixels` pixels at the ray's depth.
// Requires lib/frame.glsl.

uniform float stepPixels;   // screen distance per march step
uniform int maxSteps;       // march steps before a search gives up
uniform float minimumStep;  // world units: the smallest step, so rays along the view axis still advance

float rayEyeDepth(vec3 origin, vec3 direction, float t) { return -(origin.z + t * direction.z); }

// Window coordinates (gl_FragCoord convention) of a camera-space point in front of the camera.
vec2 fragCoordFromCamera(vec3 position) {
  vec4 clip = frame.clipFromCamera * vec4(position, 1.0);
  return (clip.xy / clip.w * 0.5 + 0.5) * frame.viewportSize.xy;
}

bool onScreen(vec2 fragCoord) {
  return all(greaterThanEqual(fragCoord, vec2(0.0))) && all(lessThan(fragCoord, frame.viewportSize.xy));
}

// The world size of one pixel at an eye depth.
float pixelSizeAt(float eyeDepth) { return 2.0 * frame.tanHalfFov.y * eyeDepth * frame.viewportSize.w; }

float marchStep(float eyeDepth) { return max(stepPixels * pixelSizeAt(max(eyeDepth, getNearClip())), minimumStep); }
