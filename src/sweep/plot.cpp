#include "sweep/plot.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>

#include "sweep/canvas.h"
#include "units/catalogue.h"

namespace glint {
namespace {

constexpr int kWidth = 1120, kHeight = 720;
// The plot area and, right of it, the legend and the key to the front's numbers.
constexpr double kLeft = 86, kRight = 770, kTop = 70, kBottom = 636;
constexpr double kPanel = 792;
constexpr Rgb8 kWhite{255, 255, 255}, kInk{34, 34, 34}, kGrid{230, 230, 230}, kFrame{120, 120, 120},
    kDominated{190, 190, 190}, kStep{60, 60, 60};

// One colour per unit family, in catalogue order (Tableau's first five: distinct in print and for
// the common colour-vision deficiencies); families beyond them share the sixth.
Rgb8 family_colour(const std::string& unit) {
  static const Rgb8 kColours[] = {{31, 119, 180}, {255, 127, 14},  {44, 160, 44},
                                  {214, 39, 40},  {148, 103, 189}, {140, 86, 75}};
  const std::vector<std::string> names = unit_names();
  const auto it = std::find(names.begin(), names.end(), unit);
  const auto i = static_cast<std::size_t>(it - names.begin());
  return kColours[std::min<std::size_t>(i, 5)];
}

// "0.002", "150", "2e-05" -> "2e-5": short labels for log ticks.
std::string tick_label(double v) {
  if (v >= 1e-3 && v < 1e5) return fmt::format("{:g}", v);
  const int e = static_cast<int>(std::floor(std::log10(v) + 1e-9));
  const double m = v / std::pow(10.0, e);
  return std::lround(m) == 1 ? fmt::format("1e{}", e) : fmt::format("{:g}e{}", std::round(m), e);
}

// A log10 axis over positive values, at least one decade wide, padded by 4 % of its span.
struct LogAxis {
  double lo = 0, hi = 1;  // log10 of the ends

  static LogAxis over(const std::vector<double>& v) {
    LogAxis a;
    if (v.empty()) return a;
    a.lo = std::log10(*std::min_element(v.begin(), v.end()));
    a.hi = std::log10(*std::max_element(v.begin(), v.end()));
    if (a.hi - a.lo < 1) {
      const double mid = (a.lo + a.hi) / 2;
      a.lo = mid - 0.5;
      a.hi = mid + 0.5;
    }
    const double pad = 0.04 * (a.hi - a.lo);
    a.lo -= pad;
    a.hi += pad;
    return a;
  }
  // Position of v between pixel p0 (lo) and p1 (hi).
  double at(double v, double p0, double p1) const {
    return p0 + (std::log10(v) - lo) / (hi - lo) * (p1 - p0);
  }
  // 1, 2, 5 x 10^k within the axis (only the powers of ten beyond three decades).
  std::vector<double> ticks() const {
    std::vector<double> out;
    const bool fine = hi - lo <= 3;
    for (int d = static_cast<int>(std::floor(lo)); d <= static_cast<int>(std::ceil(hi)); ++d)
      for (double m : {1.0, 2.0, 5.0}) {
        if (!fine && m != 1.0) continue;
        const double v = m * std::pow(10.0, d);
        if (std::log10(v) >= lo && std::log10(v) <= hi) out.push_back(v);
      }
    return out;
  }
};

struct PlotKind {
  const char* name;
  const char* x_key;
  const char* pareto;
  const char* title;
  const char* x_label;
  bool minimise_x;
};
constexpr PlotKind kPlots[] = {
    {"error_vs_area", "area_ge", "area", "Error vs area", "area (gate equivalents, log scale)",
     true},
    {"error_vs_throughput", "throughput", "throughput", "Error vs throughput",
     "throughput on this stream (results per cycle, log scale)", false},
};

struct Point {
  double x, y;  // y <= 0: drawn on the zero line below the log axis
  bool front;
  std::string unit, spec;
};

std::string error_label(const nlohmann::json& report) {
  const std::string m = report.at("error_measure").get<std::string>();
  const int bits = report.at("display_bits").get<int>();
  if (m.find("lsb") != std::string::npos && !std::isdigit(static_cast<unsigned char>(m.back())))
    return fmt::format("error: {} ({}-bit LSB, log scale)", m, bits);
  return fmt::format("error: {} (log scale)", m);
}

void draw(Canvas& c, const nlohmann::json& report, const PlotKind& kind, SweepPlot& out) {
  std::vector<Point> pts;
  for (const nlohmann::json& row : report.at("results")) {
    const nlohmann::json x = row.value(kind.x_key, nlohmann::json());  // refused: none
    const nlohmann::json& y = row.at("error");
    if (!x.is_number() || !y.is_number() || !(x.get<double>() > 0)) continue;
    pts.push_back({x.get<double>(), y.get<double>(), row.at("pareto").at(kind.pareto).get<bool>(),
                   row.at("unit").get<std::string>(), row.at("spec").get<std::string>()});
  }
  out.points = pts.size();
  std::vector<double> xs, ys;
  bool zero = false;
  for (const Point& p : pts) {
    xs.push_back(p.x);
    if (p.y > 0) {
      ys.push_back(p.y);
    } else {
      zero = true;
    }
  }
  const LogAxis ax = LogAxis::over(xs), ay = LogAxis::over(ys);
  // With zero errors the log axis stops 28 pixels above the bottom and a "0" line sits below it.
  const double y_log_bottom = zero ? kBottom - 28 : kBottom;
  const double y_zero = kBottom - 10;
  const auto px = [&](double x) { return ax.at(x, kLeft, kRight); };
  const auto py = [&](double y) { return y > 0 ? ay.at(y, y_log_bottom, kTop) : y_zero; };

  // Title and axes.
  const std::string input = report.at("input").at("path").get<std::string>();
  c.text(kLeft, 14, fmt::format("{}: {} ({} configurations)", kind.title, input, pts.size()), 17,
         kInk);
  c.text(kLeft, 44, error_label(report), 13, kInk);
  c.rect(kLeft, kTop, kRight, kBottom, {250, 250, 250});
  for (double t : ax.ticks()) {
    const double x = px(t);
    c.line(x, kTop, x, kBottom, kGrid, 1);
    c.line(x, kBottom, x, kBottom + 5, kFrame, 1);
    c.text(x, kBottom + 8, tick_label(t), 12, kInk, TextAnchor::kMiddle);
  }
  for (double t : ys.empty() ? std::vector<double>{} : ay.ticks()) {
    const double y = py(t);
    c.line(kLeft, y, kRight, y, kGrid, 1);
    c.line(kLeft - 5, y, kLeft, y, kFrame, 1);
    c.text(kLeft - 8, y - 7, tick_label(t), 12, kInk, TextAnchor::kEnd);
  }
  if (zero) {
    c.line(kLeft, y_zero, kRight, y_zero, kGrid, 1);
    c.line(kLeft - 5, y_zero, kLeft, y_zero, kFrame, 1);
    c.text(kLeft - 8, y_zero - 7, "0", 12, kInk, TextAnchor::kEnd);
    c.line(kLeft, y_log_bottom + 9, kRight, y_log_bottom + 9, kFrame, 1);  // the axis break
  }
  c.line(kLeft, kTop, kLeft, kBottom, kFrame, 1);
  c.line(kLeft, kBottom, kRight, kBottom, kFrame, 1);
  c.line(kLeft, kTop, kRight, kTop, kFrame, 1);
  c.line(kRight, kTop, kRight, kBottom, kFrame, 1);
  c.text((kLeft + kRight) / 2, kBottom + 30, kind.x_label, 13, kInk, TextAnchor::kMiddle);

  // Dominated points first, then the front over them.
  for (const Point& p : pts)
    if (!p.front) c.circle(px(p.x), py(p.y), 3, kDominated, "point dominated");
  std::vector<const Point*> front;
  for (const Point& p : pts)
    if (p.front) front.push_back(&p);
  std::sort(front.begin(), front.end(), [](const Point* a, const Point* b) {
    return a->x != b->x ? a->x < b->x : a->y > b->y;
  });
  out.front = front.size();
  // The step line: between neighbours, through the corner at the worse x and the worse y of the
  // two (the edge of the region the front dominates).
  for (std::size_t i = 0; i + 1 < front.size(); ++i) {
    const Point& a = *front[i];
    const Point& b = *front[i + 1];
    const double cx = kind.minimise_x ? b.x : a.x;
    const double cy = std::max(a.y, b.y);
    c.line(px(a.x), py(a.y), px(cx), py(cy), kStep, 1.5);
    c.line(px(cx), py(cy), px(b.x), py(b.y), kStep, 1.5);
  }
  for (std::size_t i = 0; i < front.size();) {
    // Front points that land on the same spot (equal values) share one label, "3-5".
    std::size_t j = i + 1;
    while (j < front.size() && std::abs(px(front[j]->x) - px(front[i]->x)) < 1 &&
           std::abs(py(front[j]->y) - py(front[i]->y)) < 1)
      ++j;
    for (std::size_t k = i; k < j; ++k) {
      const Point& p = *front[k];
      c.circle(px(p.x), py(p.y), 6, kInk);
      c.circle(px(p.x), py(p.y), 4.8, family_colour(p.unit), "point front");
    }
    const std::string label = j == i + 1 ? std::to_string(i + 1) : fmt::format("{}-{}", i + 1, j);
    c.text(px(front[i]->x) + 7, py(front[i]->y) - 17, label, 12, kInk);
    i = j;
  }

  // Legend: the families present, dominated points, the front.
  std::vector<std::string> families;
  for (const std::string& name : unit_names())
    if (std::any_of(pts.begin(), pts.end(), [&](const Point& p) { return p.unit == name; }))
      families.push_back(name);
  double y = kTop;
  c.text(kPanel, y, "unit family (front points)", 13, kInk);
  y += 22;
  for (const std::string& f : families) {
    c.circle(kPanel + 6, y + 7, 5, family_colour(f));
    c.text(kPanel + 18, y, f, 12, kInk);
    y += 18;
  }
  c.circle(kPanel + 6, y + 7, 3, kDominated);
  c.text(kPanel + 18, y, "dominated configuration", 12, kInk);
  y += 18;
  c.line(kPanel, y + 7, kPanel + 12, y + 7, kStep, 1.5);
  c.text(kPanel + 18, y, "Pareto front", 12, kInk);
  y += 30;
  c.text(kPanel, y, fmt::format("front: {} of {}", front.size(), pts.size()), 13, kInk);
  y += 22;
  const double max_width = kWidth - 8 - (kPanel + 24);
  for (std::size_t i = 0; i < front.size(); ++i) {
    if (y > kHeight - 36 && i + 1 < front.size()) {
      c.text(kPanel, y, fmt::format("... and {} more (see the CSV)", front.size() - i), 12, kInk);
      break;
    }
    c.text(kPanel + 18, y, std::to_string(i + 1), 12, family_colour(front[i]->unit),
           TextAnchor::kEnd);
    c.text(kPanel + 24, y, fit_text(front[i]->spec, static_cast<int>(max_width), 12), 12, kInk);
    y += 17;
  }
}

}  // namespace

std::vector<SweepPlot> sweep_plots(const nlohmann::json& report, bool png) {
  std::vector<SweepPlot> out;
  for (const PlotKind& kind : kPlots) {
    SweepPlot plot;
    plot.name = kind.name;
    SvgCanvas svg(kWidth, kHeight, kWhite);
    draw(svg, report, kind, plot);
    plot.svg = svg.finish();
    if (png) {
      ImageCanvas image(kWidth, kHeight, kWhite);
      draw(image, report, kind, plot);
      plot.png = image.image();
    }
    out.push_back(std::move(plot));
  }
  return out;
}

}  // namespace glint
