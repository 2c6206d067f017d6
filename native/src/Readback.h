#pragma once

#include <string>
#include <vector>

#include "gl/GlObjects.h"
#include "framedata/CompositeData.h"
#include "framedata/DepthLayers.h"
#include "framedata/FoamLayerData.h"
#include "framedata/LiquidData.h"
#include "spindrift/RenderResult.h"

namespace spindrift {

/// Reads a texture's first `channels.size()` channels into a layer, top row first.
ImageLayer readLayer(const Texture2D& texture, const std::string& name,
                     const std::vector<std::string>& channels);
/// A layer with every channel of every pixel set to `value`, for passes a frame did not need to run.
ImageLayer filledLayer(int width, int height, const std::string& name,
                       const std::vector<std::string>& channels, float value);

/// Appends the foam layers (foam, foam_spray, foam_surface, foam_bubble, foam_shadow, foam_irradiance,
/// foam_thickness); `foam` null (no foam in view) gives the same layers, empty, so every frame of a sequence
/// has the same channels.
void readFoamLayers(const FoamLayerData* foam, int width, int height, std::vector<ImageLayer>& layers);

/// Appends the liquid layers (liquid, liquid_splash, liquid_class, depth, normal, thickness, refraction_uv,
/// transmittance, reflection); `liquid` null (no
/// liquid in view) gives the same layers, empty (depth 1e10), so every frame of a sequence has the same channels.
void readLiquidLayers(const LiquidData* liquid, int width, int height, std::vector<ImageLayer>& layers);

/// Reads every layer of a frame into `layers`: the composite, then the liquid's, then the foam's.
void readFrameLayers(const CompositeData& composite, const LiquidData* liquid, const FoamLayerData* foam,
                     int width, int height, std::vector<ImageLayer>& layers);

/// Keeps the four depth layers of a layer set (depth and normal, front and back) as layers named
/// `<name>_front_depth`, `<name>_back_normal` and so on, when intermediate layers were asked for.
class IntermediateLayers {
 public:
  explicit IntermediateLayers(bool enabled) : enabled_(enabled) {}
  void keep(const SurfaceLayers& layers, const std::string& name);
  /// Moves the kept layers to the end of `layers`.
  void appendTo(std::vector<ImageLayer>& layers);

 private:
  bool enabled_;
  std::vector<ImageLayer> kept_;
};

}  // namespace spindrift
