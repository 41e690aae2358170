// Point labels for the inline SVG scatter plots (sweep.html's time against error): each label is put
// where it overlaps no other label and no point marker, nearest its point first, with a leader line
// when it had to move away from it. A label that finds no free place is shown as its number instead
// (and the chart lists the numbers); one whose number finds none either is not drawn (its point keeps
// its tooltip). So labels never overlap.
#pragma once

#include <string>
#include <vector>

namespace fgb::harness {

struct LabelBox {
  double x0 = 0, y0 = 0, x1 = 0, y1 = 0;
  [[nodiscard]] bool overlaps(const LabelBox& other) const {
    return x0 < other.x1 && other.x0 < x1 && y0 < other.y1 && other.y0 < y1;
  }
  [[nodiscard]] bool inside(const LabelBox& area) const {
    return x0 >= area.x0 && x1 <= area.x1 && y0 >= area.y0 && y1 <= area.y1;
  }
};

struct LabelRequest {
  double x = 0, y = 0;  // the point, in SVG units
  std::string text;     // the full label
  std::string number;   // the short label used where the full one does not fit ("3")
  bool bold = false;
  bool priority = false;  // placed before the others (front points)
};

struct PlacedLabel {
  std::string text;            // what is drawn: the full label or its number
  bool numbered = false;       // the full label did not fit: `text` is the number
  bool shown = true;           // false: not even the number found a free place; nothing is drawn
  LabelBox box;                // the estimated extent of the text
  double x = 0, baseline = 0;  // where the <text> goes (text-anchor="start", at box.x0)
  bool leader = false;         // far enough from its point to need a line to it
};

// Width of `text` in pixels at `fontSize` in DejaVu Sans (Chromium's sans-serif on Debian), from its
// advance widths rounded up; bold adds 10%. An estimate on the safe side, not a measurement.
double estimateTextWidth(const std::string& text, double fontSize, bool bold);

// Places every label inside `area` (priority labels first, then in the given order), avoiding the
// other labels and every point's marker (a square of `markerRadius` around each point). Each
// request gets one PlacedLabel, in request order; no two placed boxes overlap.
std::vector<PlacedLabel> placeLabels(const std::vector<LabelRequest>& requests, const LabelBox& area,
                                     double fontSize = 12, double markerRadius = 6);

}  // namespace fgb::harness
