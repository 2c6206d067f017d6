// Where a caustic's light lands on what the camera sees: the receiver's eye depth must match the background's
// visible surface there, within 2 % of its depth and three pixels' width (the splat's own test; a receiver
// found by marching lies within bisection's precision of it). Requires lib/frame.glsl.
float causticDepthTolerance(float backgroundEyeDepth) {
  float pixelSize = 2.0 * frame.tanHalfFov.y * backgroundEyeDepth * frame.viewportSize.w;
  return 0.02 * backgroundEyeDepth + 3.0 * pixelSize;
}
