// First-fit allocator of aligned ranges inside a fixed-size block, with coalescing frees. The
// device-memory sub-allocator uses one per memory block; pure logic, unit-tested.
#pragma once

#include <cstdint>
#include <map>
#include <optional>

namespace fgb::rhi {

class RangeAllocator {
 public:
  explicit RangeAllocator(uint64_t size);

  // Offset of a free range of `size` bytes aligned to `alignment` (a power of two), or nothing.
  std::optional<uint64_t> allocate(uint64_t size, uint64_t alignment);
  // Returns a range obtained from allocate(); throws std::logic_error on a double or foreign free.
  void free(uint64_t offset);

  [[nodiscard]] uint64_t size() const { return size_; }
  [[nodiscard]] uint64_t used() const { return used_; }
  [[nodiscard]] bool empty() const { return allocated_.empty(); }
  [[nodiscard]] size_t freeRanges() const { return free_.size(); }

 private:
  void insertFree(uint64_t offset, uint64_t size);

  uint64_t size_;
  uint64_t used_ = 0;
  std::map<uint64_t, uint64_t> free_;       // offset -> size, no two adjacent
  std::map<uint64_t, uint64_t> allocated_;  // offset -> size (including alignment padding)
};

}  // namespace fgb::rhi
