// Rounding up to a multiple, for memory offsets and sizes.
#pragma once

#include <cstdint>

namespace fgb {

// `value` rounded up to a multiple of `alignment` (which must not be 0).
constexpr uint64_t alignUp(uint64_t value, uint64_t alignment) {
  return (value + alignment - 1) / alignment * alignment;
}

}  // namespace fgb
