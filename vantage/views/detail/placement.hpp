#pragma once
/// @file
/// The check a ring and a sphere of views share: their centre and radius within the world's
/// sane range (issue 15: a radius of 1e20 m reached the sensor's ray caster).

#include <Eigen/Core>
#include <stdexcept>
#include <string_view>

#include "vantage/map/grid_spec.hpp"
#include "vantage/util/text.hpp"

namespace vantage::detail {

/// Throws std::invalid_argument naming `<what>.center` or `<what>.radius`.
inline void validate_placement(std::string_view what, const Eigen::Vector3d& center,
                               double radius) {
  if (!(center.array().abs() <= kMaxWorldCoordinate).all()) {
    throw std::invalid_argument(
        cat(what, ".center must be finite, within ", kMaxWorldCoordinate, " m of the origin"));
  }
  if (!(radius > 0.0 && radius <= kMaxWorldCoordinate)) {
    throw std::invalid_argument(
        cat(what, ".radius must lie in (0, ", kMaxWorldCoordinate, "] m, got ", radius));
  }
}

}  // namespace vantage::detail
