#pragma once
/// @file
/// The target models' rays (methods.hpp, MethodKind::kTargetModel): what one target cell's ray
/// predicts under each model. evaluators/with_predictor.hpp hands the one `GainConfig::method`
/// names to a traversal strategy (exact.cpp sums them per view; the swept search's race lists
/// them per cell). A predictor is a small value with
///   template <typename Cells>
///   TargetPrediction operator()(const Cells&, const Eigen::Vector3d& origin, const Index3& target)
///   const;
/// `Cells` is GainMap or GridCells.

#include <Eigen/Core>
#include <cstddef>

#include "vantage/gain/free_space.hpp"
#include "vantage/gain/model.hpp"
#include "vantage/gain/ray_model.hpp"
#include "vantage/gain/snapshot.hpp"
#include "vantage/gain/survival.hpp"
#include "vantage/map/line_of_sight.hpp"
#include "vantage/map/occupancy_grid.hpp"
#include "vantage/map/traversal.hpp"

namespace vantage::detail {

/// Cell values read straight from the grid, for one-off rays where a snapshot would cost more
/// than it saves.
struct GridCells {
  const OccupancyGrid& grid;
  const GridSpec& spec() const { return grid.spec(); }
  GainMap::Value value(std::size_t i) const {
    GainMap::Value v;
    v.p = grid.probability(i);
    v.entropy = entropy_bits(v.p);
    v.state = grid.state(i);
    return v;
  }
};

/// The paper's model (or `Model`, model.hpp) on the target's ray: its gain and visibility, 0 when
/// the ray stops early (visibility below `epsilon`) before it.
/// NOTE: the walk written out, not through traverse's visitor: through the visitor the paper's
/// race took about twice the time (BM_Gain30_Decision/1, 2026-11-26).
template <typename Model>
struct PaperPredictor {
  RayTables<Model> tables;
  double epsilon;
  template <typename Cells>
  TargetPrediction operator()(const Cells& map, const Eigen::Vector3d& origin,
                              const Index3& target) const {
    GridWalk walk(map.spec(), origin, target);
    if (!walk.entered()) return {};
    double p_prev = map.value(walk.linear()).p;
    RayOdds state = tables.enter(walk.m(), p_prev);
    while (!walk.at_end()) {
      if (state.hidden(epsilon)) return {};  // the early stop: a ray stops once it is hidden
      walk.advance();
      const double p = map.value(walk.linear()).p;
      tables.step(state, walk.m(), p_prev, p);
      p_prev = p;
    }
    // eq. (4); v_M: c_M's own occupancy does not update it
    return {map.value(walk.linear()).entropy - entropy_bits(state.posterior()), state.visibility()};
  }
};

/// The survival reading (survival.hpp) on the target's ray: its gain and visibility, 0 once the
/// ray is stopped (visibility below `epsilon`) before it. Walks the cells count_view_gains walks
/// (hierarchy.hpp), so the two agree bit for bit.
struct SurvivalPredictor {
  SurvivalModel model;
  double epsilon;
  template <typename Cells>
  TargetPrediction operator()(const Cells& map, const Eigen::Vector3d& origin,
                              const Index3& target) const {
    GridWalk walk(map.spec(), origin, target);
    if (!walk.entered()) return {};
    GainMap::Value cell = map.value(walk.linear());
    SurvivalModel::State state = model.enter(walk.m(), cell);
    while (!walk.at_end()) {
      if (!(state.visibility >= epsilon && state.visibility > 0.0)) return {};
      walk.advance();
      const GainMap::Value next = map.value(walk.linear());
      model.step(state, cell, next);
      cell = next;
    }
    return SurvivalModel::predict(state, cell);
  }
};

/// The survival reading's v_M alone (TargetPrediction::seen; gain left 0): SurvivalPredictor's
/// walk and products without the occupancy filter, so the same v_M bit for bit at a fraction of
/// the cost, for what keeps visibilities only (view_cells.hpp).
struct SurvivalVisibilityPredictor {
  double alpha;
  double epsilon;
  const FreeSpace* free = nullptr;  ///< free cubes to cross in one step, if any
  template <typename Cells>
  TargetPrediction operator()(const Cells& map, const Eigen::Vector3d& origin,
                              const Index3& target) const {
    GridWalk walk(map.spec(), origin, target);
    if (!walk.entered()) return {};
    CellState prev = map.value(walk.linear()).state;
    double visibility = 1.0;
    while (!walk.at_end()) {
      if (!(visibility >= epsilon && visibility > 0.0)) return {};
      if (free != nullptr && prev == CellState::kFree && free->cross(walk, map.spec())) {
        prev = map.value(walk.linear()).state;
        continue;
      }
      walk.advance();
      if (prev == CellState::kOccupied) {
        visibility = 0.0;
      } else if (prev == CellState::kUnobserved) {
        visibility *= alpha;
      }
      prev = map.value(walk.linear()).state;
    }
    return {0.0, visibility};
  }
};

/// Simple greedy: whether nothing occludes the target, 1 or 0, in bits and in cells. Walks the
/// cells count_view_gains walks (hierarchy.hpp).
struct UnblockedPredictor {
  const FreeSpace* free = nullptr;  ///< free cubes to cross in one step, if any
  template <typename Cells>
  TargetPrediction operator()(const Cells& map, const Eigen::Vector3d& origin,
                              const Index3& target) const {
    GridWalk walk(map.spec(), origin, target);
    if (walk.entered()) {
      while (!walk.at_end()) {
        const CellState state = map.value(walk.linear()).state;
        if (occludes(state)) return {0.0, 0.0};
        if (free == nullptr || state != CellState::kFree || !free->cross(walk, map.spec())) {
          walk.advance();
        }
      }
    }
    return {1.0, 1.0};
  }
};

}  // namespace vantage::detail
