#include "localize_truth.h"

#include <mrpt/poses/CPose2D.h>

#include <cmath>
#include <cstdio>
#include <functional>

#include <radarslam/eval/alignment.h>
#include <radarslam/io/trajectory_files.h>
#include <radarslam/map/keyframe_search.h>

namespace radarslam::cli {

namespace fs = std::filesystem;
using mrpt::math::TPose2D;
using mrpt::poses::CPose2D;

namespace {

using TruthAt = std::function<std::optional<TPose2D>(StampNs)>;

/// The map frame fitted to the truth at the map's keyframes.
struct Fit {
  CPose2D truth_from_map;                              ///< T with truth ~ T (+) map
  std::vector<std::optional<TPose2D>> keyframe_truth;  ///< in the map frame
  std::string how;
};

std::optional<Fit> fitMapFrame(const KeyframeMap& map, const TruthAt& truth_at) {
  std::vector<mrpt::math::TPoint2D> in_map, in_truth;
  std::vector<std::optional<TPose2D>> kf_truth(map.keyframes.size());
  for (std::size_t k = 0; k < map.keyframes.size(); ++k) {
    const auto& kf = map.keyframes[k];
    kf_truth[k] = truth_at(kf.stamp_ns);
    if (!kf_truth[k]) continue;
    in_map.emplace_back(kf.pose.x, kf.pose.y);
    in_truth.emplace_back(kf_truth[k]->x, kf_truth[k]->y);
  }
  if (in_map.empty()) return std::nullopt;
  Fit fit;
  fit.truth_from_map = CPose2D(eval::alignSE2(in_map, in_truth));
  double ss = 0;
  for (std::size_t i = 0; i < in_map.size(); ++i) {
    const auto p = fit.truth_from_map.composePoint(in_map[i]);
    ss += (p.x - in_truth[i].x) * (p.x - in_truth[i].x) + (p.y - in_truth[i].y) * (p.y - in_truth[i].y);
  }
  for (auto& g : kf_truth)
    if (g) g = (CPose2D(*g) - fit.truth_from_map).asTPose();
  fit.keyframe_truth = std::move(kf_truth);
  char buf[160];
  std::snprintf(buf, sizeof buf, "map frame fitted to %zu keyframes, residual RMS %.2f m", in_map.size(),
                std::sqrt(ss / static_cast<double>(in_map.size())));
  fit.how = buf;
  return fit;
}

/// The dataset's truth `abs` moved into the fitted map frame.
MapFrameTruth inMapFrame(Fit fit, const Trajectory& abs, const std::string& source) {
  MapFrameTruth out;
  for (const auto& sp : abs)
    out.truth.push_back({sp.stamp, (CPose2D(sp.pose) - fit.truth_from_map).asTPose()});
  out.keyframe_truth = std::move(fit.keyframe_truth);
  out.how = source + "; " + fit.how;
  return out;
}

}  // namespace

std::optional<MapFrameTruth> truthInMapFrame(const KeyframeMap& map, const DatasetReader& reader,
                                             const fs::path& dir) {
  const fs::path src = map.meta.source_dataset;
  const fs::path abs_src = src / "gt" / "poses.tum", abs_dir = dir / "gt" / "poses.tum";
  std::error_code ec;
  if (!src.empty() && fs::exists(abs_src, ec) && fs::exists(abs_dir, ec)) {
    const Trajectory src_abs = readTumTrajectory(abs_src);
    if (auto fit = fitMapFrame(map, [&](StampNs t) { return interpolatePose(src_abs, t); }))
      return inMapFrame(std::move(*fit), readTumTrajectory(abs_dir),
                        "absolute gt/poses.tum of the map's source and of the dataset");
  }
  if (!src.empty() && fs::equivalent(src, dir, ec) && reader.hasGroundTruth()) {
    // The map was built from this dataset (a SLAM map starts at the identity, a map-synth map is in
    // the truth's frame).
    if (auto fit = fitMapFrame(map, [&](StampNs t) { return reader.groundTruthAt(t); }))
      return inMapFrame(std::move(*fit), reader.groundTruth(),
                        "the dataset's ground truth (the map was built from it)");
  }
  return std::nullopt;
}

std::optional<TPose2D> mapRelativeTruth(const KeyframeMap& map, const MapFrameTruth& truth,
                                        const TPose2D& est, const TPose2D& est_truth) {
  const long nearest =
      nearestKeyframe(map, est.x, est.y, [&](std::size_t k) { return truth.keyframe_truth[k].has_value(); });
  if (nearest < 0) return std::nullopt;
  const auto best = static_cast<std::size_t>(nearest);
  const CPose2D rel_true = CPose2D(est_truth) - CPose2D(*truth.keyframe_truth[best]);
  return (CPose2D(map.keyframes[best].pose) + rel_true).asTPose();
}

std::optional<std::pair<double, double>> mapRelativeError(const KeyframeMap& map, const MapFrameTruth& truth,
                                                          const TPose2D& est, const TPose2D& est_truth) {
  // |est - keyframe ⊕ rel_true| = |rel_est - rel_true| in the keyframe's frame (a rotation apart).
  const auto local = mapRelativeTruth(map, truth, est, est_truth);
  if (!local) return std::nullopt;
  const double heading = std::abs(std::remainder(est.phi - local->phi, 2 * M_PI)) * 180 / M_PI;
  return std::make_pair(std::hypot(est.x - local->x, est.y - local->y), heading);
}

}  // namespace radarslam::cli
