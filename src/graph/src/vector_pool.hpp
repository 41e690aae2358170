// Internal: per-thread pools of vector storage, reused across frames.
//
// A frame graph is declared and compiled every frame. Keeping the large arrays of one frame for
// the next saves their allocation and, for large graphs, the page faults of touching fresh memory
// (the allocator hands big blocks back to the kernel when they are freed, and faulting them in
// again costs more than the compile itself). Used for the compiler's temporaries (ScratchVector)
// and for a FrameGraph's own arrays; results handed to the caller stay plain vectors.
#pragma once

#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

namespace fgb::graph::detail {

template <typename T>
class VectorPool {
 public:
  // Moves a pooled buffer (with capacity; empty unless given with Keep::Elements) into `into`,
  // which must be empty.
  static void take(std::vector<T>& into) {
    if (closed_) return;
    auto& buffers = instance().buffers_;
    if (buffers.empty()) return;
    into.swap(buffers.back());
    buffers.pop_back();
  }

  // What give() keeps of a vector: only its storage, or its elements too (for elements that own
  // memory worth keeping, like strings; the next user must then overwrite or drop them).
  enum class Keep : uint8_t { Storage, Elements };

  // Keeps the storage of `from` (and with Keep::Elements its elements) for a later take(); `from`
  // is left empty.
  static void give(std::vector<T>& from, Keep keep = Keep::Storage) noexcept {
    if (from.capacity() == 0) return;
    if (keep == Keep::Storage) from.clear();
    if (closed_) return;  // the thread is exiting: let the vector free its storage
    auto& buffers = instance().buffers_;
    if (buffers.size() >= kMaxBuffers) return;
    try {
      buffers.push_back(std::move(from));
    } catch (...) {  // out of memory growing the pool: just free this buffer
    }
  }

 private:
  // More buffers alive at once than any compile needs of one type: the rest are simply freed.
  static constexpr size_t kMaxBuffers = 64;

  VectorPool() = default;
  ~VectorPool() { closed_ = true; }

  static VectorPool& instance() {
    thread_local VectorPool pool;
    return pool;
  }

  std::vector<std::vector<T>> buffers_;
  // Trivially destructible, so still readable while other thread-locals (or statics holding a
  // FrameGraph) are destroyed after the pool.
  static inline thread_local bool closed_ = false;
};

}  // namespace fgb::graph::detail
