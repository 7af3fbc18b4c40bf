#include "radarslam/eval/alignment.h"

#include <cmath>
#include <stdexcept>

namespace radarslam::eval {

mrpt::math::TPose2D alignSE2(const std::vector<mrpt::math::TPoint2D>& from,
                             const std::vector<mrpt::math::TPoint2D>& to) {
  if (from.size() != to.size() || from.empty())
    throw std::invalid_argument("alignSE2: needs two non-empty point sets of equal size");
  const double n = static_cast<double>(from.size());
  double fx = 0, fy = 0, tx = 0, ty = 0;
  for (std::size_t i = 0; i < from.size(); ++i)
    fx += from[i].x, fy += from[i].y, tx += to[i].x, ty += to[i].y;
  fx /= n, fy /= n, tx /= n, ty /= n;
  // With centred points a_i (from) and b_i (to), the optimal rotation angle maximises
  // sum b_i . R a_i, i.e. theta = atan2(sum a x b, sum a . b) (2D case of Umeyama's SVD solution).
  double dot = 0, cross = 0;
  for (std::size_t i = 0; i < from.size(); ++i) {
    const double ax = from[i].x - fx, ay = from[i].y - fy, bx = to[i].x - tx, by = to[i].y - ty;
    dot += ax * bx + ay * by;
    cross += ax * by - ay * bx;
  }
  const double theta = (dot == 0 && cross == 0) ? 0.0 : std::atan2(cross, dot);
  const double c = std::cos(theta), s = std::sin(theta);
  return {tx - (c * fx - s * fy), ty - (s * fx + c * fy), theta};
}

}  // namespace radarslam::eval
