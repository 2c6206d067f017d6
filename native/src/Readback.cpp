#include "Readback.h"

#include <algorithm>

#include "spindrift/Error.h"

namespace spindrift {

ImageLayer readLayer(const Texture2D& texture, const std::string& name,
                     const std::vector<std::string>& channels) {
  const std::size_t channelCount = channels.size();
  const GLenum format = channelCount == 1   ? GL_RED
                        : channelCount == 2 ? GL_RG
                        : channelCount == 3 ? GL_RGB
                                            : GL_RGBA;
  const std::size_t rowFloats = std::size_t(texture.width) * channelCount;
  std::vector<float> bottomFirst(rowFloats * std::size_t(texture.height));
  glPixelStorei(GL_PACK_ALIGNMENT, 4);
  glGetTextureImage(texture.id(), 0, format, GL_FLOAT, GLsizei(bottomFirst.size() * sizeof(float)),
                    bottomFirst.data());
  checkGlError(("reading back " + name).c_str());
  ImageLayer layer{name, channels, std::vector<float>(bottomFirst.size())};
  for (int row = 0; row < texture.height; ++row)
    std::copy_n(bottomFirst.data() + std::size_t(texture.height - 1 - row) * rowFloats, rowFloats,
                layer.pixels.data() + std::size_t(row) * rowFloats);
  return layer;
}

ImageLayer filledLayer(int width, int height, const std::string& name,
                       const std::vector<std::string>& channels, float value) {
  return {name, channels,
          std::vector<float>(std::size_t(width) * std::size_t(height) * channels.size(), value)};
}

namespace {

ImageLayer totalThickness(const Texture2D& thicknessByType) {
  ImageLayer byType = readLayer(thicknessByType, "foam_thickness", {"R", "G", "B"});
  ImageLayer total{"foam_thickness", {"Y"}, std::vector<float>(byType.pixels.size() / 3)};
  for (std::size_t i = 0; i < total.pixels.size(); ++i)
    total.pixels[i] = byType.pixels[3 * i] + byType.pixels[3 * i + 1] + byType.pixels[3 * i + 2];
  return total;
}

}  // namespace

void readFoamLayers(const FoamLayerData* foam, int width, int height, std::vector<ImageLayer>& layers) {
  const std::vector<std::string> rgba = {"R", "G", "B", "A"}, rgb = {"R", "G", "B"};
  if (!foam) {
    for (const char* name : {"foam", "foam_spray", "foam_surface", "foam_bubble"})
      layers.push_back(filledLayer(width, height, name, rgba, 0.0f));
    layers.push_back(filledLayer(width, height, "foam_shadow", rgb, 0.0f));
    layers.push_back(filledLayer(width, height, "foam_irradiance", rgb, 0.0f));
    layers.push_back(filledLayer(width, height, "foam_thickness", {"Y"}, 0.0f));
    return;
  }
  layers.push_back(readLayer(foam->foam, "foam", rgba));
  layers.push_back(readLayer(foam->spray, "foam_spray", rgba));
  layers.push_back(readLayer(foam->surface, "foam_surface", rgba));
  layers.push_back(readLayer(foam->bubble, "foam_bubble", rgba));
  layers.push_back(readLayer(foam->shadow, "foam_shadow", rgb));
  layers.push_back(readLayer(foam->irradiance, "foam_irradiance", rgb));
  layers.push_back(totalThickness(foam->thickness));
}

void readLiquidLayers(const LiquidData* liquid, int width, int height, std::vector<ImageLayer>& layers) {
  const std::vector<std::string> rgba = {"R", "G", "B", "A"};
  if (!liquid) {
    layers.push_back(filledLayer(width, height, "liquid", rgba, 0.0f));
    layers.push_back(filledLayer(width, height, "liquid_splash", rgba, 0.0f));
    layers.push_back(filledLayer(width, height, "liquid_class", {"Y"}, 0.0f));
    layers.push_back(filledLayer(width, height, "depth", {"Z"}, 1e10f));
    layers.push_back(filledLayer(width, height, "normal", {"X", "Y", "Z"}, 0.0f));
    layers.push_back(filledLayer(width, height, "thickness", {"Y"}, 0.0f));
    for (const char* split : {"refraction_uv", "transmittance", "reflection"})
      layers.push_back(filledLayer(width, height, split, {"R", "G", "B"}, 0.0f));
    return;
  }
  layers.push_back(readLayer(liquid->color, "liquid", rgba));
  layers.push_back(readLayer(liquid->splashColor, "liquid_splash", rgba));
  layers.push_back(readLayer(liquid->surfaceClass, "liquid_class", {"Y"}));
  layers.push_back(readLayer(liquid->frontDepth, "depth", {"Z"}));
  layers.push_back(readLayer(liquid->frontNormal, "normal", {"X", "Y", "Z"}));
  layers.push_back(readLayer(liquid->thickness, "thickness", {"Y"}));
  // The refraction split for a compositor that refracts another render (docs/python-module.md).
  layers.push_back(readLayer(liquid->refractionUv, "refraction_uv", {"R", "G", "B"}));
  layers.push_back(readLayer(liquid->transmittance, "transmittance", {"R", "G", "B"}));
  layers.push_back(readLayer(liquid->reflection, "reflection", {"R", "G", "B"}));
}

void readFrameLayers(const CompositeData& composite, const LiquidData* liquid, const FoamLayerData* foam,
                     int width, int height, std::vector<ImageLayer>& layers) {
  layers.push_back(readLayer(composite.color, "composite", {"R", "G", "B", "A"}));
  readLiquidLayers(liquid, width, height, layers);
  readFoamLayers(foam, width, height, layers);
}

void IntermediateLayers::keep(const SurfaceLayers& layers, const std::string& name) {
  if (!enabled_) return;
  kept_.push_back(readLayer(layers.front.eyeDepth, name + "_front_depth", {"Z"}));
  kept_.push_back(readLayer(layers.back.eyeDepth, name + "_back_depth", {"Z"}));
  kept_.push_back(readLayer(layers.front.normal, name + "_front_normal", {"X", "Y", "Z"}));
  kept_.push_back(readLayer(layers.back.normal, name + "_back_normal", {"X", "Y", "Z"}));
}

void IntermediateLayers::appendTo(std::vector<ImageLayer>& layers) {
  for (ImageLayer& layer : kept_)
    layers.push_back(std::move(layer));
  kept_.clear();
}

}  // namespace spindrift
