// Reading one depth layer of the liquid (planar eye depth, kNoSurfaceDepth where the layer is empty) for the
// depth smoothing passes. Include after lib/frame.glsl.

// True where the layer has a surface. NaN and non-positive depths count as empty, so a corrupt input pixel
// can never spread into its neighbours.
bool hasSurface(float eyeDepth) { return eyeDepth > 0.0 && eyeDepth < 0.5 * kNoSurfaceDepth; }

// The layer's eye depth at a pixel; pixels outside the image read as empty, like the background.
float layerDepthAt(sampler2D eyeDepth, ivec2 pixel) {
  if (any(lessThan(pixel, ivec2(0))) || any(greaterThanEqual(pixel, ivec2(frame.viewportSize.xy))))
    return kNoSurfaceDepth;
  return texelFetch(eyeDepth, pixel, 0).r;
}

// The camera-space position seen through the centre of a pixel at an eye depth.
vec3 cameraPositionAtPixel(ivec2 pixel, float eyeDepth) {
  return cameraRayFromFragCoord(vec2(pixel) + 0.5) * eyeDepth;
}

// The difference to the neighbour along ±axis with the smaller depth step, in units of the centre depth (so
// that a cross product of two stays in float range at any distance); false when neither neighbour has a
// surface. Taking the smaller step, a pixel on a silhouette takes its tangent from its own surface, not from
// across the depth jump.
bool smallerOneSidedDifference(sampler2D eyeDepth, ivec2 pixel, ivec2 axis, float centreDepth, out vec3 difference) {
  float forwardDepth = layerDepthAt(eyeDepth, pixel + axis);
  float backwardDepth = layerDepthAt(eyeDepth, pixel - axis);
  bool hasForward = hasSurface(forwardDepth), hasBackward = hasSurface(backwardDepth);
  if (!hasForward && !hasBackward) return false;
  vec3 centre = cameraPositionAtPixel(pixel, 1.0);
  bool useForward = hasForward && (!hasBackward || abs(forwardDepth - centreDepth) <= abs(centreDepth - backwardDepth));
  if (useForward) difference = cameraPositionAtPixel(pixel + axis, forwardDepth / centreDepth) - centre;
  else difference = centre - cameraPositionAtPixel(pixel - axis, backwardDepth / centreDepth);
  return true;
}

// Pixels per world unit at an eye depth (the focal length in pixels over the depth), for filters whose width
// is given in particle radii.
float pixelsPerUnitAtDepth(float eyeDepth) {
  return frame.viewportSize.y / (2.0 * frame.tanHalfFov.y * eyeDepth);
}

// A 1D filter's radius in pixels: `worldRadius` projected at `eyeDepth`, at most `maximumPixels`.
int filterRadiusInPixels(float worldRadius, float eyeDepth, int maximumPixels) {
  float pixels = ceil(worldRadius * pixelsPerUnitAtDepth(eyeDepth));
  return pixels >= 0.0 ? int(min(pixels, float(maximumPixels))) : 0;
}
