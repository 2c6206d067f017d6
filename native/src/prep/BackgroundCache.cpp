#include "prep/BackgroundCache.h"

#include <cmath>

#include "spindrift/Error.h"

namespace spindrift {
namespace {

FloatImage atSize(FloatImage image, const std::filesystem::path& path, int width, int height, bool nearest) {
  if (image.width == width && image.height == height) return image;
  // Resampling to another aspect ratio would stretch the background under the liquid.
  const double imageAspect = double(image.width) / image.height, cameraAspect = double(width) / height;
  if (std::abs(imageAspect - cameraAspect) > 0.01 * cameraAspect)
    throw Error(path.string() + ": the image is " + std::to_string(image.width) + "x" +
                std::to_string(image.height) + ", which does not have the camera's aspect ratio (" +
                std::to_string(width) + "x" + std::to_string(height) + ")");
  return resizeImage(image, width, height, nearest);
}

}  // namespace

BackgroundImages BackgroundCache::load(const Background& background, int frame, int width, int height) {
  const std::filesystem::path image = background.image.empty() ? "" : pathForFrame(background.image, frame);
  const std::filesystem::path depth =
      background.depth.empty() ? image : pathForFrame(background.depth, frame);
  const std::filesystem::path environment =
      background.environment.empty() ? "" : pathForFrame(background.environment, frame);
  const std::filesystem::path liquidDepth =
      background.liquidDepth.empty() ? "" : pathForFrame(background.liquidDepth, frame);
  const std::string key = image.string() + "|" + depth.string() + "|" + environment.string() + "|" +
                          liquidDepth.string() + "|" + std::to_string(width) + "x" + std::to_string(height);
  if (key != key_) {
    key_.clear();  // Stays cleared if a read below throws, so the next frame tries again.
    color_.reset();
    eyeDepth_.reset();
    environment_.reset();
    liquidEyeDepth_.reset();
    lightPasses_.reset();
    // The depth is the colour's file's own unless the scene names another; a file read once for both.
    const bool depthInImage = !image.empty() && depth == image;
    std::optional<FloatImage> imageDepth;
    if (!image.empty()) {
      BackgroundFile file = readBackgroundFile(image, depthInImage);
      color_ = atSize(std::move(file.color), image, width, height, false);
      lightPasses_ = std::move(file.lightPasses);
      if (lightPasses_)
        for (FloatImage& pass : *lightPasses_)
          pass = atSize(std::move(pass), image, width, height, false);
      imageDepth = std::move(file.depth);
    }
    if (!depth.empty()) {
      if (!depthInImage) imageDepth = readDepthImage(depth);
      if (!imageDepth && background.depthExplicit)
        throw Error(depth.string() + ": no depth channel (expected e.g. ViewLayer.Depth.Z or Z)");
      // Nearest, not bilinear: averaging depth across a silhouette would invent surfaces in mid-air.
      if (imageDepth) eyeDepth_ = atSize(std::move(*imageDepth), depth, width, height, true);
    }
    if (!environment.empty()) environment_ = readColorImage(environment);
    if (!liquidDepth.empty()) {
      std::optional<FloatImage> depthImage = readDepthImage(liquidDepth);
      if (!depthImage)
        throw Error(liquidDepth.string() +
                    ": no depth channel for liquid_depth (expected e.g. ViewLayer.Depth.Z or Z)");
      liquidEyeDepth_ = atSize(std::move(*depthImage), liquidDepth, width, height, true);
    }
    key_ = key;
    ++generation_;
  }
  BackgroundImages images;
  images.color = color_ ? &*color_ : nullptr;
  images.eyeDepth = eyeDepth_ ? &*eyeDepth_ : nullptr;
  images.environment = environment_ ? &*environment_ : nullptr;
  images.liquidEyeDepth = liquidEyeDepth_ ? &*liquidEyeDepth_ : nullptr;
  images.lightPasses = lightPasses_ ? &*lightPasses_ : nullptr;
  images.fallbackColor = background.color;
  images.generation = generation_;
  return images;
}

}  // namespace spindrift
