// Geometric loop verification: Hough/consensus rotation search, uniqueness test, CICP refinement
// and acceptance tests (paper Sec. III-C); see loop_verifier.h.
#include "radarslam/loop/loop_verifier.h"

#include <mrpt/maps/CSimplePointsMap.h>
#include <mrpt/poses/CPose2D.h>
#include <mrpt/poses/CPosePDF.h>
#include <mrpt/slam/CICP.h>

#include <Eigen/Dense>
#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <vector>

#include "radarslam/core/errors.h"
#include "radarslam/core/yaml_params.h"
#include "radarslam/loop/point_index_2d.h"

namespace radarslam {

void loadParams(const YamlParams& yaml, LoopVerifierParams& p) {
  yaml.get("voxel_m", p.voxel_m, Range::closed(0, 100));
  yaml.get("max_search_points", p.max_search_points, Range::closed(3, 100000));
  yaml.get("rotation_steps", p.rotation_steps, Range::closed(4, 3600));
  yaml.get("max_translation_m", p.max_translation_m, Range::above(0, 1000));
  yaml.get("vote_cell_m", p.vote_cell_m, Range::closed(0.01, 100));
  yaml.get("hypotheses", p.hypotheses, Range::closed(1, 1000));
  yaml.get("suppression_distance_m", p.suppression_distance_m, Range::closed(0, 1000));
  yaml.get("suppression_angle_deg", p.suppression_angle_deg, Range::closed(0, 180));
  yaml.get("inlier_distance_m", p.inlier_distance_m, Range::above(0, 100));
  yaml.get("max_ambiguity_ratio", p.max_ambiguity_ratio, Range::closed(0, 10));
  yaml.get("min_inliers", p.min_inliers, Range::closed(0, 1e6));
  yaml.get("min_inlier_ratio", p.min_inlier_ratio, Range::closed(0, 1));
  yaml.get("max_rms_m", p.max_rms_m, Range::above(0, 100));
  yaml.get("min_inlier_sectors", p.min_inlier_sectors, Range::closed(0, 8));
  yaml.get("normal_radius_m", p.information.normal_radius_m, Range::above(0, 100));
  yaml.get("linearity_ratio", p.information.linearity_ratio, Range::closed(1, 1e6));
  yaml.get("correlation_length_m", p.information.correlation_length_m, Range::above(0, 100));
  yaml.get("min_sigma_m", p.information.min_sigma_m, Range::closed(0, 100));
  // The Hough vote grid has (2 max_translation_m / vote_cell_m)^2 cells.
  if (p.max_translation_m / p.vote_cell_m > 2000)
    yaml.fail("vote_cell_m", "max_translation_m / vote_cell_m must be <= 2000 (vote grid size)");
}

namespace {

using Vec2 = Eigen::Vector2d;

struct Pose {
  double x = 0, y = 0, th = 0;
  Vec2 apply(const Vec2& p) const {
    const double c = std::cos(th), s = std::sin(th);
    return {c * p.x() - s * p.y() + x, s * p.x() + c * p.y() + y};
  }
  Vec2 inverseApply(const Vec2& p) const {
    const double c = std::cos(th), s = std::sin(th), dx = p.x() - x, dy = p.y() - y;
    return {c * dx + s * dy, -s * dx + c * dy};
  }
};

double angleDiff(double a, double b) { return std::abs(std::remainder(a - b, 2 * M_PI)); }

std::vector<Vec2> toVec(std::span<const RadarPoint> c) {
  std::vector<Vec2> v;
  v.reserve(c.size());
  for (const auto& p : c) v.emplace_back(p.x, p.y);
  return v;
}

/// One point per voxel (the strongest, ties by order), then an even stride down to max_points.
std::vector<Vec2> thin(std::span<const RadarPoint> c, double voxel, std::size_t max_points) {
  std::vector<Vec2> out;
  if (voxel > 0) {
    std::map<std::pair<long, long>, std::size_t> best;
    for (std::size_t i = 0; i < c.size(); ++i) {
      const std::pair<long, long> key{std::lround(std::floor(c[i].x / voxel)),
                                      std::lround(std::floor(c[i].y / voxel))};
      auto [it, inserted] = best.emplace(key, i);
      if (!inserted && c[i].power > c[it->second].power) it->second = i;
    }
    for (const auto& [key, i] : best) out.emplace_back(c[i].x, c[i].y);
  } else {
    out = toVec(c);
  }
  if (out.size() > max_points) {
    std::vector<Vec2> s;
    s.reserve(max_points);
    for (std::size_t k = 0; k < max_points; ++k) s.push_back(out[k * out.size() / max_points]);
    out.swap(s);
  }
  return out;
}

/// Closed-form 2D rigid fit of pairs (a_i -> b_i), b = R a + t.
Pose fitRigid(const std::vector<Vec2>& a, const std::vector<Vec2>& b) {
  Vec2 ma = Vec2::Zero(), mb = Vec2::Zero();
  for (std::size_t i = 0; i < a.size(); ++i) ma += a[i], mb += b[i];
  ma /= static_cast<double>(a.size()), mb /= static_cast<double>(a.size());
  double sc = 0, ss = 0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    const Vec2 p = a[i] - ma, q = b[i] - mb;
    sc += p.x() * q.x() + p.y() * q.y();
    ss += p.x() * q.y() - p.y() * q.x();
  }
  Pose r;
  r.th = std::atan2(ss, sc);
  const double c = std::cos(r.th), s = std::sin(r.th);
  r.x = mb.x() - (c * ma.x() - s * ma.y());
  r.y = mb.y() - (s * ma.x() + c * ma.y());
  return r;
}

/// Short point-to-point ICP of `q` onto `c` from `pose`, gates shrinking to `gate`.
Pose quickIcp(const std::vector<Vec2>& q, const PointIndex2D& c, Pose pose, double gate) {
  std::vector<Vec2> a, b;
  for (int it = 0; it < 12; ++it) {
    const double g = gate * std::max(1.0, 3.0 - 0.25 * it);
    a.clear(), b.clear();
    for (const auto& p : q) {
      const Vec2 tp = pose.apply(p);
      const auto [d2, idx] = c.nearest(tp);
      if (d2 < g * g) a.push_back(p), b.push_back(c.points()[idx]);
    }
    if (a.size() < 3) break;
    pose = fitRigid(a, b);
  }
  return pose;
}

std::size_t consensus(const std::vector<Vec2>& q, const PointIndex2D& c, const Pose& pose, double gate) {
  std::size_t n = 0;
  for (const auto& p : q)
    if (c.nearest(pose.apply(p)).first < gate * gate) ++n;
  return n;
}

struct Hypothesis {
  Pose pose;
  int votes = 0;
  std::size_t score = 0;
};

/// Candidate points bucketed into x strips, each sorted by y: the points within a box around a
/// query point are a few binary searches away.
class StripIndex {
 public:
  StripIndex(std::vector<Vec2> pts, double strip_width) : inv_w_(1.0 / strip_width) {
    if (pts.empty()) return;
    auto strip = [&](const Vec2& v) { return static_cast<long>(std::floor(v.x() * inv_w_)); };
    std::sort(pts.begin(), pts.end(), [&](const Vec2& a, const Vec2& b) {
      const long sa = strip(a), sb = strip(b);
      return sa != sb ? sa < sb : a.y() < b.y();
    });
    first_strip_ = strip(pts.front());
    begin_.assign(static_cast<std::size_t>(strip(pts.back()) - first_strip_ + 2), 0);
    for (const auto& v : pts) ++begin_[static_cast<std::size_t>(strip(v) - first_strip_ + 1)];
    for (std::size_t i = 1; i < begin_.size(); ++i) begin_[i] += begin_[i - 1];
    pts_ = std::move(pts);
    ys_.reserve(pts_.size());
    for (const auto& v : pts_) ys_.push_back(v.y());
  }
  /// Calls f(point) for every point with |x - cx| <= r and |y - cy| <= r (and possibly a few more).
  template <class F>
  void forEachNear(double cx, double cy, double r, F&& f) const {
    if (pts_.empty()) return;
    const long lo = std::max(first_strip_, static_cast<long>(std::floor((cx - r) * inv_w_)));
    const long hi = std::min(first_strip_ + static_cast<long>(begin_.size()) - 2,
                             static_cast<long>(std::floor((cx + r) * inv_w_)));
    for (long st = lo; st <= hi; ++st) {
      const auto b = ys_.begin() + static_cast<long>(begin_[static_cast<std::size_t>(st - first_strip_)]);
      const auto e = ys_.begin() + static_cast<long>(begin_[static_cast<std::size_t>(st - first_strip_ + 1)]);
      for (auto it = std::lower_bound(b, e, cy - r); it != e && *it <= cy + r; ++it)
        f(pts_[static_cast<std::size_t>(it - ys_.begin())]);
    }
  }

 private:
  double inv_w_;
  long first_strip_ = 0;
  std::vector<std::size_t> begin_;  // points of strip first_strip_ + i: [begin_[i], begin_[i + 1])
  std::vector<Vec2> pts_;
  std::vector<double> ys_;
};

/// Per rotation, the strongest translation cell of the pair votes (2x2 window sums). A pair votes
/// only if its translation lies within the window, so each query point visits just the candidate
/// points in a box of the window's size around it (the exact cell test stays).
std::vector<Hypothesis> houghHypotheses(const std::vector<Vec2>& q, const std::vector<Vec2>& c,
                                        const LoopVerifierParams& p) {
  const int half = static_cast<int>(std::ceil(p.max_translation_m / p.vote_cell_m));
  const int side = 2 * half;
  std::vector<int> grid(static_cast<std::size_t>(side * side));
  std::vector<Hypothesis> hyps;
  hyps.reserve(static_cast<std::size_t>(p.rotation_steps));
  const double inv_cell = 1.0 / p.vote_cell_m;
  const double reach = (half + 1) * p.vote_cell_m;  // the window plus a cell: rounding-safe
  const StripIndex index(c, reach / 4);
  for (int k = 0; k < p.rotation_steps; ++k) {
    const double th = 2 * M_PI * k / p.rotation_steps;
    const double cs = std::cos(th), sn = std::sin(th);
    std::fill(grid.begin(), grid.end(), 0);
    for (const auto& a : q) {
      const double rx = cs * a.x() - sn * a.y(), ry = sn * a.x() + cs * a.y();
      index.forEachNear(rx, ry, reach, [&](const Vec2& b) {
        const int ix = static_cast<int>(std::floor((b.x() - rx) * inv_cell)) + half;
        const int iy = static_cast<int>(std::floor((b.y() - ry) * inv_cell)) + half;
        if (ix < 0 || iy < 0 || ix >= side || iy >= side) return;
        ++grid[static_cast<std::size_t>(iy * side + ix)];
      });
    }
    Hypothesis h;
    h.pose.th = th;
    h.votes = -1;
    for (int iy = 0; iy + 1 < side; ++iy)
      for (int ix = 0; ix + 1 < side; ++ix) {
        const std::size_t i = static_cast<std::size_t>(iy * side + ix);
        const int v = grid[i] + grid[i + 1] + grid[i + static_cast<std::size_t>(side)] +
                      grid[i + static_cast<std::size_t>(side) + 1];
        if (v > h.votes) {
          h.votes = v;
          h.pose.x = (ix + 1 - half) * p.vote_cell_m;  // the corner shared by the 4 cells
          h.pose.y = (iy + 1 - half) * p.vote_cell_m;
        }
      }
    hyps.push_back(h);
  }
  return hyps;
}

bool near(const Pose& a, const Pose& b, const LoopVerifierParams& p) {
  return std::hypot(a.x - b.x, a.y - b.y) < p.suppression_distance_m &&
         angleDiff(a.th, b.th) < p.suppression_angle_deg * M_PI / 180.0;
}

/// Whether every rival is a slide of the best alignment along one line (see LoopVerification::slide);
/// sets the line's direction and the farthest rival along it.
bool slideAlongOneLine(const std::vector<mrpt::math::TPose2D>& rivals, const LoopVerifierParams& p,
                       Vec2& direction, double& extent) {
  if (rivals.empty()) return false;
  const double step = 2 * M_PI / p.rotation_steps;
  const auto farthest = std::max_element(rivals.begin(), rivals.end(), [](const auto& a, const auto& b) {
    return std::hypot(a.x, a.y) < std::hypot(b.x, b.y);
  });
  const double length = std::hypot(farthest->x, farthest->y);
  if (length <= p.inlier_distance_m) return false;
  const Vec2 u(farthest->x / length, farthest->y / length);
  for (const auto& r : rivals) {
    const double across = std::abs(u.x() * r.y - u.y() * r.x);
    if (std::abs(r.phi) > step || across > p.inlier_distance_m) return false;
  }
  direction = u;
  extent = length;
  return true;
}

mrpt::maps::CSimplePointsMap toMap(std::span<const RadarPoint> c) {
  mrpt::maps::CSimplePointsMap m;
  m.reserve(c.size());
  for (const auto& p : c) m.insertPointFast(p.x, p.y, 0.f);
  m.mark_as_modified();
  return m;
}

}  // namespace

LoopVerification verifyLoop(std::span<const RadarPoint> query, std::span<const RadarPoint> candidate,
                            const LoopVerifierParams& params) {
  LoopVerification out;
  if (query.size() < params.min_inliers || candidate.size() < params.min_inliers) {
    out.reason = "too few points";
    return out;
  }
  // 1. Global search on thinned clouds.
  const std::vector<Vec2> qs = thin(query, params.voxel_m, params.max_search_points);
  const PointIndex2D cs(thin(candidate, params.voxel_m, params.max_search_points));
  std::vector<Hypothesis> all = houghHypotheses(qs, cs.points(), params);
  std::stable_sort(all.begin(), all.end(),
                   [](const Hypothesis& a, const Hypothesis& b) { return a.votes > b.votes; });
  std::vector<Hypothesis> picked;
  for (const auto& h : all) {
    if (static_cast<int>(picked.size()) >= params.hypotheses) break;
    if (std::none_of(picked.begin(), picked.end(),
                     [&](const Hypothesis& o) { return near(h.pose, o.pose, params); }))
      picked.push_back(h);
  }
  for (auto& h : picked) {
    h.pose = quickIcp(qs, cs, h.pose, params.inlier_distance_m);
    h.score = consensus(qs, cs, h.pose, params.inlier_distance_m);
  }
  std::stable_sort(picked.begin(), picked.end(),
                   [](const Hypothesis& a, const Hypothesis& b) { return a.score > b.score; });
  const Hypothesis& best = picked.front();
  std::size_t second = 0;
  for (std::size_t i = 1; i < picked.size(); ++i)
    if (!near(picked[i].pose, best.pose, params)) second = std::max(second, picked[i].score);
  out.ambiguity_ratio = best.score > 0 ? static_cast<double>(second) / static_cast<double>(best.score) : 1.0;
  for (std::size_t i = 1; i < picked.size(); ++i) {  // what makes it ambiguous, relative to the best
    const Pose& r = picked[i].pose;
    if (near(r, best.pose, params) ||
        static_cast<double>(picked[i].score) <= params.max_ambiguity_ratio * static_cast<double>(best.score))
      continue;
    const Vec2 d = best.pose.inverseApply(Vec2(r.x, r.y));
    out.rivals.push_back({d.x(), d.y(), std::remainder(r.th - best.pose.th, 2 * M_PI)});
  }
  out.slide = slideAlongOneLine(out.rivals, params, out.slide_direction, out.slide_extent_m);

  // 3. CICP refinement on the full clouds (the query aligned onto the candidate).
  const mrpt::maps::CSimplePointsMap cmap = toMap(candidate), qmap = toMap(query);
  mrpt::slam::CICP icp;
  icp.options.ICP_algorithm = mrpt::slam::icpClassic;
  icp.options.maxIterations = 80;
  icp.options.thresholdDist = 2.0 * params.inlier_distance_m;
  icp.options.thresholdAng = 0.0;
  icp.options.smallestThresholdDist = 0.3 * params.inlier_distance_m;
  icp.options.corresponding_points_decimation = 1;
  const auto result = icp.Align(&cmap, &qmap, mrpt::poses::CPose2D(best.pose.x, best.pose.y, best.pose.th));
  const mrpt::poses::CPose2D rel = result->getMeanVal();
  const Pose pose{rel.x(), rel.y(), rel.phi()};
  out.relative_pose = {rel.x(), rel.y(), rel.phi()};

  // 4. Acceptance on the full clouds.
  const PointIndex2D cfull(toVec(candidate));
  std::vector<Vec2> aligned;
  if (params.estimate_information) aligned.reserve(query.size());
  double sum2 = 0;
  std::array<bool, 8> sectors{};
  const double gate2 = params.inlier_distance_m * params.inlier_distance_m;
  for (const auto& p : query) {
    const Vec2 qp(p.x, p.y);
    const Vec2 tp = pose.apply(qp);
    if (params.estimate_information) aligned.push_back(tp);
    const double d2 = cfull.nearest(tp).first;
    if (d2 >= gate2) continue;
    ++out.inliers;
    sum2 += d2;
    double bearing = std::atan2(qp.y(), qp.x());
    if (bearing < 0) bearing += 2 * M_PI;
    sectors[std::min<std::size_t>(7, static_cast<std::size_t>(bearing * 8 / (2 * M_PI)))] = true;
  }
  out.inlier_sectors = static_cast<int>(std::count(sectors.begin(), sectors.end(), true));
  out.rms_m = out.inliers > 0 ? std::sqrt(sum2 / static_cast<double>(out.inliers)) : 0.0;
  out.inlier_ratio =
      static_cast<double>(out.inliers) / static_cast<double>(std::min(query.size(), candidate.size()));
  if (params.estimate_information)
    out.information = alignmentInformation(aligned, Vec2(pose.x, pose.y), cfull, params.inlier_distance_m,
                                           params.information);

  // The first failed test other than the ambiguity (empty: all passed).
  const char* failed = out.inliers < params.min_inliers             ? "too few inliers"
                       : out.inlier_ratio < params.min_inlier_ratio ? "low overlap"
                       : out.rms_m > params.max_rms_m               ? "large residual"
                       : out.inlier_sectors < params.min_inlier_sectors
                           ? "inliers not spread around the sensor"
                           : "";
  const bool ambiguous = out.ambiguity_ratio > params.max_ambiguity_ratio;
  out.reason = ambiguous ? "ambiguous place (a distant alignment scores almost as well)" : failed;
  out.ambiguous_only = ambiguous && *failed == '\0';
  out.accepted = out.reason.empty();
  return out;
}

}  // namespace radarslam
