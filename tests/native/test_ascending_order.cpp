// The occlusion test's nearest-first order (prep/AscendingOrder.h): a radix sort of doubles' bits that must
// give exactly what sorting (key, position) pairs gives, checked against std::sort on random keys with many
// ties, negative keys, both zeros, infinities, denormals and keys whose high digits all agree (the passes
// skipped), and on the empty and single-key cases.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <limits>
#include <random>
#include <utility>
#include <vector>

#include "prep/AscendingOrder.h"

namespace spindrift {
namespace {

std::vector<std::uint32_t> byPairs(const std::vector<double>& keys) {
  std::vector<std::pair<double, std::uint32_t>> pairs;
  for (std::size_t k = 0; k < keys.size(); ++k)
    pairs.emplace_back(keys[k], std::uint32_t(k));
  std::sort(pairs.begin(), pairs.end());
  std::vector<std::uint32_t> order;
  for (const auto& pair : pairs)
    order.push_back(pair.second);
  return order;
}

TEST(AscendingOrder, GivesWhatSortingKeyPositionPairsGives) {
  std::mt19937 random(17);
  std::uniform_real_distribution<double> depth(2.0, 12.0);
  std::uniform_int_distribution<int> pick(0, 9);
  std::vector<double> keys;
  for (int k = 0; k < 50000; ++k) {
    const int kind = pick(random);
    keys.push_back(kind == 0   ? double(pick(random))  // ties
                   : kind == 1 ? -depth(random)
                               : depth(random));
  }
  EXPECT_EQ(ascendingOrder(keys), byPairs(keys));
}

TEST(AscendingOrder, SpecialValuesAndZerosOfBothSigns) {
  const double infinity = std::numeric_limits<double>::infinity();
  const std::vector<double> keys = {0.0,       -0.0, 1.0,  -1.0,  infinity, -infinity, 4.9e-324,
                                    -4.9e-324, 0.0,  -0.0, 1e308, -1e308,   1.0};
  EXPECT_EQ(ascendingOrder(keys), byPairs(keys));
}

TEST(AscendingOrder, KeysAgreeingInTheirHighDigits) {
  // Depths a few millimetres apart around 5 m: the top 32 bits of their patterns barely differ.
  std::vector<double> keys;
  for (int k = 0; k < 1000; ++k)
    keys.push_back(5.0 + 1e-6 * double((k * 7919) % 1000));
  EXPECT_EQ(ascendingOrder(keys), byPairs(keys));
  const std::vector<double> same(100, 3.25);
  EXPECT_EQ(ascendingOrder(same), byPairs(same));
}

TEST(AscendingOrder, EmptyAndSingleKey) {
  EXPECT_TRUE(ascendingOrder({}).empty());
  EXPECT_EQ(ascendingOrder({7.0}), std::vector<std::uint32_t>{0});
}

}  // namespace
}  // namespace spindrift
