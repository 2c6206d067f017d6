#version 450 core
// Rim normals (docs/liquid.md, "Rim normals"): the front layer's normals within kRimReach pixels of a
// silhouette, turned towards the circle the front and back layers give there. At a round body's silhouette
// the normal is perpendicular to the view; smoothing fits planes to the inner side only and flattens the rim,
// so the normals recomputed from its depth face the camera too much, and a path that enters there bends too
// little and is trapped inside the body. A cross-section through the rim is taken as a circle: half the
// thickness h at a distance d from the edge gives its radius rho = (h^2 + d^2) / 2d and the normal's parts
// along the rim's outward direction and towards the camera, (rho - d) : h. Where the thickness grows as an
// edge's does (a box seen past its side, in proportion to d, not as a contour's square root), the front and
// back do not mirror each other as a contour's do, a solid lies just behind the liquid's edge (a tank's wall
// ends the pool's surface there) or the edge is a Mantaflow domain's wall (the liquid is cut there, flat),
// the normal is kept.
#include "lib/frame.glsl"
#include "lib/depth_layer.glsl"
#include "lib/rim.glsl"
#include "lib/domain_box.glsl"

layout(binding = 0) uniform sampler2D frontEyeDepth;
layout(binding = 1) uniform sampler2D frontNormal;    // world normal, coverage in w
layout(binding = 2) uniform sampler2D backEyeDepth;
layout(binding = 3) uniform sampler2D solidEyeDepth;  // the background's solids
layout(binding = 4) uniform sampler2D edgeRows;       // rim_edge_rows.frag's offsets

uniform float particleRadius;

layout(location = 0) out vec4 outNormal;  // xyz: world normal, w: coverage

// The pixels inwards from the edge at which the thickness's growth is sampled: past the lattice's bumps (a
// liquid's particles lie 4 to 5 pixels apart on the benchmark's bodies) and within the rim.
const float kGrowthStep = 6.0;
// The growth exponent of the half thickness with the distance from the edge, h ~ d^k: 0.5 on a smooth
// contour, 1 past a straight edge. Measured on the light benchmark's bodies after smoothing: the ball's rim
// 0.3 to 0.55 (median by distance), the block's edges 0.5 to 0.85.
const float kContourGrowthHigh = 0.62;
const float kContourGrowthLow = 0.15;
const float kGrowthBlend = 0.1;
// How far the front moves inwards for each step of the back's, on a contour 1 (below).
const float kMirroredLow = 0.4;
const float kMirroredHigh = 1.6;
const float kMirroredBlend = 0.2;
// A solid this far behind the liquid's back (as a share of its depth) at the edge ends the liquid against it.
const float kSolidBehindShare = 0.2;

// Distance from a camera-space point to the nearest wall of the domain's box (infinite without one).
float distanceToDomainWall(vec3 position) {
  if (!hasDomain) return 1e30;
  vec3 inBox = inDomainBox(position);
  vec3 toWalls = min(inBox - domainLow, domainHigh - inBox);
  return min(toWalls.x, min(toWalls.y, toWalls.z));
}

// The front and back depth at a pixel; (0, 0) where either layer is empty.
vec2 bodyDepths(ivec2 pixel) {
  vec2 depths = vec2(texelAt(frontEyeDepth, pixel).r, texelAt(backEyeDepth, pixel).r);
  return hasSurface(depths.x) && hasSurface(depths.y) ? depths : vec2(0.0);
}

void main() {
  ivec2 pixel = ivec2(gl_FragCoord.xy);
  vec4 normal = texelAt(frontNormal, pixel);
  outNormal = normal;
  vec2 depths = bodyDepths(pixel);
  float frontDepth = depths.x, backDepth = depths.y;
  float h = 0.5 * (backDepth - frontDepth);
  if (normal.w == 0.0 || !(h > 0.0)) return;
  // The nearest uncovered pixel: each row holds its own nearest, so the nearest in the plane minimises
  // dx^2 + dy^2 over the rows.
  float nearestSquared = float(kRimReach * kRimReach) + 0.5;
  vec2 towards = vec2(0.0);
  for (int dy = -kRimReach; dy <= kRimReach; ++dy) {
    float dx = texelAt(edgeRows, pixel + ivec2(0, dy)).r;
    float squared = dx * dx + float(dy * dy);
    if (squared < nearestSquared) {
      nearestSquared = squared;
      towards = vec2(dx, float(dy));
    }
  }
  if (towards == vec2(0.0)) return;
  // The edge lies between the last covered pixel's centre and the first uncovered one's.
  float edgePixels = max(sqrt(nearestSquared) - 0.5, 0.5);
  ivec2 inwardStep = ivec2(round(-normalize(towards) * kGrowthStep));
  vec2 inward = bodyDepths(pixel + inwardStep);
  float inwardH = 0.5 * (inward.y - inward.x);
  if (!(inwardH > h)) return;
  float growth = log(inwardH / h) / log((edgePixels + length(vec2(inwardStep))) / edgePixels);
  // Inwards from a contour the front comes towards the camera as far as the back goes away from it; past an
  // edge the two faces need not (a slab's end face seen from above: its back, the bottom face, moves, its
  // front hardly). The light benchmark's ball measured 0.63 to 1.1 (10th to 90th percentile), the block's
  // edges that pass the growth test 0.2 to 6, a slab's end face -5 to 11.
  if (!(inward.y > backDepth)) return;
  float mirrored = (frontDepth - inward.x) / (inward.y - backDepth);
  float weight = clamp((kContourGrowthHigh - growth) / kGrowthBlend, 0.0, 1.0) *
                 clamp((growth - kContourGrowthLow) / kGrowthBlend, 0.0, 1.0) *
                 clamp((mirrored - kMirroredLow) / kMirroredBlend, 0.0, 1.0) *
                 clamp((kMirroredHigh - mirrored) / kMirroredBlend, 0.0, 1.0);
  float solidBeyond = texelAt(solidEyeDepth, pixel + ivec2(towards)).r;
  if (solidBeyond < (1.0 + kSolidBehindShare) * backDepth) weight = 0.0;
  if (!(weight > 0.0)) return;

  float pixelSize = 2.0 * frame.tanHalfFov.y * frontDepth * frame.viewportSize.w;
  float d = edgePixels * pixelSize;
  float rho = (h * h + d * d) / (2.0 * d);
  if (!(d < rho)) return;  // past the circle's widest point: the body is thin here, not round
  vec3 ray = cameraRayFromFragCoord(gl_FragCoord.xy);
  vec3 towardsCamera = -normalize(ray);
  vec3 own = normalize(mat3(frame.cameraFromWorld) * normal.xyz);
  // The edge lies d from the pixel on the screen, d / cos along a surface seen at an angle (a pool's, from an
  // oblique camera). Twice that and a few radii and pixels more take in the smoothing's shift, the mesh's
  // inset and a surface that rises towards the wall: on the examples' pools a margin of once that and two
  // radii and pixels left 10 to 20 % of the far edge's pixels bent, each 5 degrees further from Cycles' normal.
  // A body cut by the wall behind it (a dome against the domain's side, a pool over its floor) has its back on
  // the wall however far smoothing drew the rim's front towards the camera (6 radii on such a dome).
  float alongSurface = d / max(abs(dot(own, towardsCamera)), 0.1);
  float margin = 2.0 * (pixelSize + particleRadius);
  if (distanceToDomainWall(ray * frontDepth) < 2.0 * alongSurface + 2.0 * margin ||
      distanceToDomainWall(ray * backDepth) < margin)
    return;
  // The rim's outward direction: the smoothed normal's own part across the view, which follows the contour;
  // the direction to the edge pixel is quantised to the pixel grid (twice the angle error at the rim).
  vec3 across = own - dot(own, towardsCamera) * towardsCamera;
  if (dot(across, across) < 1e-4) {
    vec3 screen = vec3(normalize(towards), 0.0);
    across = screen - dot(screen, towardsCamera) * towardsCamera;
  }
  vec3 circle = normalize((rho - d) * normalize(across) + h * towardsCamera);
  vec3 bent = mix(own, circle, weight);
  float bentLength = length(bent);
  if (!(bentLength > 1e-6) || isinf(bentLength)) return;
  outNormal = vec4(normalize(mat3(frame.worldFromCamera) * (bent / bentLength)), 1.0);
}
