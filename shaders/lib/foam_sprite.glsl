// The fragment side of a foam sprite (foam paper 2.1): a camera-facing disc whose depth is pushed towards
// the camera to the sphere's, so sprites overlap as spheres do. Pairs with foam_sprite.vert.

in vec2 vSpriteCoord;         // (u, v) over the sprite: the disc is u^2 + v^2 <= 1
flat in vec3 vCameraCentre;   // camera-space centre
flat in float vRadius;        // drawn world radius r_i
flat in int vFoamType;        // 0 spray, 1 surface foam, 2 bubble
flat in float vAge;           // normalised age l
flat in float vSearchRadius;  // h_i = r_i / (tan(alpha / 2) |e_z|)

struct FoamSpriteFragment {
  float distanceFromCentre;  // x of the falloffs: |(u, v)|
  float eyeDepth;            // planar eye depth of the sphere's front at this fragment
  vec3 cameraNormal;         // (u, v, w), w = sqrt(1 - u^2 - v^2)
};

// False outside the sprite's circle.
bool foamSpriteFragment(out FoamSpriteFragment fragment) {
  float squared = dot(vSpriteCoord, vSpriteCoord);
  if (squared > 1.0) return false;
  float w = sqrt(1.0 - squared);
  fragment.distanceFromCentre = sqrt(squared);
  // The paper's e_z + w r_i with e_z negative in front of the camera: nearer by w r_i in planar depth.
  fragment.eyeDepth = -vCameraCentre.z - w * vRadius;
  fragment.cameraNormal = vec3(vSpriteCoord, w);
  return fragment.eyeDepth > getNearClip();
}
