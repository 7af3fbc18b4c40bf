// The KITTI segment-error plot: mean translational (%) and rotational (deg/100 m) error per
// segment length, as bars with their values, the overall mean as a dashed line.
#include <algorithm>
#include <cmath>
#include <functional>

#include "plot_canvas.h"
#include "radarslam/eval/plots.h"

namespace radarslam::eval {

namespace {
using namespace plot;

constexpr Color kTransColor{31, 119, 180};
constexpr Color kRotColor{255, 127, 14};
constexpr Color kGrid{228, 228, 228};
constexpr Color kAxis{60, 60, 60};
constexpr Color kMuted{100, 100, 100};
constexpr Color kMeanColor{200, 30, 30};

struct Panel {
  double left, top, w, h;
  std::string title, y_title, unit;
  Color color;
  std::function<double(const KittiLengthStats&)> value;
  double mean;
};

std::string valueLabel(double v) { return fixed(v, v >= 100 ? 0 : v >= 10 ? 1 : v >= 1 ? 2 : 3); }

void drawPanel(Canvas& c, const Panel& p, const KittiResult& k) {
  double vmax = 0;
  for (const auto& l : k.per_length)
    if (l.segments) vmax = std::max(vmax, p.value(l));
  if (k.valid()) vmax = std::max(vmax, p.mean);
  // Headroom above the highest bar for its value label and the mean's legend line.
  const double step = niceStep(vmax > 0 ? vmax * 1.3 / 5 : 0.2);
  const double ymax = step * std::max(1.0, std::ceil(vmax * 1.3 / step));
  const auto y_of = [&](double v) { return p.top + p.h * (1 - v / ymax); };

  for (double v = 0; v <= ymax * (1 + 1e-9); v += step) {
    c.line({p.left, y_of(v)}, {p.left + p.w, y_of(v)}, {kGrid, 1.0});
    c.text({p.left - 8, y_of(v) + 4}, tickLabel(v, step), {11, kMuted, Anchor::End});
  }
  c.text({p.left + p.w / 2, p.top - 12}, p.title, {14, kAxis, Anchor::Middle, true});
  c.text({p.left - 50, p.top + p.h / 2}, p.y_title, {12, kAxis, Anchor::Middle, false, true});
  c.text({p.left + p.w / 2, p.top + p.h + 50}, "segment length [m]", {12, kAxis, Anchor::Middle});

  const std::size_t n = k.per_length.size();
  const double slot = p.w / static_cast<double>(std::max<std::size_t>(n, 1));
  for (std::size_t i = 0; i < n; ++i) {
    const auto& l = k.per_length[i];
    const double xc = p.left + slot * (static_cast<double>(i) + 0.5);
    c.text({xc, p.top + p.h + 17}, fixed(l.length_m, 0), {11, kAxis, Anchor::Middle});
    c.text({xc, p.top + p.h + 31}, "n=" + std::to_string(l.segments), {9, kMuted, Anchor::Middle});
    if (!l.segments) {
      c.text({xc, p.top + p.h - 6}, "n/a", {10, kMuted, Anchor::Middle});
      continue;
    }
    const double v = p.value(l), bw = slot * 0.62;
    c.rect({xc - bw / 2, y_of(v)}, bw, p.top + p.h - y_of(v), p.color, std::nullopt);
    c.text({xc, y_of(v) - 5}, valueLabel(v), {10, kAxis, Anchor::Middle});
  }
  if (k.valid()) {
    const Stroke mean_stroke{kMeanColor, 1.3, true};
    c.line({p.left, y_of(p.mean)}, {p.left + p.w, y_of(p.mean)}, mean_stroke);
    const std::string label = "mean over all lengths: " + valueLabel(p.mean) + " " + p.unit;
    const double lx = p.left + p.w - 10 - textWidth(label, 11);
    c.line({lx - 30, p.top + 14}, {lx - 6, p.top + 14}, mean_stroke);
    c.text({lx, p.top + 18}, label, {11, kMeanColor});
  } else {
    c.text({p.left + p.w / 2, p.top + p.h / 2}, "no segment: path too short", {13, kMuted, Anchor::Middle});
  }
  c.line({p.left, p.top + p.h}, {p.left + p.w, p.top + p.h}, {kAxis, 1.2});
  c.line({p.left, p.top}, {p.left, p.top + p.h}, {kAxis, 1.2});
}

}  // namespace

std::vector<std::filesystem::path> writeSegmentErrorPlot(const std::filesystem::path& stem,
                                                         const EvalReport& r) {
  const KittiResult& k = r.kitti;
  const double width = 1000, height = 440;
  const Panel trans{80,
                    100,
                    380,
                    270,
                    "Translational error",
                    "translational error [%]",
                    "%",
                    kTransColor,
                    [](const KittiLengthStats& l) { return l.t_err_percent; },
                    k.t_err_percent};
  const Panel rot{590,
                  100,
                  380,
                  270,
                  "Rotational error",
                  "rotational error [°/100 m]",
                  "°/100 m",
                  kRotColor,
                  [](const KittiLengthStats& l) { return l.r_err_deg_per_100m; },
                  k.r_err_deg_per_100m};
  const std::string title =
      "KITTI segment errors: " + shortLabel(r.est_label) + "  vs  " + shortLabel(r.gt_label);
  std::string sub = k.valid()
                        ? "mean over " + std::to_string(k.segments) + " segments (a start every " +
                              std::to_string(r.params.kitti.step_frames) + " frames)  ·  " +
                              fixed(k.t_err_percent, 3) + " %, " + fixed(k.r_err_deg_per_100m, 3) + " °/100 m"
                        : std::string("the ground-truth path is shorter than the shortest segment");
  const auto draw = [&](Canvas& c) {
    c.text({40, 32}, title, {17, kBlack, Anchor::Start, true});
    c.text({40, 55}, sub, {12, kMuted});
    drawPanel(c, trans, k);
    drawPanel(c, rot, k);
  };
  const auto files = renderBoth(stem.string(), width, height, draw);
  return {files.begin(), files.end()};
}

std::vector<std::filesystem::path> writePlots(const std::filesystem::path& dir, const EvalReport& report) {
  auto files = writeTrajectoryPlot(dir / "trajectory", report);
  const auto more = writeSegmentErrorPlot(dir / "segment_errors", report);
  files.insert(files.end(), more.begin(), more.end());
  return files;
}

}  // namespace radarslam::eval
