#include "radarslam/frontend/svd_pose.h"

#include <mrpt/tfest/se2.h>

namespace radarslam {

std::optional<mrpt::math::TPose2D> fitPoseSvd(const Correspondences& matches) {
  if (matches.size() < 2) return std::nullopt;
  mrpt::tfest::TMatchingPairList pairs;
  pairs.reserve(matches.size());
  for (std::size_t i = 0; i < matches.size(); ++i) {
    const auto& m = matches[i];
    // se2_l2 returns q with global = q (+) local.
    pairs.emplace_back(static_cast<uint32_t>(i), static_cast<uint32_t>(i), m.ref.x(), m.ref.y(), 0.0,
                       m.cur.x(), m.cur.y(), 0.0);
  }
  mrpt::math::TPose2D pose;
  if (!mrpt::tfest::se2_l2(pairs, pose)) return std::nullopt;
  return pose;
}

}  // namespace radarslam
