#pragma once
// A kd-tree over planar points (nanoflann): nearest-neighbour and radius queries. Shared by loop
// verification (loop/loop_verifier.cpp) and the localiser's submap ICP (reloc/submap_icp.cpp).
#include <Eigen/Core>
#include <cstdint>
#include <nanoflann.hpp>
#include <utility>
#include <vector>

namespace radarslam {

class PointIndex2D {
 public:
  explicit PointIndex2D(std::vector<Eigen::Vector2d> pts)
      : cloud_{std::move(pts)}, tree_(2, cloud_, nanoflann::KDTreeSingleIndexAdaptorParams(10)) {
    tree_.buildIndex();
  }
  PointIndex2D(const PointIndex2D&) = delete;  // the tree refers to cloud_
  PointIndex2D& operator=(const PointIndex2D&) = delete;

  const std::vector<Eigen::Vector2d>& points() const { return cloud_.pts; }
  std::size_t size() const { return cloud_.pts.size(); }

  /// Squared distance to the nearest point and that point's index; the index must not be empty.
  std::pair<double, std::uint32_t> nearest(const Eigen::Vector2d& q) const {
    std::uint32_t idx = 0;
    double d2 = 0;
    tree_.knnSearch(q.data(), 1, &idx, &d2);
    return {d2, idx};
  }

  /// The points within `radius` of q as (index, squared distance), unsorted; reuses `out`.
  void within(const Eigen::Vector2d& q, double radius,
              std::vector<std::pair<std::uint32_t, double>>& out) const {
    out.clear();
    tree_.radiusSearch(q.data(), radius * radius, out, nanoflann::SearchParams(32, 0, false));
  }

 private:
  struct Cloud {  // nanoflann's dataset adaptor interface
    std::vector<Eigen::Vector2d> pts;
    std::size_t kdtree_get_point_count() const { return pts.size(); }
    double kdtree_get_pt(std::size_t i, std::size_t d) const { return pts[i][static_cast<int>(d)]; }
    template <class BBOX>
    bool kdtree_get_bbox(BBOX&) const {
      return false;
    }
  };
  using Tree = nanoflann::KDTreeSingleIndexAdaptor<nanoflann::L2_Simple_Adaptor<double, Cloud>, Cloud, 2,
                                                   std::uint32_t>;
  Cloud cloud_;
  Tree tree_;
};

}  // namespace radarslam
