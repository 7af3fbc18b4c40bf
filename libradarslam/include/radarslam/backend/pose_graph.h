#pragma once
// The SLAM back end (paper Sec. III-D): keyframe poses, odometry edges and loop-closure edges with
// information matrices, optimised as an SE(2) pose graph: Levenberg-Marquardt with a sparse
// Cholesky solver (Ceres), i.e. Sparse Pose Adjustment. MRPT's optimize_graph_spa_levmarq was used
// first; in MRPT 2.5.8 it maps every edge to its nodes by a linear search over a std::set
// (levmarq.h, find_in_vector), O(edges x nodes) per call: 4.7 s for a 4000-node graph against
// 0.1 s for 1000 nodes, and the 10 000-scan run spent 83 % of its loop-closing thread there.
//
// Robustness: a wrong loop that slipped through verification must not wreck the map. After each
// optimisation the loop edge with the largest chi^2 (e^T Omega e of its residual) is removed if
// that chi^2 exceeds loop_chi2_gate, and the graph is re-optimised from the initial estimate;
// repeated up to max_loop_rejections times. Odometry edges are never removed.
#include <mrpt/math/TPose2D.h>
#include <Eigen/Core>

#include <cstddef>
#include <memory>
#include <vector>

namespace radarslam {

class YamlParams;

struct PoseGraphParams {
  int max_iterations = 100;       ///< valid [1, 10000]
  double loop_chi2_gate = 16.27;  ///< chi^2 (3 DOF) 99.9 % quantile; valid (0, 1000000]
  int max_loop_rejections = 10;   ///< valid [0, 10000]
};

/// Overrides `params` from max_iterations, loop_chi2_gate, max_loop_rejections.
void loadParams(const YamlParams& yaml, PoseGraphParams& params);

struct GraphEdge {
  std::size_t from = 0, to = 0;
  mrpt::math::TPose2D relative;                               ///< pose of `to` in the frame of `from`
  Eigen::Matrix3d information = Eigen::Matrix3d::Identity();  ///< of relative (x, y, phi)
  bool is_loop = false;
  bool active = true;  ///< false once rejected by the robust check
};

struct PoseGraphReport {
  double chi2_initial = 0, chi2_final = 0;  ///< over active edges, at the start and the end
  std::size_t iterations = 0;               ///< Levenberg-Marquardt iterations, all passes
  std::vector<std::size_t> rejected_edges;  ///< edge indices removed by the robust check
};

class PoseGraph {
 public:
  explicit PoseGraph(const PoseGraphParams& params = {});
  ~PoseGraph();

  /// Adds a node with an initial estimate; returns its index. Node 0 is the fixed root.
  std::size_t addNode(const mrpt::math::TPose2D& initial);
  /// Adds an edge; returns its index. Throws std::out_of_range for unknown nodes and
  /// std::invalid_argument for from == to or an information matrix that is not symmetric
  /// positive definite.
  std::size_t addOdometryEdge(std::size_t from, std::size_t to, const mrpt::math::TPose2D& relative,
                              const Eigen::Matrix3d& information);
  std::size_t addLoopEdge(std::size_t from, std::size_t to, const mrpt::math::TPose2D& relative,
                          const Eigen::Matrix3d& information);

  /// Optimises all nodes but the root; with the robust check (see above). Active edges after a
  /// previous optimize() stay active; rejected ones stay rejected.
  PoseGraphReport optimize();

  std::size_t numNodes() const { return poses_.size(); }
  const mrpt::math::TPose2D& pose(std::size_t i) const { return poses_.at(i); }
  const std::vector<mrpt::math::TPose2D>& poses() const { return poses_; }
  const std::vector<GraphEdge>& edges() const { return edges_; }
  /// e^T Omega e of an edge at the current poses (e = relative^-1 (+) (from^-1 (+) to)).
  double edgeChi2(std::size_t edge) const;
  /// Sum of edgeChi2 over active edges.
  double totalChi2() const;

 private:
  std::size_t addEdge(std::size_t from, std::size_t to, const mrpt::math::TPose2D& relative,
                      const Eigen::Matrix3d& information, bool is_loop);
  PoseGraphParams params_;
  std::vector<mrpt::math::TPose2D> poses_;
  std::vector<GraphEdge> edges_;
};

}  // namespace radarslam
