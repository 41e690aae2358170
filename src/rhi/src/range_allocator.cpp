#include <fgb/rhi/range_allocator.hpp>

#include <iterator>
#include <stdexcept>
#include <string>

namespace fgb::rhi {

RangeAllocator::RangeAllocator(uint64_t size) : size_(size) {
  if (size > 0) free_.emplace(0, size);
}

std::optional<uint64_t> RangeAllocator::allocate(uint64_t size, uint64_t alignment) {
  if (size == 0 || alignment == 0 || (alignment & (alignment - 1)) != 0) return std::nullopt;
  for (auto it = free_.begin(); it != free_.end(); ++it) {
    const uint64_t start = it->first;
    const uint64_t end = start + it->second;
    const uint64_t aligned = (start + alignment - 1) & ~(alignment - 1);
    if (aligned >= end || end - aligned < size) continue;
    free_.erase(it);
    // The padding in front stays free; so does the tail behind the allocation.
    if (aligned > start) insertFree(start, aligned - start);
    if (aligned + size < end) insertFree(aligned + size, end - aligned - size);
    allocated_.emplace(aligned, size);
    used_ += size;
    return aligned;
  }
  return std::nullopt;
}

void RangeAllocator::free(uint64_t offset) {
  const auto it = allocated_.find(offset);
  if (it == allocated_.end()) {
    throw std::logic_error("RangeAllocator::free: no allocation at offset " + std::to_string(offset));
  }
  const uint64_t size = it->second;
  allocated_.erase(it);
  used_ -= size;
  insertFree(offset, size);
}

void RangeAllocator::insertFree(uint64_t offset, uint64_t size) {
  auto next = free_.lower_bound(offset);
  // Merge with the following free range when they touch.
  if (next != free_.end() && offset + size == next->first) {
    size += next->second;
    next = free_.erase(next);
  }
  // Merge with the preceding free range when they touch.
  if (next != free_.begin()) {
    auto previous = std::prev(next);
    if (previous->first + previous->second == offset) {
      previous->second += size;
      return;
    }
  }
  free_.emplace_hint(next, offset, size);
}

}  // namespace fgb::rhi
