#pragma once

#include <string>
#include <vector>

#include "framedata/CompositeData.h"
#include "framedata/DepthLayers.h"
#include "framedata/FoamLayerData.h"
#include "framedata/LightData.h"
#include "framedata/LiquidData.h"
#include "gl/GlObjects.h"
#include "spindrift/RenderResult.h"

namespace spindrift {

/// The layers a frame can write, as named in the EXR (intermediate layers aside), and which of them a frame
/// reads back: reading a layer back costs a GPU-to-CPU copy of every pixel, so a caller that needs only the
/// composite asks for it alone (`--layers`).
class LayerSelection {
 public:
  /// Every layer, in the order the EXR holds them.
  static const std::vector<std::string>& allNames();
  /// All layers.
  LayerSelection() = default;
  /// The named layers; empty means all. Throws Error naming the valid layers for an unknown name.
  explicit LayerSelection(const std::vector<std::string>& names);

  bool wants(const std::string& layer) const;
  /// Whether the layer was named (not merely wanted as one of all).
  bool names(const std::string& layer) const;
  bool wantsComposite() const { return wants("composite"); }
  /// Any of liquid, liquid_splash, liquid_class, depth, normal, thickness.
  bool wantsLiquidLayers() const;
  /// Any foam layer.
  bool wantsFoamLayers() const;
  /// Any of liquid_shadow, caustics, liquid_sky.
  bool wantsLightLayers() const;

 private:
  std::vector<std::string> names_;  // Empty: all.
};

/// Reads a texture's first `channels.size()` channels into a layer, top row first.
ImageLayer readLayer(const Texture2D& texture, const std::string& name,
                     const std::vector<std::string>& channels);
/// A layer with every channel of every pixel set to `value`, for passes a frame did not need to run.
ImageLayer filledLayer(int width, int height, const std::string& name,
                       const std::vector<std::string>& channels, float value);

/// Appends the foam layers (foam, foam_spray, foam_surface, foam_bubble, foam_shadow, foam_irradiance,
/// foam_thickness); `foam` null (no foam in view) gives the same layers, empty, so every frame of a sequence
/// has the same channels.
void readFoamLayers(const FoamLayerData* foam, int width, int height, const LayerSelection& selection,
                    std::vector<ImageLayer>& layers);

/// Appends the liquid layers (liquid, liquid_splash, liquid_class, depth, normal, thickness, refraction_uv,
/// transmittance, reflection); `liquid` null (no
/// liquid in view) gives the same layers, empty (depth 1e10), so every frame of a sequence has the same
/// channels.
void readLiquidLayers(const LiquidData* liquid, int width, int height, const LayerSelection& selection,
                      std::vector<ImageLayer>& layers);

/// Reads the selected layers of a frame into `layers`: the composite, then the liquid's, then the foam's.
/// `composite` is null only when the selection does not want it.
void readFrameLayers(const CompositeData* composite, const LiquidData* liquid, const FoamLayerData* foam,
                     int width, int height, const LayerSelection& selection, std::vector<ImageLayer>& layers);

/// Keeps the four depth layers of a layer set (depth and normal, front and back) as layers named
/// `<name>_front_depth`, `<name>_back_normal` and so on, when intermediate layers were asked for.
class IntermediateLayers {
 public:
  explicit IntermediateLayers(bool enabled) : enabled_(enabled) {}
  void keep(const SurfaceLayers& layers, const std::string& name);
  /// Keeps layers already read (a pass's own intermediate layers), when enabled.
  void keep(std::vector<ImageLayer> layers);
  /// Moves the kept layers to the end of `layers`.
  void appendTo(std::vector<ImageLayer>& layers);

 private:
  bool enabled_;
  std::vector<ImageLayer> kept_;
};

/// Appends liquid_shadow, caustics and liquid_sky (RGB) when the scene has lights (`sceneHasLights`) or the
/// frame lit the background (the world's light alone): read from `lit`, or filled with 1, 0 and 1 on a frame
/// that lit nothing, so every frame of a sequence has the same channels. Only the layers `selection` wants;
/// on a frame without either, only those it names.
void readLightLayers(const LitBackgroundData* lit, bool sceneHasLights, int width, int height,
                     const LayerSelection& selection, std::vector<ImageLayer>& layers);

}  // namespace spindrift
