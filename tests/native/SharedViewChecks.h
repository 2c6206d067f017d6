#pragma once

#include <cstring>
#include <functional>
#include <vector>

#include <gtest/gtest.h>

#include "prep/FrameLiquidCache.h"
#include "prep/LiquidPreparation.h"

// Checks that the views of one frame sharing a FrameLiquidCache get what each gets alone.
namespace shared_views {

// Whether two ellipsoid lists are the same, bit for bit and in the same order.
inline bool sameInstances(const std::vector<spindrift::EllipsoidInstance>& a,
                          const std::vector<spindrift::EllipsoidInstance>& b) {
  return a.size() == b.size() &&
         (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(spindrift::EllipsoidInstance)) == 0);
}

// What a test checks of each shared view besides its ellipsoids: the view's preparation with and without the
// cache, the cache after it, the view's index and the order the views ran in.
using ViewCheck =
    std::function<void(const spindrift::LiquidPreparation& shared, const spindrift::LiquidPreparation& alone,
                       const spindrift::FrameLiquidCache& frame, int view, const std::vector<int>& order)>;

// Prepares `views` alone, then in two orders sharing one cache per order; views 0 and 1 must see every
// particle and view 2 must cull some (the one that cannot share). Returns the views prepared alone.
inline std::vector<spindrift::LiquidPreparation> expectSharedViewsGetWhatTheyGetAlone(
    const spindrift::Particles& particles, const spindrift::LiquidParameters& parameters,
    const spindrift::Camera (&views)[3], const ViewCheck& check) {
  std::vector<spindrift::LiquidPreparation> alone;
  for (const spindrift::Camera& view : views)
    alone.push_back(spindrift::prepareLiquid(particles, view, parameters));
  EXPECT_EQ(alone[0].culled, 0u);
  EXPECT_EQ(alone[1].culled, 0u);
  EXPECT_GT(alone[2].culled, 0u);
  for (const std::vector<int>& order : {std::vector<int>{0, 1, 2, 0}, std::vector<int>{2, 1, 0, 1}}) {
    spindrift::FrameLiquidCache frame;
    for (int view : order) {
      const spindrift::LiquidPreparation shared =
          spindrift::prepareLiquid(particles, views[view], parameters, &frame);
      EXPECT_TRUE(sameInstances(shared.aggregates, alone[view].aggregates)) << "view " << view;
      EXPECT_TRUE(sameInstances(shared.splashes, alone[view].splashes)) << "view " << view;
      check(shared, alone[view], frame, view, order);
    }
  }
  return alone;
}

}  // namespace shared_views
