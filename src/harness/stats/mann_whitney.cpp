#include <fgb/harness/stats/mann_whitney.hpp>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <vector>

namespace fgb::harness {
namespace {

struct Ranked {
  double rankSumA = 0.0;
  double tieTerm = 0.0;  // sum over tie groups of (t^3 - t)
};

Ranked rankSum(std::span<const double> a, std::span<const double> b) {
  struct Item {
    double value;
    bool fromA;
  };
  std::vector<Item> items;
  items.reserve(a.size() + b.size());
  for (double v : a) items.push_back({v, true});
  for (double v : b) items.push_back({v, false});
  std::sort(items.begin(), items.end(), [](const Item& x, const Item& y) { return x.value < y.value; });

  Ranked ranked;
  std::size_t i = 0;
  while (i < items.size()) {
    std::size_t j = i;
    while (j < items.size() && items[j].value == items[i].value) ++j;
    const double tied = static_cast<double>(j - i);
    const double midRank = (static_cast<double>(i + 1) + static_cast<double>(j)) / 2.0;  // 1-based
    for (std::size_t k = i; k < j; ++k) {
      if (items[k].fromA) ranked.rankSumA += midRank;
    }
    ranked.tieTerm += tied * tied * tied - tied;
    i = j;
  }
  return ranked;
}

// Number of arrangements of na a's and nb b's with U = u, for every u: the recurrence
// f(n, m, u) = f(n-1, m, u-m) + f(n, m-1, u) (the largest element is an a, or a b). Returned as
// probabilities under the null hypothesis.
std::vector<double> exactUDistribution(std::size_t na, std::size_t nb) {
  const std::size_t maxU = na * nb;
  // table[n][m] is the distribution for n a's and m b's, kept for the current and previous n.
  std::vector<std::vector<double>> previous(nb + 1), current(nb + 1);
  for (std::size_t m = 0; m <= nb; ++m) previous[m] = {1.0};  // n = 0: only U = 0
  for (std::size_t n = 1; n <= na; ++n) {
    current[0] = {1.0};  // m = 0: only U = 0
    for (std::size_t m = 1; m <= nb; ++m) {
      std::vector<double> counts(n * m + 1, 0.0);
      const auto& withoutA = previous[m];   // largest is an a: it beats all m b's
      for (std::size_t u = 0; u < withoutA.size(); ++u) counts[u + m] += withoutA[u];
      const auto& withoutB = current[m - 1];  // largest is a b
      for (std::size_t u = 0; u < withoutB.size(); ++u) counts[u] += withoutB[u];
      current[m] = std::move(counts);
    }
    std::swap(previous, current);
  }
  std::vector<double> distribution = previous[nb];
  distribution.resize(maxU + 1, 0.0);
  double total = 0.0;
  for (double c : distribution) total += c;
  for (double& c : distribution) c /= total;
  return distribution;
}

void requireUsable(std::span<const double> group, const char* name) {
  if (group.empty()) throw std::invalid_argument(std::string("Mann-Whitney: group ") + name + " is empty");
  for (double v : group) {
    if (!std::isfinite(v)) throw std::invalid_argument(std::string("Mann-Whitney: group ") + name + " has a non-finite value");
  }
}

}  // namespace

double normalCdf(double x) { return 0.5 * std::erfc(-x / std::sqrt(2.0)); }

MannWhitneyResult mannWhitneyU(std::span<const double> a, std::span<const double> b) {
  requireUsable(a, "a");
  requireUsable(b, "b");
  const double na = static_cast<double>(a.size());
  const double nb = static_cast<double>(b.size());
  const Ranked ranked = rankSum(a, b);

  MannWhitneyResult result;
  result.uA = ranked.rankSumA - na * (na + 1.0) / 2.0;
  result.uB = na * nb - result.uA;

  const bool hasTies = ranked.tieTerm > 0.0;
  if (!hasTies && a.size() <= kMannWhitneyExactLimit && b.size() <= kMannWhitneyExactLimit) {
    const auto distribution = exactUDistribution(a.size(), b.size());
    const auto u = static_cast<std::size_t>(std::llround(result.uA));
    double atMost = 0.0;
    for (std::size_t k = 0; k <= u; ++k) atMost += distribution[k];
    double atLeast = 0.0;
    for (std::size_t k = u; k < distribution.size(); ++k) atLeast += distribution[k];
    result.exact = true;
    result.pAGreater = std::min(1.0, atLeast);
    result.pALess = std::min(1.0, atMost);
  } else {
    const double n = na + nb;
    const double mean = na * nb / 2.0;
    const double variance = na * nb / 12.0 * ((n + 1.0) - ranked.tieTerm / (n * (n - 1.0)));
    if (variance <= 0.0) return result;  // every value equal: no evidence either way
    const double sigma = std::sqrt(variance);
    // Continuity correction: U moves in steps of 1/2 with ties, 1 without; 0.5 is the usual choice.
    result.z = (result.uA - mean) / sigma;
    result.pAGreater = 1.0 - normalCdf((result.uA - 0.5 - mean) / sigma);
    result.pALess = normalCdf((result.uA + 0.5 - mean) / sigma);
  }
  result.pAGreater = std::clamp(result.pAGreater, 0.0, 1.0);
  result.pALess = std::clamp(result.pALess, 0.0, 1.0);
  result.pTwoSided = std::min(1.0, 2.0 * std::min(result.pAGreater, result.pALess));
  return result;
}

}  // namespace fgb::harness
