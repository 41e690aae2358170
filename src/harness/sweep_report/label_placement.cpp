// Greedy label placement: candidates on rings of growing radius around each point, the first free
// one wins (see label_placement.hpp).
#include "label_placement.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>

namespace fgb::harness {
namespace {

constexpr double kPi = 3.14159265358979323846;
// Radii tried around a point, nearest first; beyond the first a leader line joins label and point.
constexpr double kRadii[] = {9, 20, 34, 52, 76, 104, 140};
constexpr int kDirections = 16;
constexpr double kLeaderFrom = 15;  // a label whose box starts farther than this gets a leader line

// Advance width in em of one DejaVu Sans character (units per em 2048), rounded up.
double advanceEm(char c) {
  if (c >= '0' && c <= '9') return 0.64;
  if (c == '=' || c == '+' || c == '<' || c == '>') return 0.84;
  if (c == '.' || c == ',' || c == ' ' || c == ':' || c == ';') return 0.32;
  if (c == 'i' || c == 'l' || c == 'j' || c == '|' || c == '\'') return 0.28;
  if (c == 'f' || c == 't' || c == 'r' || c == '-' || c == '(' || c == ')') return 0.42;
  if (c == 'm') return 0.98;
  if (c == 'w') return 0.82;
  if (c == '_') return 0.5;
  if (c >= 'A' && c <= 'Z') return 0.78;
  return 0.64;  // other lowercase letters (at most 0.64 em) and anything else
}

// The box of a label whose nearest corner or side sits at distance `radius` from the point in
// direction `angle` (so the label grows away from the point).
LabelBox boxAround(double x, double y, double width, double height, double radius, double angle) {
  const double dx = std::cos(angle), dy = -std::sin(angle);  // SVG y grows downwards
  const double ax = x + radius * dx, ay = y + radius * dy;
  double x0 = ax - width / 2, y0 = ay - height / 2;
  if (dx > 0.35) x0 = ax;
  if (dx < -0.35) x0 = ax - width;
  if (dy > 0.35) y0 = ay;
  if (dy < -0.35) y0 = ay - height;
  return {x0, y0, x0 + width, y0 + height};
}

// Directions to try, the preferred first: up-right, right, down-right, up, down, then the left side.
std::vector<double> preferredAngles() {
  std::vector<double> angles;
  for (int k = 0; k < kDirections; ++k) angles.push_back(2 * kPi * k / kDirections);
  const auto preference = [](double a) {
    const double upRight = kPi / 6;
    double d = std::fmod(std::abs(a - upRight), 2 * kPi);
    return std::min(d, 2 * kPi - d);
  };
  std::stable_sort(angles.begin(), angles.end(), [&](double a, double b) { return preference(a) < preference(b); });
  return angles;
}

bool isFree(const LabelBox& box, const LabelBox& area, const std::vector<LabelBox>& taken) {
  if (!box.inside(area)) return false;
  return std::none_of(taken.begin(), taken.end(), [&](const LabelBox& t) { return box.overlaps(t); });
}

}  // namespace

double estimateTextWidth(const std::string& text, double fontSize, bool bold) {
  double em = 0;
  for (char c : text) em += advanceEm(c);
  return em * fontSize * (bold ? 1.1 : 1.0) + 2;
}

std::vector<PlacedLabel> placeLabels(const std::vector<LabelRequest>& requests, const LabelBox& area, double fontSize,
                                     double markerRadius) {
  // Obstacles: every point's marker, then each label as it is placed.
  std::vector<LabelBox> taken;
  for (const auto& r : requests) {
    taken.push_back({r.x - markerRadius, r.y - markerRadius, r.x + markerRadius, r.y + markerRadius});
  }
  std::vector<std::size_t> order(requests.size());
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(),
                   [&](std::size_t a, std::size_t b) { return requests[a].priority && !requests[b].priority; });

  const std::vector<double> angles = preferredAngles();
  const double height = std::ceil(fontSize * 1.2);
  auto tryPlace = [&](const LabelRequest& r, const std::string& text, PlacedLabel& out) {
    const double width = estimateTextWidth(text, fontSize, r.bold);
    for (double radius : kRadii) {
      for (double angle : angles) {
        const LabelBox box = boxAround(r.x, r.y, width, height, radius, angle);
        if (!isFree(box, area, taken)) continue;
        taken.push_back(box);
        out.text = text;
        out.box = box;
        out.x = box.x0;
        out.baseline = box.y0 + fontSize * 0.92;  // DejaVu Sans ascent above the baseline
        out.leader = radius > kLeaderFrom;
        return true;
      }
    }
    return false;
  };

  std::vector<PlacedLabel> placed(requests.size());
  for (std::size_t i : order) {
    const LabelRequest& r = requests[i];
    if (tryPlace(r, r.text, placed[i])) continue;
    placed[i].numbered = true;
    if (!tryPlace(r, r.number, placed[i])) placed[i].shown = false;
  }
  return placed;
}

}  // namespace fgb::harness
