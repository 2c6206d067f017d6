#include "spindrift/RenderResult.h"

namespace spindrift {

const ImageLayer* RenderResult::layer(const std::string& name) const {
  for (const ImageLayer& candidate : layers)
    if (candidate.name == name) return &candidate;
  return nullptr;
}

nlohmann::json FrameStats::toJson() const {
  nlohmann::json passesJson = nlohmann::json::array();
  for (const PassTiming& pass : passes) {
    passesJson.push_back({{"name", pass.name},
                          {"gpu_ms", pass.gpuMilliseconds},
                          {"cpu_ms", pass.cpuMilliseconds},
                          {"samples_passed", pass.samplesPassed}});
  }
  nlohmann::json skippedJson = nlohmann::json::array();
  nlohmann::json raymarchJson = nullptr;  // null unless liquid.surface = raymarch
  if (raymarch.enabled)
    raymarchJson = {{"stepping", raymarch.adaptiveStepping ? "adaptive" : "uniform"},
                    {"density_particles", raymarch.densityParticles},
                    {"grid_cells", raymarch.gridCells},
                    {"rays_cast", raymarch.raysCast},
                    {"hits", raymarch.hits},
                    {"total_steps", raymarch.totalSteps},
                    {"average_steps_per_ray", raymarch.averageStepsPerRay},
                    {"density_evaluations_per_ray", raymarch.densityEvaluationsPerRay},
                    {"refinement_evaluations_per_ray", raymarch.refinementEvaluationsPerRay},
                    {"particles_visited_per_ray", raymarch.particlesVisitedPerRay},
                    {"tiles",
                     {{"full", raymarch.tiles[0]},
                      {"half", raymarch.tiles[1]},
                      {"quarter", raymarch.tiles[2]},
                      {"empty", raymarch.tiles[3]}}}};
  for (const SkippedPass& pass : skipped)
    skippedJson.push_back({{"name", pass.name}, {"reason", pass.reason}});
  return {
      {"frame", frame},
      {"resolution", {width, height}},
      {"gl_renderer", glRenderer},
      {"gl_version", glVersion},
      {"particles",
       {{"liquid", counts.liquid},
        {"spray", counts.spray},
        {"bubble", counts.bubble},
        {"foam", counts.foam},
        {"dropped_invalid", counts.droppedInvalid}}},
      {"liquid",
       {{"splash_particles", liquid.splashParticles},
        {"aggregate_particles", liquid.aggregateParticles},
        {"isotropic_interior", liquid.isotropicInterior},
        {"full_neighbours", liquid.fullNeighbours},
        {"min_neighbours_applied", liquid.minNeighboursApplied},
        {"rest_density", liquid.restDensity},
        {"culled", liquid.culled},
        {"hidden_behind_solids", liquid.hiddenBehindSolids},
        {"splashes_absorbed", liquid.splashesAbsorbed},
        {"hidden_interior_dropped", liquid.hiddenInteriorDropped},
        {"hidden_interior_front_layer_only", liquid.hiddenInteriorFrontLayerOnly},
        {"hidden_interior_back_layer_only", liquid.hiddenInteriorBackLayerOnly},
        {"hidden_interior_not_applied", liquid.hiddenInteriorNotApplied},
        {"hidden_interior_ms", liquid.hiddenInteriorMilliseconds},
        {"occluded_from_front", liquid.occludedFromFront},
        {"occluded_from_back", liquid.occludedFromBack},
        {"occluded_dropped", liquid.occludedDropped},
        {"occluded_reach_pixels", liquid.occludedReachPixels},
        {"occluded_shown_pixels", liquid.occludedShownPixels},
        {"occlusion_ms", liquid.occlusionMilliseconds},
        {"liquid_pixels", liquid.liquidPixels},
        {"tiles_shaded", liquid.tilesShaded},
        {"tiles", liquid.tiles},
        {"rays_with_second_body", liquid.raysWithSecondBody},
        {"total_internal_reflections", liquid.totalInternalReflections},
        {"exits_off_screen", liquid.exitsOffScreen},
        {"exits_behind_solids", liquid.exitsBehindSolids},
        {"camera_in_liquid", liquid.cameraInLiquid},
        {"front_layer_skipped", liquid.frontLayerSkipped},
        {"second_body_orders",
         {{"splash_splash", liquid.orders[0]},
          {"splash_aggregate", liquid.orders[1]},
          {"aggregate_splash", liquid.orders[2]},
          {"aggregate_aggregate", liquid.orders[3]}}},
        {"shapes_kept", liquid.shapesNotKept.empty()},
        {"shapes_not_kept", liquid.shapesNotKept},
        {"neighbour_ms", liquid.neighbourMilliseconds},
        {"anisotropy_ms", liquid.anisotropyMilliseconds}}},
      {"foam",
       {{"spray_particles", foam.sprayParticles},
        {"surface_particles", foam.surfaceParticles},
        {"bubble_particles", foam.bubbleParticles},
        {"culled", foam.culled},
        {"hidden_behind_solids", foam.hiddenBehindSolids},
        {"hidden_under_liquid", foam.hiddenUnderLiquid},
        {"sub_pixel", foam.subPixel},
        {"foam_pixels", foam.foamPixels},
        {"occlusion_estimates", foam.occlusionEstimates},
        {"ao_samples_per_pixel", foam.aoSamplesPerPixel},
        {"lights", foam.lights},
        {"tiles_shaded", foam.tilesShaded},
        {"tiles", foam.tiles}}},
      {"light",
       {{"lights", light.lights},
        {"lights_seeing_liquid", light.lightsSeeingLiquid},
        {"caustics", light.caustics},
        {"light_passes", light.lightPasses},
        {"prepare_ms", light.prepareMilliseconds},
        {"view_size", light.viewSize},
        {"views_kept", light.viewsKept},
        {"world_alone", light.worldAlone},
        {"view_particles", light.viewParticles},
        {"view_particles_left_out", light.viewParticlesLeftOut},
        {"view_particles_column_thinned", light.viewParticlesColumnThinned},
        {"tiles_shaded", light.tilesShaded},
        {"tiles", light.tiles},
        {"sky_occlusion_scale", light.skyOcclusionScale}}},
      {"raymarch", raymarchJson},
      {"passes", passesJson},
      {"skipped", skippedJson},
      {"load_ms", loadMilliseconds},
      {"prepare_ms", prepareMilliseconds},
      {"readback_ms", readbackMilliseconds},
      {"total_ms", totalMilliseconds},
      {"first_frame", firstFrame},
      {"setup",
       {{"ms", setup.milliseconds},
        {"programs_compiled", setup.programsCompiled},
        {"programs_from_cache", setup.programsFromCache},
        {"programs_rejected", setup.programsRejected}}},
  };
}

}  // namespace spindrift
