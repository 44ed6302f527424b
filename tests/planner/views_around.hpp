#pragma once
// Four candidate views around a block at the origin, from +x, +y, -x and -y, each looking at its
// centre, with travel 4, 3, 2 and 1 m (planner_test.cpp, the architecture's worked examples).

#include <cmath>
#include <vector>

#include "vantage/planner/types.hpp"
#include "vantage/views/ring.hpp"

namespace vantage::test {

inline std::vector<Candidate> views_around_block() {
  std::vector<Candidate> candidates;
  for (int k = 0; k < 4; ++k) {
    const double a = k * M_PI / 2;
    const Eigen::Vector3d eye(1.5 * std::cos(a), 1.5 * std::sin(a), 0.3);
    candidates.push_back({Frustum(look_at(eye, Eigen::Vector3d::Zero()),
                                  SensorFov{deg2rad(60), deg2rad(45), 0.2, 4.0}),
                          4.0 - k, true});
  }
  return candidates;
}

}  // namespace vantage::test
