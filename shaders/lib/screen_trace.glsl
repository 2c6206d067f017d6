// Screen-space ray marching in camera space (after McGuire and Mara 2014): a ray o + t d (unit d) is clipped
// to the view, projected, and sampled at even steps of about `stepPixels` along its image on the screen, with
// depth interpolated perspective-correctly. A ray along the view axis projects to a few pixels and is sampled
// a few times over its whole depth range, so searches detect crossings by the sign change of a depth
// difference between samples, never by landing inside a surface. Requires lib/frame.glsl.

uniform float stepPixels;  // screen distance between samples
uniform int maxSteps;      // samples at most; a longer image is sampled more sparsely

float rayEyeDepth(vec3 origin, vec3 direction, float t) { return -(origin.z + t * direction.z); }

// The world size of one pixel at an eye depth.
float pixelSizeAt(float eyeDepth) { return 2.0 * frame.tanHalfFov.y * eyeDepth * frame.viewportSize.w; }

struct ScreenRay {
  vec3 origin;
  vec3 direction;
  vec3 start;       // camera-space points at the segment's ends, divided by their eye depth
  vec3 end;
  float inverseDepthStart;
  float inverseDepthEnd;
  float reach;      // the fraction of the segment that stays on screen
  int samples;
};

// The ray from `origin` (on screen, in front of the camera) clipped to the near and far planes and the screen,
// sampled about every `pixelsPerStep` pixels.
ScreenRay screenRaySampledEvery(vec3 origin, vec3 direction, float pixelsPerStep) {
  float tFar = direction.z < 0.0 ? (getFarClip() + origin.z) / -direction.z : 1e30;
  float tNear = direction.z > 0.0 ? (-origin.z - getNearClip()) / direction.z : 1e30;
  float tEnd = max(min(tFar, tNear), 0.0);
  vec3 endPoint = origin + tEnd * direction;
  ScreenRay ray;
  ray.origin = origin;
  ray.direction = direction;
  ray.inverseDepthStart = 1.0 / max(-origin.z, getNearClip());
  ray.inverseDepthEnd = 1.0 / max(-endPoint.z, getNearClip());
  ray.start = origin * ray.inverseDepthStart;
  ray.end = endPoint * ray.inverseDepthEnd;
  // Clip the segment's image to the screen (Liang-Barsky, only the far end can leave it).
  vec2 from = fragCoordFromCamera(origin), to = fragCoordFromCamera(endPoint);
  vec2 delta = to - from;
  ray.reach = 1.0;
  for (int axis = 0; axis < 2; ++axis) {
    if (delta[axis] > 0.0) ray.reach = min(ray.reach, (frame.viewportSize[axis] - 0.01 - from[axis]) / delta[axis]);
    if (delta[axis] < 0.0) ray.reach = min(ray.reach, (0.01 - from[axis]) / delta[axis]);
  }
  ray.reach = clamp(ray.reach, 0.0, 1.0);
  float screenLength = length(delta) * ray.reach;
  ray.samples = clamp(int(ceil(screenLength / pixelsPerStep)), 4, maxSteps);
  return ray;
}

// The same, sampled every `stepPixels`.
ScreenRay screenRay(vec3 origin, vec3 direction) { return screenRaySampledEvery(origin, direction, stepPixels); }

// The ray parameter t at fraction s of the segment's image (perspective-correct).
float screenRayT(ScreenRay ray, float s) {
  float inverseDepth = mix(ray.inverseDepthStart, ray.inverseDepthEnd, s);
  vec3 position = mix(ray.start, ray.end, s) / inverseDepth;
  return max(dot(position - ray.origin, ray.direction), 0.0);
}

// The parameter of the k-th of the ray's samples (k = 1 ... samples).
float screenRaySampleT(ScreenRay ray, int k) { return screenRayT(ray, ray.reach * float(k) / float(ray.samples)); }
