#include "passes/FoamOcclusionPass.h"

#include <algorithm>
#include <cmath>

#include <glm/trigonometric.hpp>

#include "passes/FrameUniforms.h"

namespace spindrift {
namespace {

// Large enough to resolve an environment's hue by direction; irradiance varies slowly.
constexpr int kIrradianceMapWidth = 64;
constexpr int kIrradianceMapHeight = 32;

}  // namespace

SamplesInsideSphere samplesInsideUnitSphere(const std::vector<glm::vec4>& cube) {
  SamplesInsideSphere kept;
  kept.insideAmongFirst.reserve(cube.size() + 1);
  for (const glm::vec4& point : cube) {
    kept.insideAmongFirst.push_back(std::uint32_t(kept.inside.size()));
    if (!(point.w > 1.0f || point.w == 0.0f)) kept.inside.push_back(point);
  }
  kept.insideAmongFirst.push_back(std::uint32_t(kept.inside.size()));
  return kept;
}

FoamOcclusionPass::FoamOcclusionPass(const ShaderLibrary& shaders)
    : program_(shaders.program({"fullscreen.vert", "foam_occlusion.frag"})),
      irradianceMapProgram_(shaders.program({"foam_irradiance_map.comp"})),
      upsampleProgram_(shaders.program({"fullscreen.vert", "foam_occlusion_upsample.frag"})),
      occludersProgram_(shaders.program({"fullscreen.vert", "foam_occluders.frag"})),
      emptyVertexArray_(createVertexArray()),
      framebuffer_(createFramebuffer()),
      haltonSamples_(createBuffer()),
      haltonInsideCounts_(createBuffer()),
      counters_(createBuffer()) {
  // The samples are the same for every pixel and frame (a constant seed): made once, by the shader library's
  // own Halton code, so what the tests check is what the pass uses.
  const ProgramObject generator = shaders.program({"foam_halton_samples.comp"});
  const BufferObject generated = createBuffer();
  const GLsizeiptr generatedBytes = GLsizeiptr(kMaximumSamples * sizeof(glm::vec4));
  glNamedBufferStorage(generated.id(), generatedBytes, nullptr, 0);
  glUseProgram(generator.id());
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, generated.id());
  glDispatchCompute(kMaximumSamples / 64, 1, 1);
  glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
  std::vector<glm::vec4> cube(kMaximumSamples);
  glGetNamedBufferSubData(generated.id(), 0, generatedBytes, cube.data());
  // About half of the cube's points lie outside the unit sphere, and the paper skips them. A loop that skips
  // them in the shader still runs their iterations on llvmpipe, every lane of a group of eight alike, so the
  // pass reads the kept points alone (the drop's foam_occlusion 28-29 -> 17-18 ms, its layers bit-identical).
  SamplesInsideSphere kept = samplesInsideUnitSphere(cube);
  const std::size_t keptCount = std::max<std::size_t>(kept.inside.size(), 1);  // a buffer may not be empty
  kept.inside.resize(keptCount);
  glNamedBufferStorage(haltonSamples_.id(), GLsizeiptr(keptCount * sizeof(glm::vec4)), kept.inside.data(), 0);
  glNamedBufferStorage(haltonInsideCounts_.id(),
                       GLsizeiptr(kept.insideAmongFirst.size() * sizeof(std::uint32_t)),
                       kept.insideAmongFirst.data(), 0);
  glNamedBufferStorage(counters_.id(), 3 * sizeof(std::uint32_t), nullptr, GL_DYNAMIC_STORAGE_BIT);
  checkGlError("making the foam's SSAO samples");
}

void FoamOcclusionPass::bindLamps(GLuint program, const std::vector<Light>& lights) {
  // Laid out as FoamLamp (std430: three vec4s).
  std::vector<glm::vec4> lamps;
  for (const Light& light : lights) {
    lamps.emplace_back(light.direction, float(int(light.type)));  // The order of the shader's types.
    lamps.emplace_back(light.position, light.strength);
    lamps.emplace_back(light.color, std::cos(glm::radians(0.5f * light.spotAngleDegrees)));
  }
  const std::size_t count = lamps.size() / 3;
  lamps.resize(std::max<std::size_t>(count, 1) * 3);  // a buffer may not be empty
  if (lamps.size() > lampCapacity_) {
    lamps_ = createBuffer();
    glNamedBufferStorage(lamps_.id(), GLsizeiptr(lamps.size() * sizeof(glm::vec4)), nullptr,
                         GL_DYNAMIC_STORAGE_BIT);
    lampCapacity_ = lamps.size();
  }
  glNamedBufferSubData(lamps_.id(), 0, GLsizeiptr(lamps.size() * sizeof(glm::vec4)), lamps.data());
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 3, lamps_.id());
  glUniform1i(uniformLocation(program, "foamLampCount"), GLint(count));
}

void FoamOcclusionPass::bindEnvironment(GLuint program, const BackgroundData& background) const {
  glBindTextureUnit(5, background.environment ? background.environment->id() : 0);
  glUniform1i(uniformLocation(program, "hasEnvironment"), background.environment ? 1 : 0);
  glUniform3fv(uniformLocation(program, "fallbackColor"), 1, &background.fallbackColor.x);
}

FoamOcclusionData FoamOcclusionPass::run(const FoamSurfaceData& surface, const FoamIntensityData& intensity,
                                         const FoamSceneDepth& scene, const BackgroundData& background,
                                         const std::vector<Light>& lights, const FoamParameters& parameters,
                                         const PixelTiles* tiles, int width, int height) {
  const bool useIrradianceMap = parameters.irradiance == "irradiance_map";
  if (useIrradianceMap) {
    ensureTexture(irradianceMap_, GL_RGBA16F, kIrradianceMapWidth, kIrradianceMapHeight);
    glTextureParameteri(irradianceMap_.id(), GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    glTextureParameteri(irradianceMap_.id(), GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glTextureParameteri(irradianceMap_.id(), GL_TEXTURE_WRAP_S, GL_REPEAT);
    glUseProgram(irradianceMapProgram_.id());
    bindEnvironment(irradianceMapProgram_.id(), background);
    glBindImageTexture(0, irradianceMap_.id(), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA16F);
    glDispatchCompute(kIrradianceMapWidth / 8, kIrradianceMapHeight / 8, 1);
    glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT);
    checkGlError("making the foam's irradiance map");
  }

  // The samples' four reads packed into one texture: on llvmpipe a sample's fetches are most of its cost.
  ensureTexture(occluders_, GL_RGBA32F, width, height);
  bindColorTargets(framebuffer_.id(), {&occluders_});
  glDisable(GL_DEPTH_TEST);
  glDisable(GL_BLEND);
  glUseProgram(occludersProgram_.id());
  glBindTextureUnit(0, surface.depthAndSearchRadius.id());
  glBindTextureUnit(2, intensity.intensity.id());
  glBindTextureUnit(3, scene.fluidEyeDepth.id());
  glBindTextureUnit(4, scene.solidEyeDepth.id());
  drawFullscreenTriangle(emptyVertexArray_.id());
  checkGlError("packing the foam's occluders");

  // Estimates, one per block (the full-resolution textures themselves when a block is one pixel).
  const int block = parameters.occlusion_block;
  ensureTexture(shadow_, GL_RG32F, width, height);
  ensureTexture(irradiance_, GL_RGBA16F, width, height);
  if (block > 1) {
    ensureTexture(blockShadow_, GL_RG32F, (width + block - 1) / block, (height + block - 1) / block);
    ensureTexture(blockIrradiance_, GL_RGBA16F, (width + block - 1) / block, (height + block - 1) / block);
  }
  if (tiles) {  // what foam_occlusion.frag and foam_occlusion_upsample.frag write where there is no foam
    const float noShadow[4] = {0.0f, 1e10f, 0.0f, 0.0f}, noIrradiance[4] = {0.0f, 0.0f, 0.0f, 0.0f};
    clearColorTargets(framebuffer_.id(), {&shadow_}, noShadow);
    clearColorTargets(framebuffer_.id(), {&irradiance_}, noIrradiance);
  }
  Texture2D& estimatedShadow = block > 1 ? blockShadow_ : shadow_;
  Texture2D& estimatedIrradiance = block > 1 ? blockIrradiance_ : irradiance_;
  bindColorTargets(framebuffer_.id(), {&estimatedShadow, &estimatedIrradiance});
  glDisable(GL_DEPTH_TEST);
  glDisable(GL_BLEND);
  const std::uint32_t zeros[3] = {0, 0, 0};
  glNamedBufferSubData(counters_.id(), 0, sizeof zeros, zeros);
  const GLuint program = program_.id();
  glUseProgram(program);
  const FoamParameters& p = parameters;
  glUniform1f(uniformLocation(program, "initialRadiusFactor"), p.ao_initial_radius_factor);
  glUniform1f(uniformLocation(program, "radiusIncrementFactor"), p.ao_radius_increment_factor);
  glUniform1i(uniformLocation(program, "passes"), p.ao_passes);
  glUniform1f(uniformLocation(program, "sampleDensity"), p.ao_sample_density);
  glUniform1i(uniformLocation(program, "minSamples"), std::min(p.ao_min_samples, p.ao_max_samples));
  glUniform1i(uniformLocation(program, "maxSamples"), p.ao_max_samples);
  glUniform1f(uniformLocation(program, "maxOcclusionDistance"), p.ao_max_occlusion_distance);
  glUniform1f(uniformLocation(program, "liquidOpacity"), p.ao_liquid_opacity);
  glUniform3f(uniformLocation(program, "shadowShape"), p.shadow_scale, p.shadow_exponent, p.shadow_offset);
  glUniform1i(uniformLocation(program, "useIrradianceMap"), useIrradianceMap ? 1 : 0);
  glUniform1i(uniformLocation(program, "blockSize"), block);
  bindEnvironment(program, background);
  bindLamps(program, parameters.lit_by_lights ? lights : std::vector<Light>{});
  glBindTextureUnit(0, surface.depthAndSearchRadius.id());
  glBindTextureUnit(1, surface.normal.id());
  glBindTextureUnit(2, intensity.intensity.id());
  glBindTextureUnit(6, useIrradianceMap ? irradianceMap_.id() : 0);
  glBindTextureUnit(7, occluders_.id());
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, haltonSamples_.id());
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, counters_.id());
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 2, haltonInsideCounts_.id());
  // Blocks of pixels are estimated over the whole (smaller) target; single pixels in the foam's tiles only.
  drawFullscreen(emptyVertexArray_.id(), block > 1 ? nullptr : tiles);
  checkGlError("estimating the foam's shadow and irradiance");
  if (block > 1) {
    bindColorTargets(framebuffer_.id(), {&shadow_, &irradiance_});
    glUseProgram(upsampleProgram_.id());
    glUniform1i(uniformLocation(upsampleProgram_.id(), "blockSize"), block);
    glBindTextureUnit(0, blockShadow_.id());
    glBindTextureUnit(1, blockIrradiance_.id());
    glBindTextureUnit(2, surface.depthAndSearchRadius.id());
    glBindTextureUnit(3, intensity.intensity.id());
    drawFullscreen(emptyVertexArray_.id(), tiles);
    checkGlError("upsampling the foam's shadow and irradiance");
  }
  return {shadow_, irradiance_};
}

FoamOcclusionStatistics FoamOcclusionPass::statistics() const {
  std::uint32_t counters[3] = {0, 0, 0};
  glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
  glGetNamedBufferSubData(counters_.id(), 0, sizeof counters, counters);
  FoamOcclusionStatistics statistics;
  statistics.foamPixels = counters[0];
  statistics.samples = counters[1];
  statistics.estimates = counters[2];
  return statistics;
}

}  // namespace spindrift
