#include "prep/AscendingOrder.h"

#include <algorithm>
#include <cstring>
#include <utility>

namespace spindrift {
namespace {

// The bits of a double as an unsigned integer that orders as the double does: a positive's sign bit set, a
// negative's every bit flipped. −0 is made +0 first, as the two compare equal.
std::uint64_t orderedBits(double key) {
  const double canonical = key + 0.0;  // −0 + 0 = +0
  std::uint64_t bits;
  std::memcpy(&bits, &canonical, sizeof bits);
  return bits >> 63 ? ~bits : bits | (std::uint64_t(1) << 63);
}

}  // namespace

std::vector<std::uint32_t> ascendingOrder(const std::vector<double>& keys) {
  const std::size_t count = keys.size();
  std::vector<std::uint64_t> bits(count), bitsOut(count);
  std::vector<std::uint32_t> order(count), orderOut(count);
  for (std::size_t k = 0; k < count; ++k) {
    bits[k] = orderedBits(keys[k]);
    order[k] = std::uint32_t(k);
  }
  constexpr int kDigitBits = 16;
  constexpr std::size_t kDigits = std::size_t(1) << kDigitBits;
  std::vector<std::uint32_t> offsets(kDigits);
  for (int shift = 0; shift < 64; shift += kDigitBits) {
    std::fill(offsets.begin(), offsets.end(), 0u);
    for (const std::uint64_t key : bits)
      ++offsets[(key >> shift) & (kDigits - 1)];
    if (count == 0 || offsets[(bits[0] >> shift) & (kDigits - 1)] == count) continue;  // one digit: in order
    std::uint32_t start = 0;
    for (std::uint32_t& offset : offsets)
      start += std::exchange(offset, start);
    for (std::size_t k = 0; k < count; ++k) {
      const std::uint32_t to = offsets[(bits[k] >> shift) & (kDigits - 1)]++;
      bitsOut[to] = bits[k];
      orderOut[to] = order[k];
    }
    bits.swap(bitsOut);
    order.swap(orderOut);
  }
  return order;
}

}  // namespace spindrift
