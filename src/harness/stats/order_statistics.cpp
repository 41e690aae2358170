#include <fgb/harness/stats/order_statistics.hpp>

#include <fgb/harness/base/parallel.hpp>

#include <algorithm>
#include <array>
#include <mutex>
#include <stdexcept>

namespace fgb::harness::detail {

std::vector<uint32_t> selectOrderKeys(std::size_t count, const OrderKeysOf& keysOf, const std::vector<std::size_t>& ranks) {
  constexpr std::size_t kBins = 1 << 16;
  for (std::size_t rank : ranks) {
    if (rank >= count) throw std::out_of_range("selectOrderKeys: rank beyond the data");
  }
  std::mutex mutex;
  // Runs count(keys, n, histogram) over all keys, chunk by chunk, with a histogram per worker that
  // is added to `total` (uint32 counts: flushed well before they could overflow).
  auto histogramPass = [&](std::size_t histograms, const auto& countKeys, std::vector<uint64_t>& total) {
    total.assign(histograms * kBins, 0);
    parallelFor(count, 1 << 16, [&](std::size_t begin, std::size_t end) {
      std::vector<uint32_t> local(histograms * kBins, 0);
      std::array<uint32_t, kOrderKeyChunk> keys{};
      auto flush = [&] {
        std::lock_guard lock(mutex);
        for (std::size_t i = 0; i < local.size(); ++i) total[i] += local[i];
        std::fill(local.begin(), local.end(), 0u);
      };
      std::size_t sinceFlush = 0;
      for (std::size_t b = begin; b < end; b += keys.size()) {
        const std::size_t e = std::min(end, b + keys.size());
        keysOf(b, e, keys.data());
        countKeys(keys.data(), e - b, local.data());
        sinceFlush += e - b;
        if (sinceFlush > (std::size_t{1} << 31)) {
          flush();
          sinceFlush = 0;
        }
      }
      flush();
    });
  };
  // Pass 1: the high 16 bits.
  std::vector<uint64_t> high;
  histogramPass(1, [](const uint32_t* keys, std::size_t n, uint32_t* h) {
    for (std::size_t i = 0; i < n; ++i) ++h[keys[i] >> 16];
  }, high);
  // The bin of each rank and the rank within that bin.
  std::vector<uint32_t> binOf(ranks.size());
  std::vector<uint64_t> rankInBin(ranks.size());
  std::vector<int> slotOfBin(kBins, -1);
  std::vector<uint32_t> slotBins;
  for (std::size_t r = 0; r < ranks.size(); ++r) {
    uint64_t before = 0;
    uint32_t bin = 0;
    while (before + high[bin] <= ranks[r]) before += high[bin++];
    binOf[r] = bin;
    rankInBin[r] = ranks[r] - before;
    if (slotOfBin[bin] < 0) {
      slotOfBin[bin] = static_cast<int>(slotBins.size());
      slotBins.push_back(bin);
    }
  }
  // Pass 2: the low 16 bits of the keys in those bins.
  std::vector<uint64_t> low;
  const int* slots = slotOfBin.data();
  histogramPass(slotBins.size(), [slots](const uint32_t* keys, std::size_t n, uint32_t* h) {
    for (std::size_t i = 0; i < n; ++i) {
      const int slot = slots[keys[i] >> 16];
      if (slot >= 0) ++h[static_cast<std::size_t>(slot) * kBins + (keys[i] & 0xffffu)];
    }
  }, low);
  std::vector<uint32_t> result(ranks.size());
  for (std::size_t r = 0; r < ranks.size(); ++r) {
    const uint64_t* h = low.data() + static_cast<std::size_t>(slotOfBin[binOf[r]]) * kBins;
    uint64_t before = 0;
    uint32_t value = 0;
    while (before + h[value] <= rankInBin[r]) before += h[value++];
    result[r] = (binOf[r] << 16) | value;
  }
  return result;
}

}  // namespace fgb::harness::detail
