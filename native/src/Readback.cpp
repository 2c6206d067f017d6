#include "Readback.h"

#include <sys/mman.h>

#include <algorithm>
#include <cstdint>

#include "spindrift/Error.h"

namespace spindrift {

namespace {

const std::vector<std::string> kLiquidLayers = {"liquid",        "liquid_splash", "liquid_class",
                                                "depth",         "normal",        "thickness",
                                                "refraction_uv", "transmittance", "reflection"};
const std::vector<std::string> kFoamLayers = {
    "foam", "foam_spray", "foam_surface", "foam_bubble", "foam_shadow", "foam_irradiance", "foam_thickness"};
const std::vector<std::string> kLightLayers = {"liquid_shadow", "caustics", "liquid_sky"};

// `count` floats whose pages are mapped before they are written: one madvise maps them all, where writing
// fresh pages faults once per 4 KiB page (a process's first readback is its first touch of that memory: at
// 960×540 its 104 MB took 55 ms of faults and clearing against 37 populated; docs/frame-cost.md). Memory the
// allocator gives again is mapped already, and populating it would still visit every page (1.5 ms a later
// 480×270 frame): only a first page that is not resident is taken for fresh memory. Where the kernel cannot
// (before Linux 5.14), the pages fault in as before.
std::vector<float> prefaultedFloats(std::size_t count) {
  std::vector<float> floats;
  floats.reserve(count);
  const std::size_t pageSize = 4096;
  const auto first = (reinterpret_cast<std::uintptr_t>(floats.data()) + pageSize - 1) & ~(pageSize - 1);
  const auto last = (reinterpret_cast<std::uintptr_t>(floats.data() + count)) & ~(pageSize - 1);
#ifdef MADV_POPULATE_WRITE
  unsigned char resident = 0;
  if (last > first && mincore(reinterpret_cast<void*>(first), pageSize, &resident) == 0 && !(resident & 1u))
    madvise(reinterpret_cast<void*>(first), last - first, MADV_POPULATE_WRITE);
#endif
  floats.resize(count);
  return floats;
}

bool contains(const std::vector<std::string>& names, const std::string& name) {
  return std::find(names.begin(), names.end(), name) != names.end();
}

}  // namespace

const std::vector<std::string>& LayerSelection::allNames() {
  static const std::vector<std::string> names = [] {
    std::vector<std::string> all = {"composite"};
    all.insert(all.end(), kLiquidLayers.begin(), kLiquidLayers.end());
    all.insert(all.end(), kFoamLayers.begin(), kFoamLayers.end());
    all.insert(all.end(), kLightLayers.begin(), kLightLayers.end());
    return all;
  }();
  return names;
}

LayerSelection::LayerSelection(const std::vector<std::string>& names) : names_(names) {
  for (const std::string& name : names_)
    if (!contains(allNames(), name)) {
      std::string valid;
      for (const std::string& known : allNames())
        valid += (valid.empty() ? "" : ", ") + known;
      throw Error("unknown layer \"" + name + "\" (layers: " + valid + ")");
    }
}

bool LayerSelection::wants(const std::string& layer) const {
  return names_.empty() || contains(names_, layer);
}

bool LayerSelection::names(const std::string& layer) const {
  return contains(names_, layer);
}

bool LayerSelection::wantsLiquidLayers() const {
  return std::any_of(kLiquidLayers.begin(), kLiquidLayers.end(),
                     [this](const auto& name) { return wants(name); });
}

bool LayerSelection::wantsLightLayers() const {
  return std::any_of(kLightLayers.begin(), kLightLayers.end(),
                     [this](const auto& name) { return wants(name); });
}

bool LayerSelection::wantsFoamLayers() const {
  return std::any_of(kFoamLayers.begin(), kFoamLayers.end(),
                     [this](const auto& name) { return wants(name); });
}

ImageLayer readLayer(const Texture2D& texture, const std::string& name,
                     const std::vector<std::string>& channels) {
  const std::size_t channelCount = channels.size();
  const GLenum format = channelCount == 1   ? GL_RED
                        : channelCount == 2 ? GL_RG
                        : channelCount == 3 ? GL_RGB
                                            : GL_RGBA;
  const std::size_t rowFloats = std::size_t(texture.width) * channelCount;
  // Read into the layer itself and turn it top row first in place: a second buffer of the layer's size cost
  // more than the read (its fresh pages are faulted in and cleared by the kernel: at 1920×1080 a 33 MB RGBA
  // buffer took 70–100 ms on the project's VM, glGetTextureImage 5 ms).
  ImageLayer layer{name, channels, prefaultedFloats(rowFloats * std::size_t(texture.height))};
  glPixelStorei(GL_PACK_ALIGNMENT, 4);
  glGetTextureImage(texture.id(), 0, format, GL_FLOAT, GLsizei(layer.pixels.size() * sizeof(float)),
                    layer.pixels.data());
  checkGlError(("reading back " + name).c_str());
  for (int row = 0; row < texture.height / 2; ++row) {
    float* top = layer.pixels.data() + std::size_t(row) * rowFloats;
    std::swap_ranges(top, top + rowFloats,
                     layer.pixels.data() + std::size_t(texture.height - 1 - row) * rowFloats);
  }
  return layer;
}

ImageLayer filledLayer(int width, int height, const std::string& name,
                       const std::vector<std::string>& channels, float value) {
  ImageLayer layer{name, channels,
                   prefaultedFloats(std::size_t(width) * std::size_t(height) * channels.size())};
  std::fill(layer.pixels.begin(), layer.pixels.end(), value);
  return layer;
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

void readFoamLayers(const FoamLayerData* foam, int width, int height, const LayerSelection& selection,
                    std::vector<ImageLayer>& layers) {
  const std::vector<std::string> rgba = {"R", "G", "B", "A"}, rgb = {"R", "G", "B"};
  struct Part {
    const char* name;
    const Texture2D* texture;
    const std::vector<std::string>& channels;
  };
  const Part parts[] = {{"foam", foam ? &foam->foam : nullptr, rgba},
                        {"foam_spray", foam ? &foam->spray : nullptr, rgba},
                        {"foam_surface", foam ? &foam->surface : nullptr, rgba},
                        {"foam_bubble", foam ? &foam->bubble : nullptr, rgba},
                        {"foam_shadow", foam ? &foam->shadow : nullptr, rgb},
                        {"foam_irradiance", foam ? &foam->irradiance : nullptr, rgb}};
  for (const Part& part : parts) {
    if (!selection.wants(part.name)) continue;
    layers.push_back(part.texture ? readLayer(*part.texture, part.name, part.channels)
                                  : filledLayer(width, height, part.name, part.channels, 0.0f));
  }
  if (selection.wants("foam_thickness"))
    layers.push_back(foam ? totalThickness(foam->thickness)
                          : filledLayer(width, height, "foam_thickness", {"Y"}, 0.0f));
}

void readLiquidLayers(const LiquidData* liquid, int width, int height, const LayerSelection& selection,
                      std::vector<ImageLayer>& layers) {
  const std::vector<std::string> rgba = {"R", "G", "B", "A"}, rgb = {"R", "G", "B"}, y = {"Y"}, z = {"Z"},
                                 xyz = {"X", "Y", "Z"};
  struct Part {
    const char* name;
    const Texture2D* texture;
    const std::vector<std::string>& channels;
    float empty;  // The value where no liquid is.
  };
  const Part parts[] = {{"liquid", liquid ? &liquid->color : nullptr, rgba, 0.0f},
                        {"liquid_splash", liquid ? &liquid->splashColor : nullptr, rgba, 0.0f},
                        {"liquid_class", liquid ? &liquid->surfaceClass : nullptr, y, 0.0f},
                        {"depth", liquid ? &liquid->frontDepth : nullptr, z, 1e10f},
                        {"normal", liquid ? &liquid->frontNormal : nullptr, xyz, 0.0f},
                        {"thickness", liquid ? &liquid->thickness : nullptr, y, 0.0f},
                        // The refraction split for a compositor that refracts another render
                        // (docs/python-module.md).
                        {"refraction_uv", liquid ? &liquid->refractionUv : nullptr, rgb, 0.0f},
                        {"transmittance", liquid ? &liquid->transmittance : nullptr, rgb, 0.0f},
                        {"reflection", liquid ? &liquid->reflection : nullptr, rgb, 0.0f}};
  for (const Part& part : parts) {
    if (!selection.wants(part.name)) continue;
    layers.push_back(part.texture ? readLayer(*part.texture, part.name, part.channels)
                                  : filledLayer(width, height, part.name, part.channels, part.empty));
  }
}

void readFrameLayers(const CompositeData* composite, const LiquidData* liquid, const FoamLayerData* foam,
                     int width, int height, const LayerSelection& selection,
                     std::vector<ImageLayer>& layers) {
  if (composite && selection.wantsComposite())
    layers.push_back(readLayer(composite->color, "composite", {"R", "G", "B", "A"}));
  readLiquidLayers(liquid, width, height, selection, layers);
  readFoamLayers(foam, width, height, selection, layers);
}

void IntermediateLayers::keep(const SurfaceLayers& layers, const std::string& name) {
  if (!enabled_) return;
  kept_.push_back(readLayer(layers.front.eyeDepth, name + "_front_depth", {"Z"}));
  kept_.push_back(readLayer(layers.back.eyeDepth, name + "_back_depth", {"Z"}));
  kept_.push_back(readLayer(layers.front.normal, name + "_front_normal", {"X", "Y", "Z"}));
  kept_.push_back(readLayer(layers.back.normal, name + "_back_normal", {"X", "Y", "Z"}));
}

void IntermediateLayers::keep(std::vector<ImageLayer> layers) {
  if (!enabled_) return;
  for (ImageLayer& layer : layers)
    kept_.push_back(std::move(layer));
}

void IntermediateLayers::appendTo(std::vector<ImageLayer>& layers) {
  for (ImageLayer& layer : kept_)
    layers.push_back(std::move(layer));
  kept_.clear();
}

void readLightLayers(const LitBackgroundData* lit, bool sceneHasLights, int width, int height,
                     const LayerSelection& selection, std::vector<ImageLayer>& layers) {
  const std::vector<std::string> rgb = {"R", "G", "B"};
  const struct {
    const char* name;
    const Texture2D* texture;
    float empty;
  } lightLayers[] = {{"liquid_shadow", lit ? &lit->liquidShadow : nullptr, 1.0f},
                     {"caustics", lit ? &lit->caustics : nullptr, 0.0f},
                     {"liquid_sky", lit ? &lit->skyKept : nullptr, 1.0f}};
  // A frame no light lit has them only where they are named (a compositor built to read them: the add-on's
  // with sky_without_lamps), as what leaves the background as it is.
  for (const auto& layer : lightLayers) {
    if (!(sceneHasLights || lit ? selection.wants(layer.name) : selection.names(layer.name))) continue;
    layers.push_back(layer.texture ? readLayer(*layer.texture, layer.name, rgb)
                                   : filledLayer(width, height, layer.name, rgb, layer.empty));
  }
}

}  // namespace spindrift
