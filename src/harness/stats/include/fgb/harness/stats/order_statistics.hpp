// Exact order statistics of large float arrays without sorting them (for the flip and metrics rooms):
// the percentiles of a 4K FLIP map and the median luminance of HDR-FLIP's exposure range.
#pragma once

#include <cstddef>
#include <cstdint>
#include <cstring>
#include <functional>
#include <vector>

namespace fgb::harness::detail {

// The sort key of a value: its IEEE bit pattern with the sign bit flipped for non-negative values
// and all bits flipped for negative ones, which orders keys like the values (-0 just below +0).
inline uint32_t orderKey(float v) {
  uint32_t bits;
  std::memcpy(&bits, &v, sizeof bits);
  return (bits & 0x80000000u) ? ~bits : (bits | 0x80000000u);
}

inline float fromOrderKey(uint32_t key) {
  const uint32_t bits = (key & 0x80000000u) ? (key & 0x7fffffffu) : ~key;
  float v;
  std::memcpy(&v, &bits, sizeof v);
  return v;
}

// Writes the keys of elements [begin, end) (at most kOrderKeyChunk of them) to `keys`.
inline constexpr std::size_t kOrderKeyChunk = 4096;
using OrderKeysOf = std::function<void(std::size_t begin, std::size_t end, uint32_t* keys)>;

// The keys at the given ranks (0-based positions in ascending order) among `count` keys: exactly
// what std::nth_element would put there. Two parallel passes over the data, each a histogram of
// 16 bits of the key (radix selection), instead of an O(n log n) sort or repeated selections.
std::vector<uint32_t> selectOrderKeys(std::size_t count, const OrderKeysOf& keysOf, const std::vector<std::size_t>& ranks);

}  // namespace fgb::harness::detail
