#pragma once

#include <string>
#include <vector>

#include "gl/GlObjects.h"
#include "passes/FoamBlurPass.h"
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

}  // namespace spindrift
