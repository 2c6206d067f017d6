#version 450 core
// The liquid's colour: up to four refractions through the splash and aggregate depth layers, found by
// screen-space marching with secant refinement, Schlick Fresnel reflections, total internal reflection and
// Beer-Lambert absorption along the path in liquid (liquid paper, sections 4.4 and 4.5, equations 6-9).
#include "lib/frame.glsl"
#include "lib/environment.glsl"
#include "lib/optics.glsl"
#include "lib/screen_trace.glsl"
#include "lib/domain_box.glsl"

// The four layers' normals, layer = body * 2 + back (splash front, splash back, aggregate front, aggregate
// back; refraction_layers.frag copies them): one fetch where a choice among four textures fetched all four.
layout(binding = 4) uniform sampler2DArray layerNormals;
layout(binding = 8) uniform sampler2D backgroundColor;
layout(binding = 9) uniform sampler2D backgroundEyeDepth;
layout(binding = 10) uniform sampler2D environmentMap;
// The four depth layers, one texel per pixel: splash front, splash back, aggregate front, aggregate back
// (refraction_layers.frag packs them). The marches read them through frontDepth and backDepth.
layout(binding = 11) uniform sampler2D layerDepths;

// Counts of rays by what they met, for the frame's stats (see RefractionPass::Statistics).
layout(std430, binding = 1) buffer RayCounters {
  uint rayCounters[9];  // 0-3: paths splash>splash, splash>aggregate, aggregate>splash, aggregate>aggregate;
                        // 4: rays with a second body; 5: total internal reflections; 6: liquid pixels;
                        // 7: marches inside a body that left the screen before its far surface;
                        // 8: marches inside a body that passed behind a solid hiding it
};

uniform bool hasSplash;
uniform bool hasAggregate;
uniform bool hasEnvironment;
uniform vec3 fallbackColor;
uniform float indexOfRefraction;
uniform vec3 absorptionPerUnitLength;  // a * c_a of equation 9, per RGB channel
uniform int maxRefractions;            // 1, 2 or 4
// Surface meetings a path may spend on total internal reflection besides the four its refractions take: light
// trapped in a sheet of water by total internal reflection travels on along it, absorbed all the way.
uniform int maxInternalReflections;
uniform float reflectionStepPixels;    // screen distance between samples of the marches reflections take
// The camera is inside the aggregated body (under water): every ray starts in liquid, the body's front is the
// near plane and the first surface a ray meets is the body's back layer, the liquid's surface seen from below.
uniform bool cameraInLiquid;
uniform float solidContactDistance;  // two particle radii: a solid this close behind the drawn back touches it
// A Mantaflow domain's box (lib/domain_box.glsl): beyond it lies air between the liquid and whatever solid is
// there (the domain's floor), so a solid outside it never touches the liquid.

// What a solid in the liquid, lit from above it, is seen with: its lit radiance divided by n^2, from air and
// from inside the liquid alike. This is the convention of the path tracer the layers composite over: Cycles
// keeps a ray's radiance where it refracts, so light that enters the water reaches a submerged solid with
// 1 / n^2 of the irradiance physics gives it (its solid angle narrows by n^2 with no gain in radiance), and
// the sky seen through the surface from below keeps its radiance, as the crossings below keep it. Seen from
// air the two conventions agree (physics loses the same 1 / n^2 on the way out); seen from inside the water
// only this one makes a submerged floor and the sky in Snell's window agree with each other and with the
// user's render (docs/liquid.md, "A camera under water").
float submergedSolidDivisor() { return indexOfRefraction * indexOfRefraction; }

layout(location = 0) out vec4 outLiquid;       // premultiplied RGBA over transparent
layout(location = 1) out vec4 outSplash;       // the same, where the first surface is a splash
layout(location = 2) out float outClass;       // 0 background, 1 splash, 2 aggregate
layout(location = 3) out float outThickness;   // path length in liquid
layout(location = 4) out float outFrontDepth;  // eye depth of the first surface; 1e10 where none
layout(location = 5) out vec4 outFrontNormal;  // world normal of the first surface, coverage

// The refraction split for a compositor that refracts another render of the background (Blender's Map UV):
// liquid = background(uv) * transmittance + reflection. Images, not attachments: the framebuffer already has
// six of the eight draw buffers GL guarantees. Every pixel writes all three.
layout(rgba32f, binding = 0) uniform writeonly image2D refractionUvImage;  // u, v (0..1, bottom left), looked up, stand-in
layout(rgba32f, binding = 1) uniform writeonly image2D transmittanceImage; // of that background colour, to the eye
layout(rgba32f, binding = 2) uniform writeonly image2D reflectionImage;    // every other light of the pixel

#include "lib/layer_marches.glsl"

void main() {
  ivec2 pixel = ivec2(gl_FragCoord.xy);
  vec3 viewDirection = normalize(cameraRayFromFragCoord(gl_FragCoord.xy));
  vec4 drawnDepths = texelAt(layerDepths, pixel);
  float splashDepth = hasSplash ? drawnDepths.x : kNoSurfaceDepth;
  float aggregateDepth = hasAggregate ? drawnDepths.z : kNoSurfaceDepth;
  float firstDepth = min(splashDepth, aggregateDepth);
  outLiquid = vec4(0.0);
  outSplash = vec4(0.0);
  outClass = 0.0;
  outThickness = 0.0;
  outFrontDepth = kNoSurfaceDepth;
  outFrontNormal = vec4(0.0);
  imageStore(refractionUvImage, pixel, vec4(0.0));
  imageStore(transmittanceImage, pixel, vec4(0.0));
  imageStore(reflectionImage, pixel, vec4(0.0));
  bool underLiquid = cameraInLiquid && hasAggregate;
  if (firstDepth >= kNoSurfaceDepth * 0.5 && !underLiquid) return;
  atomicAdd(rayCounters[6], 1u);

  // Equations 6-8 unrolled into a running sum: colour += throughput * F_k * b(r_k), throughput *= 1 - F_k, and
  // Beer-Lambert (equation 9) multiplies the throughput by exp(-a c_a l) for every segment in liquid.
  vec3 colour = vec3(0.0);
  vec3 throughput = vec3(1.0);
  vec3 direction = viewDirection;
  float pathInLiquid = 0.0;
  int refractions = 0;
  bool inside = false;
  int secondBody = -1;
  ivec2 entryPixel = pixel;  // where the path last entered a body, for the thickness of an unseen remainder
  vec2 hiddenEndTexel = vec2(-1.0);  // the background texel that stands in for an end hidden behind a solid
  float ignoredDistance = 0.0;
  // Where the last search for a second body passed behind the solids, when it found no body.
  SolidHit solidBehind;
  solidBehind.found = false;
  bool searchedBehind = false;
  int body, firstBody;
  vec3 position, normal;
  if (underLiquid) {
    // Under water the whole view is liquid. The path runs from the eye through liquid to the body's back
    // layer, the surface seen from below, unless a solid comes first: then the pixel is that solid, absorbed,
    // seen as a submerged solid is.
    body = firstBody = kAggregate;
    float surfaceDepth = backDepth(kAggregate, pixel);
    float solidDepth = texelAt(backgroundEyeDepth, pixel).r;
    float endDepth = min(min(surfaceDepth, solidDepth), getFarClip());
    pathInLiquid = endDepth / -viewDirection.z;
    throughput = exp(-absorptionPerUnitLength * pathInLiquid);
    outClass = 2.0;
    outThickness = pathInLiquid;
    if (!(surfaceDepth < solidDepth && surfaceDepth < getFarClip())) {
      bool seesSolid = solidDepth < getFarClip();
      throughput /= submergedSolidDivisor();
      vec3 seen = seesSolid ? texelAt(backgroundColor, pixel).rgb : vec3(0.0);
      vec4 ownUv = vec4(gl_FragCoord.xy * frame.viewportSize.zw, 1.0, 0.0);
      imageStore(refractionUvImage, pixel, seesSolid ? ownUv : vec4(0.0));
      imageStore(transmittanceImage, pixel, vec4(seesSolid ? throughput : vec3(0.0), 0.0));
      outLiquid = vec4(throughput * seen, 1.0);
      return;
    }
    position = viewDirection * (surfaceDepth / -viewDirection.z);
    inside = true;
    outFrontDepth = surfaceDepth;
  } else {
    body = firstBody = splashDepth <= aggregateDepth ? kSplash : kAggregate;
    position = viewDirection * (firstDepth / -viewDirection.z);
    outFrontDepth = firstDepth;
  }
  // The first surface's normal, one lookup for both cases (as in the loop below): under water the body's back
  // layer, the surface seen from below.
  normal = surfaceNormal(body, underLiquid, gl_FragCoord.xy);
  if (dot(normal, normal) == 0.0) normal = underLiquid ? viewDirection : -viewDirection;
  // The normal pass shows the side that faces the camera, as Cycles' does for a surface seen from behind.
  outFrontNormal =
      vec4(mat3(frame.worldFromCamera) * (underLiquid && dot(normal, viewDirection) > 0.0 ? -normal : normal), 1.0);
  // Every meeting with a surface is a crossing: up to four refractions (into a body, out, into a second, out)
  // and the total internal reflections between them. A path whose crossings are spent inside the liquid sees
  // straight on from the surface it last met.
  bool metBack;  // the side and place of the surface each crossing meets, for its normal
  vec2 metAt;
  for (int crossing = 0; crossing < 4 + maxInternalReflections; ++crossing) {
    // The normal faces the side the ray comes from.
    vec3 facing = dot(normal, direction) < 0.0 ? normal : -normal;
    float cosine = -dot(facing, direction);
    float indexRatio = inside ? indexOfRefraction : 1.0 / indexOfRefraction;
    vec3 refracted = refract(direction, facing, indexRatio);
    bool totalInternalReflection = dot(refracted, refracted) == 0.0;
    vec3 reflected = reflect(direction, facing);
    if (totalInternalReflection) {
      // All light is reflected back into the liquid: the path travels on inside the body along the
      // reflection, to its next meeting with the surface, within the loop's budget of crossings.
      atomicAdd(rayCounters[5], 1u);
      direction = reflected;
    } else {
      // Schlick's cosine is taken on the rarer (air) side, which is the refracted side when leaving.
      float fresnel = schlickFresnel(inside ? -dot(refracted, facing) : cosine, indexOfRefraction);
      // Under water the light reflected at the surface from below crosses the liquid to the solid it comes
      // from, a submerged one; inside a body seen from outside the reflection's path in liquid is short and
      // left out.
      float reflectedDistance;
      vec2 reflectedTexel;
      // Fresnel weights it by a few per cent: a coarser march than the refraction's (docs/frame-cost.md).
      vec3 reflectedColour = colourAlong(position, reflected, reflectionStepPixels, reflectedTexel, reflectedDistance);
      if (inside && underLiquid)
        reflectedColour *= exp(-absorptionPerUnitLength * reflectedDistance) /
                           (reflectedTexel.x >= 0.0 ? submergedSolidDivisor() : 1.0);
      colour += throughput * fresnel * reflectedColour;
      throughput *= 1.0 - fresnel;
      direction = refracted;
      ++refractions;
      inside = !inside;
    }
    if (inside) {
      Crossing exit = findExit(position, direction, body);
      float length = exit.t;  // Where the liquid ends, or where a march that never left it stopped.
      if (!exit.found) {
        atomicAdd(rayCounters[exit.hidden ? 8 : 7], 1u);
        // The march left the screen, or passed behind a solid, inside the liquid. The unseen rest of the path
        // is estimated from the body's thickness where the path entered it: a path through a body that thick
        // along this direction is (back - front) / |cos| long, of which `length` was seen.
        float thicknessHere = max(backDepth(body, entryPixel) - frontDepth(body, entryPixel), 0.0);
        length = max(length, thicknessHere / max(abs(direction.z), 0.2));
      }
      pathInLiquid += length;
      throughput *= exp(-absorptionPerUnitLength * length);
      if (exit.hidden) {
        // A path that goes on behind a solid hiding the liquid (under a tank's rim) ends on a submerged
        // surface no view shows: it is seen as a submerged solid is, and what stands in for it is the
        // background where the path was last seen in the liquid, the container behind the water (not the
        // solid in front of the path, whose outside faces the camera).
        position += exit.t * direction;
        throughput /= submergedSolidDivisor();
        hiddenEndTexel = exit.fragCoord;
        break;
      }
      if (exit.found && exit.solid) {
        // The path ends on a solid inside the liquid (a pool's floor, a stone under water), seen from air
        // through the surface the path entered by or, under water, from inside the liquid.
        position += exit.t * direction;
        throughput /= submergedSolidDivisor();
        break;
      }
      if (!exit.found || refractions >= maxRefractions) {
        // One refraction, or a march that left the screen: the light behind comes straight through.
        position += exit.t * direction;
        break;
      }
      position += exit.t * direction;
      metBack = exit.back;
      metAt = exit.fragCoord;
    } else {
      if (refractions >= maxRefractions) break;
      Crossing entry = findEntry(position, direction, solidBehind);
      if (!entry.found) {
        searchedBehind = true;
        break;
      }
      secondBody = entry.body;
      atomicAdd(rayCounters[4], 1u);
      position += entry.t * direction;
      body = entry.body;
      entryPixel = ivec2(entry.fragCoord);
      metBack = entry.back;
      metAt = entry.fragCoord;
    }
    // The surface met, looked up once for both branches: llvmpipe would run both lookups (20 texel fetches
    // each) for every pixel of the group. Where the layer has no normal the ray goes on as it was, out of the
    // body it was in (direction) or into the one it met (-direction) once the normal is turned to face it.
    normal = surfaceNormal(body, metBack, metAt);
    if (dot(normal, normal) == 0.0) normal = inside ? direction : -direction;
  }
  // The last lookup is the background the compositor refracts, when it is one; all else is reflected light.
  vec2 finalTexel = hiddenEndTexel;
  vec3 finalColour = vec3(0.0);
  if (hiddenEndTexel.x >= 0.0)
    finalColour = texelAt(backgroundColor, ivec2(hiddenEndTexel)).rgb;
  else if (dot(throughput, throughput) > 0.0) {
    // A path whose search for a second body found none has marched this very ray already. One colourBehind
    // for both: llvmpipe would run a ternary's two calls, and so two secant refinements, for every pixel.
    SolidHit solid = solidBehind;
    if (!searchedBehind) solid = solidAlong(position, direction, stepPixels, ignoredDistance);
    finalColour = colourBehind(position, direction, solid, finalTexel, ignoredDistance);
  }
  bool seesBackground = finalTexel.x >= 0.0;
  // A: the texel only stands in for an end hidden behind a solid, so refraction_footprint.frag does not
  // average about it (not read back).
  imageStore(refractionUvImage, pixel,
             seesBackground ? vec4(finalTexel * frame.viewportSize.zw, 1.0, hiddenEndTexel.x >= 0.0 ? 1.0 : 0.0)
                            : vec4(0.0));
  imageStore(transmittanceImage, pixel, vec4(seesBackground ? throughput : vec3(0.0), 0.0));
  imageStore(reflectionImage, pixel, vec4(seesBackground ? colour : colour + throughput * finalColour, 0.0));
  colour += throughput * finalColour;
  if (secondBody >= 0) atomicAdd(rayCounters[firstBody * 2 + secondBody], 1u);

  outLiquid = vec4(colour, 1.0);
  outSplash = firstBody == kSplash ? outLiquid : vec4(0.0);
  outClass = firstBody == kSplash ? 1.0 : 2.0;
  outThickness = pathInLiquid;
}
