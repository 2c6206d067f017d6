#pragma once

#include <cstddef>
#include <vector>

#include "prep/LiquidPreparation.h"
#include "spindrift/Scene.h"

namespace spindrift {

/// One draw of the impostor pass: the ellipsoids [first, first + count) of its list, with the program that
/// clips them to the domain's box or the one that does not.
struct ImpostorDraw {
  int first = 0;
  int count = 0;
  bool clip = false;
};

/// The draws of the front and the back depth layer, in list order.
struct ImpostorDraws {
  std::vector<ImpostorDraw> front;
  std::vector<ImpostorDraw> back;
  int clipped = 0;  ///< Ellipsoids drawn with the clip: those the domain's box cuts or leaves out.
};

/// Without a domain: each layer is one draw of the ellipsoids LayerSplit gives it.
ImpostorDraws unclippedDraws(std::size_t count, const LayerSplit& split);

/// Only ellipsoids that reach a face of the domain's box need the per-fragment clip to it; llvmpipe runs the
/// clip's code on every fragment of a program that has it, about a third of the dam break's depth layers. So
/// each of the list's groups [front only | both | back only] (LayerSplit) is reordered, keeping the order
/// within each part, to [clipped | free], [free | clipped] and [clipped | free]: each layer is then three
/// draws at most. An ellipsoid whose bounding sphere lies inside the box by a margin is free; the clip leaves
/// its surface exactly as it is.
ImpostorDraws orderForDomainClip(std::vector<EllipsoidInstance>& ellipsoids, const LayerSplit& split,
                                 const DomainBox& domain);

}  // namespace spindrift
