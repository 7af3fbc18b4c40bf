// The trajectory plot: estimate (after the ATE alignment) over ground truth, top view, equal axes.
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include "plot_canvas.h"
#include "radarslam/eval/plots.h"

namespace radarslam::eval {

namespace {
using namespace plot;

constexpr Color kGtColor{150, 150, 150};
constexpr Color kEstColor{31, 119, 180};
constexpr Color kStartColor{44, 160, 44};
constexpr Color kEndColor{214, 39, 40};
constexpr Color kGrid{228, 228, 228};
constexpr Color kAxis{60, 60, 60};
constexpr Color kMuted{90, 90, 90};

struct Frame {  // world metres -> canvas points
  double x0, y1, s, left, top;
  Pt operator()(double x, double y) const { return {left + (x - x0) * s, top + (y1 - y) * s}; }
};

std::string subtitle(const EvalReport& r) {
  std::string s = "aligned in SE(2) (ATE RMSE " + fixed(r.ate.trans_m.rmse, 2) + " m)";
  if (r.kitti.valid())
    s += "  ·  KITTI " + fixed(r.kitti.t_err_percent, 2) + " %, " + fixed(r.kitti.r_err_deg_per_100m, 2) +
         " °/100 m";
  s += "  ·  " + fixed(r.gt_path_length_m, 0) + " m, " + std::to_string(r.association.size()) + " poses";
  return s;
}

void drawMarkerSquare(Canvas& c, Pt p, double half, std::optional<Color> fill, std::optional<Stroke> stroke) {
  c.rect({p.x - half, p.y - half}, 2 * half, 2 * half, fill, stroke);
}

}  // namespace

std::vector<std::filesystem::path> writeTrajectoryPlot(const std::filesystem::path& stem,
                                                       const EvalReport& r) {
  const auto& gt = r.association.gt;
  const auto& est = r.ate.est_aligned;
  double xmin = std::numeric_limits<double>::max(), ymin = xmin, xmax = -xmin, ymax = -xmin;
  for (const auto* poses : {&gt, &est})
    for (const auto& p : *poses) {
      xmin = std::min(xmin, p.x), xmax = std::max(xmax, p.x);
      ymin = std::min(ymin, p.y), ymax = std::max(ymax, p.y);
    }
  // Pad the data box and keep a minimum extent so a standing-still trajectory still has axes.
  double rx = std::max(xmax - xmin, 1.0), ry = std::max(ymax - ymin, 1.0);
  const double cx = 0.5 * (xmin + xmax), cy = 0.5 * (ymin + ymax);
  rx *= 1.08, ry *= 1.08;
  // Plot area: 780 points across, height from the aspect ratio (clamped), equal scale on both axes.
  const double left = 84, right = 28, top = 78, bottom = 64, plot_w = 780;
  double plot_h = plot_w * ry / rx;
  if (plot_h < 380) plot_h = 380, ry = rx * plot_h / plot_w;
  if (plot_h > 900) plot_h = 900, rx = ry * plot_w / plot_h;
  const Frame f{cx - rx / 2, cy + ry / 2, plot_w / rx, left, top};
  const double width = left + plot_w + right, height = top + plot_h + bottom;

  std::vector<Pt> gt_pts, est_pts;
  for (const auto& p : gt) gt_pts.push_back(f(p.x, p.y));
  for (const auto& p : est) est_pts.push_back(f(p.x, p.y));

  // Legend in the corner the trajectories cross least.
  const std::array<std::string, 6> entries{"ground truth",     "estimate (aligned)", "start (ground truth)",
                                           "start (estimate)", "end (ground truth)", "end (estimate)"};
  const double legend_w = 36 + textWidth("start (ground truth)", 12) + 14,
               legend_h = 14 + 20.0 * entries.size();
  std::array<Pt, 4> corners{Pt{left + 10, top + 10}, Pt{left + plot_w - 10 - legend_w, top + 10},
                            Pt{left + 10, top + plot_h - 10 - legend_h},
                            Pt{left + plot_w - 10 - legend_w, top + plot_h - 10 - legend_h}};
  std::size_t best = 0, best_count = std::numeric_limits<std::size_t>::max();
  for (std::size_t k = 0; k < corners.size(); ++k) {
    std::size_t n = 0;
    for (const auto* pts : {&gt_pts, &est_pts})
      for (const Pt& p : *pts)
        n += p.x >= corners[k].x - 8 && p.x <= corners[k].x + legend_w + 8 && p.y >= corners[k].y - 8 &&
             p.y <= corners[k].y + legend_h + 8;
    if (n < best_count) best = k, best_count = n;
  }
  const Pt legend = corners[best];

  const std::string title = "Trajectory: " + shortLabel(r.est_label) + "  vs  " + shortLabel(r.gt_label);
  const auto draw = [&](Canvas& c) {
    // Grid with metre labels (same step on both axes).
    const double step = niceStep(std::max(rx, ry) / 8);
    const double gx0 = cx - rx / 2, gx1 = cx + rx / 2, gy0 = cy - ry / 2, gy1 = cy + ry / 2;
    for (double x = std::ceil(gx0 / step) * step; x <= gx1; x += step) {
      const Pt a = f(x, gy0), b = f(x, gy1);
      c.line(a, b, {kGrid, 1.0});
      c.line(a, {a.x, a.y + 5}, {kAxis, 1.0});
      c.text({a.x, a.y + 20}, tickLabel(x, step), {12, kMuted, Anchor::Middle});
    }
    for (double y = std::ceil(gy0 / step) * step; y <= gy1; y += step) {
      const Pt a = f(gx0, y), b = f(gx1, y);
      c.line(a, b, {kGrid, 1.0});
      c.line({a.x - 5, a.y}, a, {kAxis, 1.0});
      c.text({a.x - 9, a.y + 4}, tickLabel(y, step), {12, kMuted, Anchor::End});
    }
    c.rect({left, top}, plot_w, plot_h, std::nullopt, Stroke{kAxis, 1.2});
    c.text({left + plot_w / 2, top + plot_h + 48}, "x [m]", {13, kAxis, Anchor::Middle});
    c.text({24, top + plot_h / 2}, "y [m]", {13, kAxis, Anchor::Middle, false, true});
    c.text({left, 30}, title, {17, kBlack, Anchor::Start, true});
    c.text({left, 54}, subtitle(r), {12, kMuted});

    c.polyline(gt_pts, {kGtColor, 3.2});
    c.polyline(est_pts, {kEstColor, 1.6});
    if (!gt_pts.empty()) {
      // The start ring is larger and drawn first so that an end at the start stays visible inside it.
      c.circle(gt_pts.front(), 8, kStartColor, Stroke{kWhite, 1.5});
      c.circle(est_pts.front(), 6, std::nullopt, Stroke{kStartColor, 2.0});
      drawMarkerSquare(c, gt_pts.back(), 4.5, kEndColor, Stroke{kWhite, 1.0});
      drawMarkerSquare(c, est_pts.back(), 5.5, std::nullopt, Stroke{kEndColor, 2.0});
    }

    c.rect(legend, legend_w, legend_h, kWhite, Stroke{{170, 170, 170}, 1.0});
    for (std::size_t k = 0; k < entries.size(); ++k) {
      const double y = legend.y + 17 + 20.0 * static_cast<double>(k);
      const Pt m{legend.x + 18, y};
      switch (k) {
        case 0:
          c.line({m.x - 10, y}, {m.x + 10, y}, {kGtColor, 3.2});
          break;
        case 1:
          c.line({m.x - 10, y}, {m.x + 10, y}, {kEstColor, 1.6});
          break;
        case 2:
          c.circle(m, 7, kStartColor, Stroke{kWhite, 1.5});
          break;
        case 3:
          c.circle(m, 5.5, std::nullopt, Stroke{kStartColor, 2.0});
          break;
        case 4:
          drawMarkerSquare(c, m, 4.5, kEndColor, std::nullopt);
          break;
        default:
          drawMarkerSquare(c, m, 5, std::nullopt, Stroke{kEndColor, 2.0});
          break;
      }
      c.text({legend.x + 36, y + 4.5}, entries[k], {12, kAxis});
    }
  };
  const auto files = renderBoth(stem.string(), width, height, draw);
  return {files.begin(), files.end()};
}

}  // namespace radarslam::eval
