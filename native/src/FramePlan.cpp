#include "FramePlan.h"

#include <algorithm>

namespace spindrift {

const char* passName(Pass pass) {
  switch (pass) {
    case Pass::Background:
      return "background";
    case Pass::OccluderDepth:
      return "occluder_depth";
    case Pass::LiquidMeshDepth:
      return "liquid_mesh_depth";
    case Pass::SplashDepthLayers:
      return "splash_depth_layers";
    case Pass::AggregateDepthLayers:
      return "aggregate_depth_layers";
    case Pass::Smoothing:
      return "smoothing";
    case Pass::Refraction:
      return "refraction";
    case Pass::FoamSceneDepth:
      return "foam_scene_depth";
    case Pass::FoamDepth:
      return "foam_depth";
    case Pass::FoamThickness:
      return "foam_thickness";
    case Pass::FoamIntensity:
      return "foam_intensity";
    case Pass::FoamOcclusion:
      return "foam_occlusion";
    case Pass::FoamBlur:
      return "foam_blur";
    case Pass::Composite:
      return "composite";
  }
  return "unknown";
}

bool FramePlan::runs(Pass pass) const {
  return std::find(passes.begin(), passes.end(), pass) != passes.end();
}

FramePlan planFrame(const FrameContents& contents) {
  FramePlan plan;
  // A pass runs when `reason` is empty; otherwise it is listed as skipped with that reason.
  auto decide = [&plan](Pass pass, const char* reason) {
    if (reason)
      plan.skipped.push_back({passName(pass), reason});
    else
      plan.passes.push_back(pass);
  };
  const bool splashes = contents.splashParticles > 0;
  const bool aggregates = contents.aggregateParticles > 0;
  decide(Pass::Background, nullptr);
  decide(Pass::OccluderDepth, contents.occluderMeshes > 0 ? nullptr : "no occluders");
  decide(Pass::LiquidMeshDepth, contents.liquidMesh ? nullptr : "no liquid mesh");
  decide(Pass::SplashDepthLayers, splashes ? nullptr : "no splash particles in view");
  decide(Pass::AggregateDepthLayers, aggregates ? nullptr : "no aggregate particles in view");
  decide(Pass::Smoothing, !aggregates                    ? "no aggregate particles in view"
                          : contents.smoothing == "none" ? "liquid.smoothing is none"
                                                         : nullptr);
  decide(Pass::Refraction, splashes || aggregates ? nullptr : "no liquid particles in view");
  const char* noFoam = contents.foamParticles > 0 ? nullptr : "no foam particles in view";
  for (Pass pass : {Pass::FoamSceneDepth, Pass::FoamDepth, Pass::FoamThickness, Pass::FoamIntensity,
                    Pass::FoamOcclusion, Pass::FoamBlur})
    decide(pass, noFoam);
  decide(Pass::Composite, nullptr);
  return plan;
}

}  // namespace spindrift
