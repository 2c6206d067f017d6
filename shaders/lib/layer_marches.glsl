// The refraction's lookups in the four depth layers (a body's front and back depth and normal at a pixel or
// between pixels) and its screen-space marches through them: where a ray leaves the body it is in, enters the
// next body or meets a solid, each crossing bracketed by the march and refined by the secant method, and the
// colour a ray sees where it leaves everything the layers hold. Included by refraction.frag alone, after its
// samplers, uniforms and outputs, which these read; requires lib/frame.glsl, lib/environment.glsl and
// lib/screen_trace.glsl.

const int kSplash = 0;
const int kAggregate = 1;

// A body's front and back depth in one texel of the packed layers.
vec2 bodyDepths(int body, vec4 packedDepths) {
  vec2 depths = body == kSplash ? packedDepths.xy : packedDepths.zw;
  if (body == kAggregate && cameraInLiquid) depths.x = getNearClip();
  return depths;
}
// A body's front and back depth at a pixel.
vec2 texelDepths(int body, ivec2 pixel) { return bodyDepths(body, texelAt(layerDepths, pixel)); }
float frontDepth(int body, ivec2 pixel) { return texelDepths(body, pixel).x; }
float backDepth(int body, ivec2 pixel) { return texelDepths(body, pixel).y; }
vec4 normalTexel(int body, bool back, ivec2 pixel) {
  return texelAt(layerNormals, ivec3(pixel, body * 2 + (back ? 1 : 0)));
}

// A body's front and back depth between texel centres, both from the same four texels of the packed layers:
// fetched once for both, which llvmpipe did not share between two calls (the refraction pass 40-42 -> 35-37
// ms on the dam break). Where one of the four texels has no surface in a layer (a silhouette) that layer takes
// the nearest texel instead, so depth is never blended with "nothing here".
vec2 interpolatedDepths(int body, vec2 fragCoord) {
  ivec2 base;
  vec2 weight;
  bilinearFootprint(fragCoord, base, weight);
  vec2 d00 = texelDepths(body, base), d10 = texelDepths(body, base + ivec2(1, 0));
  vec2 d01 = texelDepths(body, base + ivec2(0, 1)), d11 = texelDepths(body, base + ivec2(1, 1));
  vec2 nearest = texelDepths(body, ivec2(fragCoord));
  vec2 blended = mix(mix(d00, d10, weight.x), mix(d01, d11, weight.x), weight.y);
  const float gap = kNoSurfaceDepth * 0.5;
  bool frontGap = any(greaterThanEqual(vec4(d00.x, d10.x, d01.x, d11.x), vec4(gap)));
  bool backGap = any(greaterThanEqual(vec4(d00.y, d10.y, d01.y, d11.y), vec4(gap)));
  return vec2(frontGap ? nearest.x : blended.x, backGap ? nearest.y : blended.y);
}

// Outward camera-space normal of a body's front or back surface, interpolated like interpolatedDepths; zero where the
// layer has none.
vec3 surfaceNormal(int body, bool back, vec2 fragCoord) {
  ivec2 base;
  vec2 weight;
  bilinearFootprint(fragCoord, base, weight);
  vec4 n00 = normalTexel(body, back, base), n10 = normalTexel(body, back, base + ivec2(1, 0));
  vec4 n01 = normalTexel(body, back, base + ivec2(0, 1)), n11 = normalTexel(body, back, base + ivec2(1, 1));
  vec4 normal = (n00.w * n10.w * n01.w * n11.w > 0.0)
                    ? mix(mix(n00, n10, weight.x), mix(n01, n11, weight.x), weight.y)
                    : normalTexel(body, back, ivec2(fragCoord));
  return normal.w > 0.0 ? normalize(mat3(frame.cameraFromWorld) * normal.xyz) : vec3(0.0);
}
bool bodyPresent(int body) { return body == kSplash ? hasSplash : hasAggregate; }

// How far inside a body the eye depth z is, given the body's front and back depth there and the solid's:
// positive inside, negative outside; `back` says which boundary is nearer. The background's solids cut the
// body: nothing lies inside past them.
float insideDistanceBetween(vec2 depths, float solidDepth, float z, out bool back) {
  // Set on every path: an out parameter left unwritten is undefined (a crossing refined onto a pixel without
  // the layer would take its normal from either side).
  back = false;
  if (depths.x >= kNoSurfaceDepth * 0.5) return -1e30;
  float rear = min(depths.y, solidDepth);
  back = rear - z < z - depths.x;
  return min(z - depths.x, rear - z);
}
// The same at a window position. `interpolated` selects bilinear depth (for refinement) over the nearest
// texel (for marching).
float insideDistance(int body, vec2 fragCoord, float z, bool interpolated, out bool back) {
  ivec2 pixel = ivec2(fragCoord);
  vec2 depths = interpolated ? interpolatedDepths(body, fragCoord) : texelDepths(body, pixel);
  return insideDistanceBetween(depths, texelAt(backgroundEyeDepth, pixel).r, z, back);
}

struct Crossing {
  bool found;
  float t;
  int body;
  bool back;   // crossed the body's back boundary
  bool solid;  // that boundary is a solid inside the body (a pool's floor), not the liquid's back surface
  bool hidden;  // not found: the ray passed behind a solid that hides the body (a tank's near wall)
  vec2 fragCoord;
};

// Where a march outside the liquid first passed behind the background's solids: the samples on both sides of
// the crossing, for the secant refinement. findEntry records it as it searches for a second body, so a path
// that finds none does not march the same ray again for the colour behind it (colourBehind).
struct SolidHit {
  bool found;
  float previousT, previousF, t, f;
};

// A depth difference along the ray whose sign change marks the crossing being searched for.
const int kInsideBody = 0;      // f = distance inside the body (positive inside): leaving it
const int kBehindFront = 1;     // f = z - front depth of the body: passing behind its front surface
const int kBehindSolid = 2;     // f = z - background depth: meeting a solid

// The crossing functions of kBehindFront and kInsideBody at eye depth z, given the depths there. Where the
// body has no layer, a pixel's size outside it: negative, and no sharper a step than the march can bracket.
float behindFront(float front, float z) { return front >= kNoSurfaceDepth * 0.5 ? -pixelSizeAt(z) : z - front; }
float insideBody(vec2 depths, float solidDepth, float z) {
  bool back;
  float f = insideDistanceBetween(depths, solidDepth, z, back);
  return f < -1e29 ? -pixelSizeAt(z) : f;
}

float crossingFunction(int kind, int body, vec3 origin, vec3 direction, float t, bool interpolated) {
  vec3 position = origin + t * direction;
  vec2 fragCoord = clamp(fragCoordFromCamera(position), vec2(0.0), frame.viewportSize.xy - 1.0);
  float z = -position.z;
  float solidDepth = texelAt(backgroundEyeDepth, ivec2(fragCoord)).r;
  if (kind == kBehindSolid) return z - solidDepth;
  vec2 depths = interpolated ? interpolatedDepths(body, fragCoord) : texelDepths(body, ivec2(fragCoord));
  return kind == kBehindFront ? behindFront(depths.x, z) : insideBody(depths, solidDepth, z);
}

// The secant method, kept bracketed (the Illinois variant of regula falsi), between two parameters whose
// crossing function differs in sign.
float refineCrossing(int kind, int body, vec3 origin, vec3 direction, float tA, float fA, float tB, float fB) {
  float t = tB;
  int retained = 0;
  for (int i = 0; i < 10; ++i) {
    t = (abs(fB - fA) > 1e-30) ? tB - fB * (tB - tA) / (fB - fA) : 0.5 * (tA + tB);
    t = clamp(t, min(tA, tB), max(tA, tB));
    float f = crossingFunction(kind, body, origin, direction, t, true);
    if (sign(f) == sign(fB)) {
      tB = t;
      fB = f;
      if (retained == -1) fA *= 0.5;  // A stayed twice: halve its weight so the bracket closes from both ends.
      retained = -1;
    } else {
      tA = t;
      fA = f;
      if (retained == 1) fB *= 0.5;
      retained = 1;
    }
  }
  return t;
}

Crossing crossingAt(int body, vec3 origin, vec3 direction, float t) {
  Crossing crossing;
  crossing.found = true;
  crossing.hidden = false;
  crossing.body = body;
  crossing.t = t;
  crossing.fragCoord = clamp(fragCoordFromCamera(origin + t * direction), vec2(0.0), frame.viewportSize.xy - 1.0);
  vec2 depths = interpolatedDepths(body, crossing.fragCoord);
  float solidDepth = texelAt(backgroundEyeDepth, ivec2(crossing.fragCoord)).r;
  insideDistanceBetween(depths, solidDepth, rayEyeDepth(origin, direction, t), crossing.back);
  // A solid that the body's drawn back lies on (within solidContactDistance, the bottom's undulation), or
  // that lies in front of it, ends the path there.
  float drawnBack = depths.y;
  crossing.solid = crossing.back && drawnBack < kNoSurfaceDepth * 0.5 && solidDepth < drawnBack + solidContactDistance;
  if (crossing.solid && hasDomain) {
    // Where the ray meets the solid (its planar depth grows by -direction.z per unit).
    float toSolid = -direction.z > 1e-6 ? (solidDepth + origin.z) / -direction.z : t;
    vec3 inBox = inDomainBox(origin + toSolid * direction);
    crossing.solid = all(greaterThan(inBox, domainLow)) && all(lessThan(inBox, domainHigh));
  }
  return crossing;
}

ivec2 texelOf(vec3 position) {
  return ivec2(clamp(fragCoordFromCamera(position), vec2(0.0), frame.viewportSize.xy - 1.0));
}

// A march skips its samples that are still in the texel the ray starts in: there it compares the ray with the
// depth of the very surface it starts from, and the sign of the difference is noise. A ray just out of a body
// would "enter" it again at once (findEntry, above water and under it): through the middle of a flat slab seen
// head on, whose faces stand a particle radius out (liquid.reach_radius), 230 of its middle 256 paths crossed
// four surfaces instead of two and lost a second (1 - F)^2 (GLLiquidLayers.SlabFollowsBeerLambert); the
// dam-break example changed in 8 of 518,400 pixels. Under water a reflection from below near the screen's edge would
// also "leave" through the surface that just reflected it (findExit); above water that check is left as it
// was measured.
bool inStartTexel(vec3 origin, vec3 direction, float t, ivec2 startTexel) {
  return texelOf(origin + t * direction) == startTexel;
}

// The marches below only bracket a crossing inside their loop of samples and refine it after the loop: on
// llvmpipe the body of an `if` runs for a group of eight pixels whether or not any of them takes it, and a loop
// runs its body at least once, so a refinement written inside the loop cost a pass of its own loop and a
// crossing's interpolated lookups at every sample (docs/frame-cost.md, session 40).

// Marches from inside `body` to where the ray leaves it.
Crossing findExit(vec3 origin, vec3 direction, int body) {
  ScreenRay ray = screenRay(origin, direction);
  float previousT = 0.0, previousF = 1e-6;
  float t = 0.0, f = 1e-6;
  bool crossed = false, hidden = false;
  ivec2 startTexel = texelOf(origin);
  for (int k = 1; k <= ray.samples; ++k) {
    t = screenRaySampleT(ray, k);
    if (cameraInLiquid && inStartTexel(origin, direction, t, startTexel)) continue;
    // crossingFunction(kInsideBody, ...) with its two fetches kept for the check below: llvmpipe fetched
    // them twice.
    vec3 position = origin + t * direction;
    ivec2 texel = texelOf(position);
    vec2 depths = texelDepths(body, texel);
    float solidDepth = texelAt(backgroundEyeDepth, texel).r;
    f = insideBody(depths, solidDepth, -position.z);
    if (f < 0.0 && depths.x >= kNoSurfaceDepth * 0.5 && rayEyeDepth(origin, direction, t) > solidDepth) {
      // Where the ray is, a solid stands in front of it and the body has no layers: the solid hides the
      // liquid there (a tank's near wall hides the water below its rim), so where the path ends is not seen.
      // (Where the body has no layers the crossing function is negative, so this is checked only there.)
      hidden = true;
      break;
    }
    if (f < 0.0) {
      crossed = true;
      break;
    }
    previousT = t;
    previousF = f;
  }
  if (crossed)
    return crossingAt(body, origin, direction, refineCrossing(kInsideBody, body, origin, direction, previousT, previousF, t, f));
  Crossing none;
  none.found = false;
  none.hidden = hidden;
  // Hidden: the path was last seen in the liquid at the previous sample. Otherwise the ray left the screen
  // inside the liquid: the liquid ends where the view does.
  none.t = hidden ? previousT : t;
  none.fragCoord = hidden ? vec2(texelOf(origin + previousT * direction)) + 0.5 : vec2(0.0);
  return none;
}

// Marches from outside every body to where the ray passes behind a body's front surface while in front of its
// back surface, or until a solid stops it. The inner loop runs to the next sample that passes behind a front;
// the outer one checks that bracket and, where the ray passed behind the body instead, marches on.
// `solid`: where the ray first passed behind a solid, as colourAlong's march would find it (its samples in the
// start texel included).
Crossing findEntry(vec3 origin, vec3 direction, out SolidHit solid) {
  Crossing none;
  none.found = false;
  none.hidden = false;
  solid.found = false;
  ScreenRay ray = screenRay(origin, direction);
  float previousT = 0.0;
  vec2 previousF = vec2(-1e-6);
  float solidPreviousT = 0.0, solidPreviousF = -1.0;
  ivec2 startTexel = texelOf(origin);
  int k = 1;
  for (int bracketsChecked = 0; bracketsChecked <= maxSteps; ++bracketsChecked) {
    float t = 0.0;
    vec2 f = vec2(-1.0);
    bvec2 bracketed = bvec2(false);
    for (; k <= ray.samples; ++k) {
      t = screenRaySampleT(ray, k);
      // crossingFunction's kBehindSolid and both bodies' kBehindFront, from one fetch of each texture.
      vec3 position = origin + t * direction;
      ivec2 texel = texelOf(position);
      float z = -position.z;
      float behindSolid = z - texelAt(backgroundEyeDepth, texel).r;
      vec4 packedDepths = texelAt(layerDepths, texel);
      if (behindSolid >= 0.0 && !solid.found) solid = SolidHit(true, solidPreviousT, solidPreviousF, t, behindSolid);
      solidPreviousT = t;
      solidPreviousF = behindSolid;
      if (inStartTexel(origin, direction, t, startTexel)) continue;
      if (behindSolid >= 0.0) {
        k = ray.samples + 1;  // a solid ends the search
        break;
      }
      f = vec2(hasSplash ? behindFront(bodyDepths(kSplash, packedDepths).x, z) : -1.0,
               // Under water the aggregate's front is the near plane, so passing behind it says nothing:
               // a ray that has left the water is followed into splashes only.
               hasAggregate && !cameraInLiquid ? behindFront(bodyDepths(kAggregate, packedDepths).x, z) : -1.0);
      bracketed = bvec2(f.x >= 0.0 && previousF.x < 0.0, f.y >= 0.0 && previousF.y < 0.0);
      if (any(bracketed)) break;
      previousT = t;
      previousF = f;
    }
    if (!any(bracketed)) break;
    for (int body = 0; body < 2; ++body) {
      if (bracketed[body]) {
        float tEntry = refineCrossing(kBehindFront, body, origin, direction, previousT, previousF[body], t, f[body]);
        vec3 position = origin + tEntry * direction;
        vec2 fragCoord = clamp(fragCoordFromCamera(position), vec2(0.0), frame.viewportSize.xy - 1.0);
        // Behind the front but also in front of the back: inside, so this is an entry.
        if (-position.z <= interpolatedDepths(body, fragCoord).y) return crossingAt(body, origin, direction, tEntry);
      }
    }
    previousT = t;
    previousF = f;
    ++k;
  }
  return none;
}

// The colour behind the solid a march found (`travelled` becomes the refined distance to it), or, where it
// found none, what lies beyond the screen (`travelled` is left as it is).
vec3 colourBehind(vec3 origin, vec3 direction, SolidHit solid, out vec2 backgroundTexel, inout float travelled) {
  backgroundTexel = vec2(-1.0);
  if (solid.found) {
    float tHit = refineCrossing(kBehindSolid, 0, origin, direction, solid.previousT, solid.previousF, solid.t, solid.f);
    travelled = tHit;
    vec2 hit = clamp(fragCoordFromCamera(origin + tHit * direction), vec2(0.0), frame.viewportSize.xy - 1.0);
    backgroundTexel = hit;
    // Between texels: where a refraction magnifies the background its image is drawn smooth, as the path
    // tracer's is, not in steps of whole texels.
    return bilinearOnSurface(backgroundColor, backgroundEyeDepth, hit, -(origin + tHit * direction).z).rgb;
  }
  if (direction.z < 0.0) {
    vec2 vanishing = fragCoordFromCamera(direction * getFarClip());
    if (onScreen(vanishing) && texelAt(backgroundEyeDepth, ivec2(vanishing)).r >= kNoSurfaceDepth * 0.5) {
      backgroundTexel = vec2(ivec2(vanishing)) + 0.5;
      return texelAt(backgroundColor, ivec2(vanishing)).rgb;
    }
  }
  vec3 worldDirection = mat3(frame.worldFromCamera) * direction;
  return hasEnvironment ? texture(environmentMap, equirectangularUvFromDirection(worldDirection)).rgb : fallbackColor;
}

// colourAlong's march: where the ray first passes behind the background's solids, if it does on screen;
// `travelled` becomes the last sample's distance.
SolidHit solidAlong(vec3 origin, vec3 direction, float pixelsPerStep, out float travelled) {
  ScreenRay ray = screenRaySampledEvery(origin, direction, pixelsPerStep);
  SolidHit solid;
  solid.found = false;
  float previousT = 0.0, previousF = -1.0;
  travelled = 0.0;
  for (int k = 1; k <= ray.samples && !solid.found; ++k) {
    float t = screenRaySampleT(ray, k);
    travelled = t;
    float f = crossingFunction(kBehindSolid, 0, origin, direction, t, false);
    if (f >= 0.0) solid = SolidHit(true, previousT, previousF, t, f);
    previousT = t;
    previousF = f;
  }
  return solid;
}

// b(.) of equation 6: the colour seen from `origin` along `direction` outside the liquid: the background image
// where the ray meets a solid of its depth; a ray towards the sky sees the background image at the direction's
// vanishing point when that pixel is infinitely far; a ray that leaves the screen sees the environment (or the
// background colour). `backgroundTexel` is the window position of the background texel looked up (its
// centre), or negative when the colour came from the environment or the flat colour; `travelled` is how far
// the ray went: to the solid it met, or as far as the screen let it be followed.
vec3 colourAlong(vec3 origin, vec3 direction, float pixelsPerStep, out vec2 backgroundTexel, out float travelled) {
  SolidHit solid = solidAlong(origin, direction, pixelsPerStep, travelled);
  return colourBehind(origin, direction, solid, backgroundTexel, travelled);
}
