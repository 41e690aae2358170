#include <fgb/harness/base/parallel.hpp>

#include <algorithm>
#include <cstdlib>
#include <exception>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

namespace fgb::harness {

unsigned workerCount() {
  if (const char* forced = std::getenv("FGBENCH_THREADS")) {
    try {
      const int n = std::stoi(forced);
      if (n >= 1) return static_cast<unsigned>(n);
    } catch (const std::exception&) {
      // Not a number: fall back to the hardware count.
    }
  }
  return std::max(1u, std::thread::hardware_concurrency());
}

void parallelFor(std::size_t count, std::size_t minChunk,
                 const std::function<void(std::size_t begin, std::size_t end)>& body) {
  if (count == 0) return;
  const std::size_t maxWorkers = std::max<std::size_t>(1, count / std::max<std::size_t>(1, minChunk));
  const std::size_t workers = std::min<std::size_t>(workerCount(), maxWorkers);
  if (workers <= 1) {
    body(0, count);
    return;
  }
  const std::size_t chunk = (count + workers - 1) / workers;
  std::exception_ptr failure;
  std::mutex failureMutex;
  auto run = [&](std::size_t begin, std::size_t end) {
    try {
      body(begin, end);
    } catch (...) {
      std::lock_guard lock(failureMutex);
      if (!failure) failure = std::current_exception();
    }
  };
  std::vector<std::thread> threads;
  threads.reserve(workers - 1);
  for (std::size_t w = 1; w < workers; ++w) {
    const std::size_t begin = w * chunk;
    const std::size_t end = std::min(count, begin + chunk);
    if (begin < end) threads.emplace_back(run, begin, end);
  }
  run(0, std::min(count, chunk));  // the calling thread takes the first chunk
  for (auto& t : threads) t.join();
  if (failure) std::rethrow_exception(failure);
}

}  // namespace fgb::harness
