#pragma once
/// @file
/// Expected information gain of candidate views (eqs. 1, 3, 4; MODEL.md "One view").

#include <Eigen/Core>
#include <cstddef>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "vantage/map/occupancy_grid.hpp"
#include "vantage/views/frustum.hpp"

namespace vantage {

/// How the gain of one target cell is predicted.
enum class GainMethod {
  kProbabilistic,  ///< the paper's visibility HMM and occupancy filter, parameter alpha
  kGreedy,  ///< simple greedy: 1 if nothing occupied lies before the cell (infinite visibility)
};

std::string_view to_string(GainMethod method);
/// Parses "probabilistic" or "greedy"; throws std::invalid_argument naming the value.
GainMethod parse_gain_method(std::string_view name);

/// Settings of a gain evaluation.
struct GainConfig {
  GainMethod method = GainMethod::kProbabilistic;
  double alpha = 0.997;  ///< observability parameter a, in (0, 1]
  int num_threads = 0;   ///< 0 = all cores; results are identical for any count

  /// Throws std::invalid_argument naming the field.
  void validate() const;
};

/// The predicted gain of one view.
struct ViewGain {
  double gain = 0.0;        ///< expected number of unobserved cells the view turns known [bits]
  std::size_t targets = 0;  ///< unobserved cells inside the frustum
};

/// Exact evaluation: every unobserved cell inside the frustum on its own ray from the sensor
/// origin to the cell's centre, summed. The reference for every faster evaluation.
std::vector<ViewGain> exact_view_gains(const OccupancyGrid& grid, std::span<const Frustum> views,
                                       const GainConfig& config);

/// Exact gain of one view.
ViewGain exact_view_gain(const OccupancyGrid& grid, const Frustum& view, const GainConfig& config);

/// Predicted gain of one target cell seen from `origin`, whatever its state (known cells are
/// evaluated too; the view sums skip them).
double exact_cell_gain(const OccupancyGrid& grid, const Eigen::Vector3d& origin,
                       const Index3& target, const GainConfig& config);

}  // namespace vantage
