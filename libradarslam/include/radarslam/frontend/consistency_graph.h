#pragma once
// Pairwise consistency of matches (paper Sec. III-A, eq. (3)). Two matches i, j are consistent if
// a rigid motion can explain both. As printed, eq. (3) compares the lengths of the two
// displacements |P_t^i - P_k^i| and |P_t^j - P_k^j|; that test is not invariant to rotation
// (points far from the sensor move further when the vehicle turns). The default therefore uses
// the rigid-body invariant — distances between the two keypoints are preserved:
//   | |P_t^i - P_t^j| - |P_k^i - P_k^j| | < delta_c
// The literal form is kept as an option for the ablation.
#include "radarslam/frontend/correspondence.h"
#include "radarslam/frontend/max_clique.h"

namespace radarslam {

enum class ConsistencyTest { PairwiseDistance, DisplacementLength };

DenseGraph buildConsistencyGraph(const Correspondences& matches, double delta_c_m,
                                 ConsistencyTest test = ConsistencyTest::PairwiseDistance);

}  // namespace radarslam
