// SCRATCH (not committed): every visible particle as a splash sphere.
#include "prep/LiquidPreparation.h"
#include "prep/VisibleSpheres.h"
namespace spindrift {
LiquidPreparation prepareLiquid(const Particles& particles, const Camera& camera, const LiquidParameters&) {
  LiquidPreparation result;
  const VisibleSpheres visible = visibleSpheres(particles, ParticleKind::Liquid, camera);
  result.culled = visible.culled;
  for (const glm::vec4& s : visible.spheres) {
    EllipsoidInstance e{};
    e.centreAndBoundingRadius = s;
    for (int i = 0; i < 3; ++i) { e.inverseAxesRows[i] = glm::vec4(0); e.inverseAxesRows[i][i] = 1.0f / s.w; }
    result.splashes.push_back(e);
  }
  return result;
}
}
