// Collapse area factors from a rectified side view: the filament's underside per column.
#include "postprocess/measure/measure_collapse.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <iomanip>
#include <opencv2/imgproc.hpp>
#include <sstream>

#include "postprocess/measure/collapse_side_view.h"
#include "slicer/input_error.h"

namespace strand::post::measure {

namespace {

// Ink from half way between the backdrop and the pillars' ink.
constexpr float kInkShare = 0.5f;
// A run of ink thinner than this many nozzles is noise, not the filament.
constexpr double kLeastRunNozzles = 0.2;
// The underside is looked for from this many nozzles above the silhouette's top, down to the
// bed, and that far below the bed line ink counts as lying on the bed.
constexpr double kAboveNozzles = 1.0;
constexpr double kBedNozzles = 0.25;
// The gap's columns start this far (at least) inside the pillars' faces, clear of their edge.
constexpr double kInsetPx = 2.0;

struct Gap {
  int index = 0;
  double gap_mm = 0.0;
  double x0 = 0.0, x1 = 0.0;  // the pillars' faces
};

struct Layout {
  std::vector<Gap> gaps;
  PillarRow row;
  double pillar_height_mm = 0.0;  // under the filament: its intended underside
};

Layout layout_of(const nlohmann::json& derived, const std::string& what) {
  Layout l;
  try {
    for (const auto& g : derived.at("gaps")) {
      l.gaps.push_back({g.at("index").get<int>(), g.at("gap_mm"), g.at("start_mm")[0], g.at("end_mm")[0]});
    }
    l.pillar_height_mm = derived.at("pillar_height_mm").get<double>();
    l.row.top_mm = derived.at("filament_z_mm").get<double>();
    l.row.nozzle_mm = derived.at("nozzle_mm").get<double>();
    // Reports from before pillar_mm was written: the pillar between the first two gaps.
    l.row.side_mm = derived.contains("pillar_mm") ? derived.at("pillar_mm").get<double>()
                    : l.gaps.size() >= 2         ? l.gaps[1].x0 - l.gaps[0].x1
                                                 : 0.0;
    if (derived.contains("fiducials")) l.row.marks = fiducials_of(derived, what);
  } catch (const nlohmann::json::exception&) {
    throw InputError(what + ": the job report lacks derived gaps, pillar_mm, pillar_height_mm, filament_z_mm or nozzle_mm");
  }
  // A row a machine can print: sizes positive and under a metre, gaps in order along x.
  const auto sane = [](double v) { return v > 0 && v < 1000; };
  bool ok = !l.gaps.empty() && l.gaps.size() <= 100 && sane(l.row.side_mm) && sane(l.row.nozzle_mm) &&
            sane(l.pillar_height_mm) && sane(l.row.top_mm) && l.row.top_mm > l.pillar_height_mm;
  for (std::size_t k = 0; ok && k < l.gaps.size(); ++k) {
    ok = std::abs(l.gaps[k].x0) < 1000 && sane(l.gaps[k].x1 - l.gaps[k].x0) &&
         (k == 0 || l.gaps[k].x0 >= l.gaps[k - 1].x1 + l.row.side_mm - 1e-6);
  }
  if (!ok) throw InputError(what + ": the job report's derived gaps and pillars do not describe a row of pillars");
  l.row.left_mm.push_back(l.gaps.front().x0 - l.row.side_mm);
  for (const auto& g : l.gaps) l.row.left_mm.push_back(g.x1);
  return l;
}

// One gap measured: the underside per column (NAN where no filament was found).
struct GapResult {
  std::vector<cv::Point2d> underside_mm;  // (x, z); z NAN where missing
  double area_factor_pct = 0.0;
  double max_sag_mm = 0.0;
  double found_share = 0.0;
  std::string cls;
};

// The bottom of the topmost run of ink (at least `least_run` pixels) in column `col`, from
// row `from` down: its z in mm (sub-pixel, where the ink share crosses one half), 0 when the
// run reaches row `bed`, NAN when there is no run above it.
double underside_at(const SideView& v, int col, int from, int bed, int least_run) {
  int run = 0;
  for (int r = std::max(0, from); r < v.ink.rows; ++r) {
    const float here = v.ink.at<float>(r, col);
    if (here >= kInkShare) {
      if (++run >= least_run && r >= bed) return 0.0;
      continue;
    }
    if (run >= least_run) {
      const float above = v.ink.at<float>(r - 1, col);
      const double row = r - 1 + (above - kInkShare) / std::max(1e-6f, above - here);
      return std::max(0.0, v.z_of(row));
    }
    run = 0;
    if (r >= bed) break;
  }
  return NAN;
}

// The underside per column between the faces, kept clear of their blur; the area under it by
// trapezoids, from the faces' top edges (where a filament that holds leaves the pillars) to the
// first and last columns, or from the bed where the filament is missing there.
GapResult measure_gap(const SideView& v, const Gap& g, const Layout& l) {
  const double nozzle = l.row.nozzle_mm, h = l.pillar_height_mm;
  const double inset = std::min(std::max(kInsetPx / v.px_per_mm, 0.5 * v.edge_mm), 0.25 * (g.x1 - g.x0));
  int c0 = static_cast<int>(std::ceil(v.to_px(g.x0 + inset, 0).x));
  int c1 = static_cast<int>(std::floor(v.to_px(g.x1 - inset, 0).x));
  c0 = std::clamp(c0, 0, v.ink.cols - 1);
  c1 = std::clamp(std::max(c0, c1), 0, v.ink.cols - 1);
  const int from = static_cast<int>(v.to_px(0, l.row.top_mm + kAboveNozzles * nozzle).y);
  const int bed = static_cast<int>(v.to_px(0, -kBedNozzles * nozzle).y);
  const int least_run = std::max(2, static_cast<int>(std::lround(kLeastRunNozzles * nozzle * v.px_per_mm)));
  GapResult out;
  std::vector<double> found;
  for (int c = c0; c <= c1; ++c) {
    const double z = underside_at(v, c, from, bed, least_run);
    out.underside_mm.push_back({v.x_of(c), z});
    if (!std::isnan(z)) found.push_back(z);
  }
  const auto& u = out.underside_mm;
  const auto held = [&](const cv::Point2d& p) { return std::isnan(p.y) ? 0.0 : std::min(p.y, h); };
  std::vector<cv::Point2d> profile = {{g.x0, std::isnan(u.front().y) ? 0.0 : h}};
  for (const auto& p : u) profile.push_back({p.x, held(p)});
  profile.push_back({g.x1, std::isnan(u.back().y) ? 0.0 : h});
  double area = 0.0;
  for (std::size_t i = 1; i < profile.size(); ++i) {
    area += (profile[i].x - profile[i - 1].x) * (profile[i].y + profile[i - 1].y) / 2;
  }
  out.found_share = static_cast<double>(found.size()) / static_cast<double>(u.size());
  out.area_factor_pct = std::clamp(100.0 * area / ((g.x1 - g.x0) * h), 0.0, 100.0);
  out.max_sag_mm = found.empty() ? h : std::max(0.0, h - percentile(found, 0.02));
  out.cls = out.found_share < 1 - kBrokenShare                 ? "broken"
            : out.area_factor_pct >= kSpansAreaFactorPct ? "spans"
                                                          : "collapsed";
  return out;
}

std::string fixed(double v, int digits) {
  std::ostringstream o;
  o << std::fixed << std::setprecision(digits) << v;
  return o.str();
}

// The gap on the overlay: the intended underside (green), the one found (red; magenta ticks
// on the bed where none was), and the class letter with Cf above.
void draw_gap(cv::Mat& img, const SideView& v, const Gap& g, const GapResult& m, const Layout& l) {
  const auto px = [&](double x, double z) {
    const cv::Point2d p = v.to_px(x, z);
    return cv::Point(static_cast<int>(std::lround(p.x)), static_cast<int>(std::lround(p.y)));
  };
  cv::line(img, px(g.x0, l.pillar_height_mm), px(g.x1, l.pillar_height_mm), {40, 180, 40}, 1, cv::LINE_AA);
  std::vector<cv::Point> run;
  const auto flush = [&] {
    if (run.size() > 1) cv::polylines(img, run, false, {40, 40, 230}, 2, cv::LINE_AA);
    run.clear();
  };
  for (const auto& p : m.underside_mm) {
    if (std::isnan(p.y)) {
      flush();
      cv::line(img, px(p.x, 0), px(p.x, -0.3 * l.row.nozzle_mm), {200, 0, 200}, 1);
      continue;
    }
    run.push_back(px(p.x, p.y));
  }
  flush();
  const std::string label = std::string(1, static_cast<char>(std::toupper(m.cls[0]))) + " " +
                            fixed(m.area_factor_pct, 0);
  const double font = std::clamp(v.px_per_mm / 90, 0.35, 0.6);
  int base = 0;
  const cv::Size text = cv::getTextSize(label, cv::FONT_HERSHEY_SIMPLEX, font, 1, &base);
  const cv::Point at = px((g.x0 + g.x1) / 2, l.row.top_mm + 0.3 * l.row.nozzle_mm);
  cv::putText(img, label, at - cv::Point(text.width / 2, 0), cv::FONT_HERSHEY_SIMPLEX, font, {255, 80, 0}, 1, cv::LINE_AA);
}

// The widest gap that spans with every narrower gap spanning too; null when the narrowest
// does not.
nlohmann::json widest_spanned(std::vector<std::pair<double, bool>> gap_spans) {
  std::stable_sort(gap_spans.begin(), gap_spans.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
  nlohmann::json widest = nullptr;
  for (const auto& [gap, spans] : gap_spans) {
    if (!spans) break;
    widest = gap;
  }
  return widest;
}

}  // namespace

Measured measure_collapse(const cv::Mat& photo, const nlohmann::json& report, const std::string& what) {
  const nlohmann::json derived = derived_of_test(report, "collapse", "collapse-test", what);
  const Layout l = layout_of(derived, what);
  const double nozzle = l.row.nozzle_mm;
  const double margin = std::max(2.0, 3 * nozzle);
  const SideView v = rectified_side_view(photo, l.row, std::clamp(24.0 / nozzle, 4.0, 60.0), margin, what);

  Measured out;
  out.overlay = v.color.clone();
  for (double left : l.row.left_mm) {
    cv::rectangle(out.overlay, v.to_px(left, l.row.top_mm), v.to_px(left + l.row.side_mm, 0), {255, 80, 0}, 1, cv::LINE_AA);
  }
  std::vector<std::pair<double, bool>> spans;  // per gap: its width, and whether it spans
  nlohmann::json js = nlohmann::json::array();
  std::ostringstream text;
  for (const auto& g : l.gaps) {
    const GapResult m = measure_gap(v, g, l);
    draw_gap(out.overlay, v, g, m, l);
    spans.push_back({g.gap_mm, m.cls == "spans"});
    js.push_back({{"index", g.index},
                  {"gap_mm", g.gap_mm},
                  {"collapse_area_factor_pct", round_to(m.area_factor_pct, 1)},
                  {"max_sag_mm", round_to(m.max_sag_mm, 3)},
                  {"filament_found_share", round_to(m.found_share, 3)},
                  {"class", m.cls}});
    text << "  gap " << std::setw(2) << g.index << "  " << std::setw(6) << fixed(g.gap_mm, 3) << " mm  Cf " << std::setw(5)
         << fixed(m.area_factor_pct, 1) << " %  sag " << fixed(m.max_sag_mm, 3) << " mm  " << m.cls << "\n";
  }
  const nlohmann::json widest = widest_spanned(spans);
  text << "  widest spanned gap " << (widest.is_null() ? std::string("none") : fixed(widest.get<double>(), 3) + " mm")
       << " (Cf >= " << fixed(kSpansAreaFactorPct, 0) << " % there and in every narrower gap)\n";
  if (v.mirrored) text << "  photographed from the back: the row read mirrored\n";
  cv::putText(out.overlay,
              "green: intended underside, red: found (magenta: none); S spans, C collapsed, B broken, with Cf %" +
                  std::string(v.mirrored ? "; photo from the back, shown from the front" : ""),
              {6, 16}, cv::FONT_HERSHEY_SIMPLEX, 0.45, {0, 0, 0}, 1, cv::LINE_AA);
  out.items = std::to_string(l.gaps.size()) + " gaps";
  out.details = text.str();
  out.json = {{"test", "collapse"},
              {"nozzle_mm", nozzle},
              {"ink", v.dark_ink ? "darker than the backdrop" : "lighter than the backdrop"},
              {"contrast", round_to(v.contrast, 3)},
              {"px_per_mm", round_to(v.px_per_mm, 3)},
              {"mirrored", v.mirrored},
              {"edge_mm", round_to(v.edge_mm, 3)},
              {"fit_rms_mm", round_to(v.fit_rms_mm, 3)},
              {"pillar_height_mm", l.pillar_height_mm},
              {"spans_from_pct", kSpansAreaFactorPct},
              {"widest_spanned_gap_mm", widest},
              {"gaps", js}};
  return out;
}

}  // namespace strand::post::measure
