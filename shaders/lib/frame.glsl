// The frame's camera, shared by every pass (binding 0). Mirrors FrameUniforms in
// native/src/passes/FrameUniforms.h, std140. Camera space is Blender's: looking down -Z, +Y up; "eye depth"
// is planar depth along the view axis (positive in front of the camera), as in Blender's Depth pass.
layout(std140, binding = 0) uniform FrameBlock {
  mat4 clipFromCamera;
  mat4 cameraFromWorld;
  mat4 worldFromCamera;
  vec4 viewportSize;  // width, height, 1/width, 1/height
  vec4 clipPlanes;    // near, far, 1 / far, unused
  vec4 tanHalfFov;    // tan(fov_x / 2), tan(fov_y / 2), unused, unused
  vec4 pixelTiles;    // the side of a pixel tile (framedata/PixelTiles.h), unused, unused, unused
} frame;

// What depth and normal outputs hold where there is no surface: Blender's "nothing here" depth.
const float kNoSurfaceDepth = 1e10;

// A texel by its integer position, through the sampler: on llvmpipe (Mesa 22.3) textureLod with nearest
// filtering costs less than texelFetch (the plane fit 29-31 -> 24-25 ms, the refraction 37-38 -> 32-34 ms on
// the dam break; docs/frame-cost.md, session 49). Every texture the passes make filters NEAREST (gl/GlObjects.cpp), so
// a position inside it gives exactly its texel, as texelFetch does. Outside it the texture's wrap mode
// answers (clamp to edge, or the border where a pass sets one) where texelFetch's result is undefined.
vec4 texelAt(sampler2D image, ivec2 texel) {
  return textureLod(image, (vec2(texel) + 0.5) / vec2(textureSize(image, 0)), 0.0);
}
vec4 texelAt(sampler2DArray images, ivec3 texel) {
  return textureLod(images, vec3((vec2(texel.xy) + 0.5) / vec2(textureSize(images, 0).xy), float(texel.z)), 0.0);
}

// Bilinear weights of the four texels around a window position (in pixels, texel centres at half-integers),
// and the first of them.
void bilinearFootprint(vec2 fragCoord, out ivec2 base, out vec2 weight) {
  vec2 texel = clamp(fragCoord - 0.5, vec2(0.0), frame.viewportSize.xy - 1.001);
  base = ivec2(floor(texel));
  weight = texel - vec2(base);
}

// A viewport-sized image between its texels' centres, bilinear in those of the four nearest that show the
// surface at eye depth `depth` (their `eyeDepth` within a tenth of it): a lookup on the floor just behind a
// wall's edge does not take the wall's colour. Where none of them does, the nearest texel.
const float kSameSurface = 0.1;
vec4 bilinearOnSurface(sampler2D image, sampler2D eyeDepth, vec2 fragCoord, float depth) {
  ivec2 base;
  vec2 weight;
  bilinearFootprint(fragCoord, base, weight);
  vec4 sum = vec4(0.0);
  float total = 0.0;
  for (int corner = 0; corner < 4; ++corner) {
    ivec2 texel = base + ivec2(corner & 1, corner >> 1);
    vec2 along = mix(1.0 - weight, weight, vec2(texel - base));
    if (abs(texelAt(eyeDepth, texel).r - depth) > kSameSurface * depth) continue;
    sum += along.x * along.y * texelAt(image, texel);
    total += along.x * along.y;
  }
  return total > 0.0 ? sum / total : texelAt(image, ivec2(fragCoord));
}

float getNearClip() { return frame.clipPlanes.x; }
float getFarClip() { return frame.clipPlanes.y; }
vec3 getCameraWorldPosition() { return frame.worldFromCamera[3].xyz; }

// The camera-space ray through a window position (gl_FragCoord.xy, origin bottom left), scaled so that its
// z is -1: multiplying it by an eye depth gives the camera-space point at that depth.
vec3 cameraRayFromFragCoord(vec2 fragCoord) {
  vec2 ndc = fragCoord * frame.viewportSize.zw * 2.0 - 1.0;
  return vec3(ndc * frame.tanHalfFov.xy, -1.0);
}

vec3 worldPositionFromFragCoord(vec2 fragCoord, float eyeDepth) {
  return (frame.worldFromCamera * vec4(cameraRayFromFragCoord(fragCoord) * eyeDepth, 1.0)).xyz;
}

vec3 worldDirectionFromFragCoord(vec2 fragCoord) {
  return normalize(mat3(frame.worldFromCamera) * cameraRayFromFragCoord(fragCoord));
}

// Window coordinates (gl_FragCoord convention) of a camera-space point in front of the camera.
vec2 fragCoordFromCamera(vec3 position) {
  vec4 clip = frame.clipFromCamera * vec4(position, 1.0);
  return (clip.xy / clip.w * 0.5 + 0.5) * frame.viewportSize.xy;
}

bool onScreen(vec2 fragCoord) {
  return all(greaterThanEqual(fragCoord, vec2(0.0))) && all(lessThan(fragCoord, frame.viewportSize.xy));
}

// The depth-buffer value written with gl_FragDepth: eye depth over the far plane's, so a 32-bit float depth
// buffer orders surfaces with float's own relative precision from the near to the far plane, as finely as the
// eye depths themselves. (A logarithm did the same coarser, and cost the dam break's impostor layers about
// 5 % of its frame on llvmpipe: docs/frame-cost.md.)
float depthBufferFromEyeDepth(float eyeDepth) { return clamp(eyeDepth * frame.clipPlanes.z, 0.0, 1.0); }
