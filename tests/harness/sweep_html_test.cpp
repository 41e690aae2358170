// The sweep report's plot (sweep.html): its axis ticks and duration labels, and where it places
// the points' labels (label_placement.hpp) so that none covers another label or a point.
#include <gtest/gtest.h>

#include <cmath>
#include <fgb/harness/report/html_util.hpp>
#include <string>
#include <utility>
#include <vector>

#include "label_placement.hpp"

namespace fgb::harness {
namespace {

TEST(SweepHtml, TicksAreDecimalsAndDurationsHaveUnits) {
  EXPECT_EQ(durationLabel(2380.0), "2.4 s");
  EXPECT_EQ(durationLabel(380.0), "380 ms");
  EXPECT_EQ(durationLabel(0.9), "0.9 ms");
  EXPECT_EQ(durationLabel(0.05), "50 µs");
  EXPECT_EQ(durationLabel(2000.0), "2 s");
  EXPECT_EQ(tickLabel(0.0005), "0.0005");
  EXPECT_EQ(tickLabel(2000.0), "2000");
  EXPECT_EQ(tickLabel(0.02), "0.02");
  // A narrow range still gets two 1-2-5 ticks, each a 1, 2 or 5 times a power of ten.
  for (const auto& [lo, hi] : {std::pair{2300.0, 2450.0}, std::pair{0.0031, 0.0033}, std::pair{0.9, 1.1}}) {
    const LogAxis axis = paddedLogAxis(lo, hi);
    EXPECT_LE(axis.lo, lo);
    EXPECT_GE(axis.hi, hi);
    const auto ticks = axis.ticks();
    ASSERT_GE(ticks.size(), 2u) << lo << ".." << hi;
    for (double t : ticks) {
      const double mantissa = t / std::pow(10.0, std::floor(std::log10(t) + 1e-9));
      EXPECT_TRUE(std::abs(mantissa - 1) < 1e-6 || std::abs(mantissa - 2) < 1e-6 || std::abs(mantissa - 5) < 1e-6) << t;
      EXPECT_EQ(tickLabel(t).find('e'), std::string::npos) << t;
    }
  }
}

TEST(SweepHtml, LabelsOfCrowdedPointsDoNotOverlap) {
  // 16 points in four tight clusters, as a sweep of MSAA x a speed-only knob draws them.
  std::vector<LabelRequest> requests;
  for (int cluster = 0; cluster < 4; ++cluster) {
    for (int k = 0; k < 4; ++k) {
      const std::string text =
          "msaa=" + std::to_string(1 << cluster) + " lighting.max_per_cluster=" + std::to_string(4 << (2 * k));
      requests.push_back({200.0 + 150 * cluster + 3 * k, 300.0 - 60 * cluster - 2 * k, text,
                          std::to_string(requests.size() + 1), k == 0, k == 0});
    }
  }
  const LabelBox area{80, 30, 850, 450};
  const auto labels = placeLabels(requests, area);
  ASSERT_EQ(labels.size(), requests.size());
  std::size_t full = 0;
  for (std::size_t i = 0; i < labels.size(); ++i) {
    if (requests[i].priority) {
      EXPECT_TRUE(labels[i].shown && !labels[i].numbered) << "front label " << i << " not shown in full";
    }
    if (!labels[i].shown) continue;
    full += labels[i].numbered ? 0 : 1;
    EXPECT_TRUE(labels[i].box.inside(area)) << i;
    EXPECT_GE(labels[i].box.x1 - labels[i].box.x0 + 1e-9, estimateTextWidth(labels[i].text, 12, requests[i].bold));
    for (std::size_t j = 0; j < requests.size(); ++j) {
      const LabelBox marker{requests[j].x - 6, requests[j].y - 6, requests[j].x + 6, requests[j].y + 6};
      EXPECT_FALSE(labels[i].box.overlaps(marker)) << "label " << i << " covers point " << j;
      if (j > i && labels[j].shown) {
        EXPECT_FALSE(labels[i].box.overlaps(labels[j].box)) << i << " and " << j;
      }
    }
  }
  EXPECT_GE(full, 8u);  // most labels fit in full; the rest are numbered, not dropped
}

TEST(SweepHtml, LabelsThatFindNoPlaceBecomeNumbersAndStillDoNotOverlap) {
  // 24 points on one spot of a small plot: not every long label fits around it.
  std::vector<LabelRequest> requests;
  for (int i = 0; i < 24; ++i) {
    requests.push_back({300, 200, "msaa=8 lighting.max_per_cluster=" + std::to_string(1000 + i), std::to_string(i + 1),
                        false, i == 0});
  }
  const LabelBox area{80, 30, 600, 400};
  const auto labels = placeLabels(requests, area);
  std::size_t numbered = 0;
  for (std::size_t i = 0; i < labels.size(); ++i) {
    if (labels[i].numbered && labels[i].shown) {
      ++numbered;
      EXPECT_EQ(labels[i].text, requests[i].number);
    }
    for (std::size_t j = i + 1; j < labels.size(); ++j) {
      if (labels[i].shown && labels[j].shown) {
        EXPECT_FALSE(labels[i].box.overlaps(labels[j].box)) << i << " and " << j;
      }
    }
  }
  EXPECT_FALSE(labels[0].numbered);  // the priority (front) label is placed first, in full
  EXPECT_GT(numbered, 0u);
}

}  // namespace
}  // namespace fgb::harness
