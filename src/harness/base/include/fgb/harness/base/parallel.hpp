// Row-parallel loops over std::thread: the image metrics are embarrassingly parallel per row.
#pragma once

#include <cstddef>
#include <functional>

namespace fgb::harness {

// Worker count: hardware threads, overridable with FGBENCH_THREADS (1 = serial, for profiling).
unsigned workerCount();

// Calls body(begin, end) on disjoint chunks covering [0, count), on up to workerCount() threads.
// Chunks are at least `minChunk` long so tiny loops stay on the calling thread. Exceptions from a
// worker are rethrown on the calling thread.
void parallelFor(std::size_t count, std::size_t minChunk,
                 const std::function<void(std::size_t begin, std::size_t end)>& body);

}  // namespace fgb::harness
