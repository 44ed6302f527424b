#pragma once
/// @file
/// The walk from a sensor's origin to one target cell that the survival reading and greedy's
/// count evaluate (docs/decision.md, "The hierarchical walk"), cell by cell or across whole blocks
/// of one class in one step, with the same cells either way.
///
/// It visits the cells `traverse` (map/traversal.hpp) visits, with one difference in arithmetic:
/// the k-th boundary of an axis is at t0 + k * dt, computed afresh, not by adding dt k times. So
/// where a whole block is crossed at once, the counts of boundaries crossed on each axis come out
/// of the same formula a cell-by-cell walk evaluates, and both walks take the same cells to the
/// last bit, ties between axes included (tests/gain/hierarchy_test.cpp).

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>

#include "vantage/map/grid_spec.hpp"
#include "vantage/map/traversal.hpp"

namespace vantage {

/// A 6-connected walk to a target cell whose boundary parameters are t0 + k * dt.
class TargetWalk {
 public:
  /// Starts on the ray from `from` to the centre of `target` (a cell of the grid), at the first
  /// grid cell the ray enters. entered() is false when it never does.
  TargetWalk(const GridSpec& spec, const Eigen::Vector3d& from, const Index3& target) {
    const Eigen::Vector3d to = spec.center(target);
    const Index3 first = spec.lattice_index(from);
    const Eigen::Vector3d dir = to - from;
    double t_enter = 0.0, t_exit = 1.0;
    if (!clip_to_grid(spec, from, dir, t_enter, t_exit) || t_enter > t_exit) return;
    for (int a = 0; a < 3; ++a) {
      step_[a] = dir[a] > 0.0 ? 1 : -1;
      left_[a] = std::max(0, (target[a] - first[a]) * step_[a]);
      if (dir[a] == 0.0 || left_[a] == 0) {
        left_[a] = 0;
        continue;
      }
      dt_[a] = spec.resolution / std::abs(dir[a]);
      const double boundary =
          spec.origin[a] + (first[a] + (step_[a] > 0 ? 1 : 0)) * spec.resolution;
      t0_[a] = (boundary - from[a]) / dir[a];
    }
    cell_ = first;
    if (!spec.contains(first)) {
      // As traverse(): jump to the cell that holds the entry point, pulled onto the grid.
      const Index3 entry = spec.lattice_index(from + t_enter * dir)
                               .cwiseMax(Index3::Zero())
                               .cwiseMin(spec.dims - Index3::Ones());
      for (int a = 0; a < 3; ++a) {
        const int n = std::clamp((entry[a] - first[a]) * step_[a], 0, left_[a]);
        done_[a] = n;
        cell_[a] += n * step_[a];
      }
      if (!spec.contains(cell_)) return;
    }
    m_ = done_.sum();
    stride_[0] = step_.x();
    stride_[1] = step_.y() * static_cast<std::ptrdiff_t>(spec.dims.x());
    stride_[2] = step_.z() * static_cast<std::ptrdiff_t>(spec.dims.x()) * spec.dims.y();
    linear_ = static_cast<std::ptrdiff_t>(spec.linear(cell_));
    target_linear_ = static_cast<std::ptrdiff_t>(spec.linear(target));
    for (int a = 0; a < 3; ++a) refresh(a);
    octant_ = (step_[0] > 0 ? 1 : 0) | (step_[1] > 0 ? 2 : 0) | (step_[2] > 0 ? 4 : 0);
    entered_ = true;
  }

  bool entered() const { return entered_; }
  /// The octant of the walk's steps: bit a set when it steps towards higher indices on axis a
  /// (FreeSpace's octants).
  int octant() const { return octant_; }
  /// The cell the walk is in.
  const Index3& cell() const { return cell_; }
  /// Its linear index in the grid.
  std::size_t linear() const { return static_cast<std::size_t>(linear_); }
  /// Its position along the ray from the origin's cell: c_m of docs/model.md.
  int m() const { return m_; }
  /// NOTE: by linear index: the walk stays in the grid, where it names the cell.
  bool at_target() const { return linear_ == target_linear_; }

  /// Moves to the next cell, along the axis whose boundary comes first (the lower axis on a tie).
  /// Only before the target.
  /// NOTE: a branch per axis with constant indices, not an indexed select: the walk's state then
  /// stays in registers (the race's lists, BM_DecisionAtScale).
  [[gnu::always_inline]] void advance() {
    if (next_[0] <= next_[1]) {
      if (next_[0] <= next_[2]) {
        step_along<0>();
      } else {
        step_along<2>();
      }
    } else if (next_[1] <= next_[2]) {
      step_along<1>();
    } else {
      step_along<2>();
    }
  }

  /// Leaves the box [lo, hi] of cells, which holds the walk's cell and not the target, in one
  /// step: afterwards the walk is in the first cell outside the box. Returns how many cells of
  /// the box the walk was in (its cell included).
  int leave_box(const Index3& lo, const Index3& hi) {
    // The crossing that leaves the box first: (parameter, axis), ordered as advance() orders them.
    int exit_axis = -1;
    double exit_t = std::numeric_limits<double>::infinity();
    for (int a = 0; a < 3; ++a) {
      const int inside = step_[a] > 0 ? hi[a] - cell_[a] : cell_[a] - lo[a];  // cells to the face
      const int k = done_[a] + inside;  // the crossing that leaves through the face
      if (k >= left_[a]) continue;      // the target's index is reached first on this axis
      const double t = boundary(a, k);
      if (t < exit_t) {
        exit_t = t;
        exit_axis = a;
      }
    }
    int cells = 1;
    for (int a = 0; a < 3; ++a) {
      // Crossings on axis a that come before the exit: boundary(a, k) < exit_t, or equal with
      // a lower axis; monotonic in k, so counted by an estimate corrected against the formula.
      int k;
      if (a == exit_axis) {
        k = done_[a] + (step_[a] > 0 ? hi[a] - cell_[a] : cell_[a] - lo[a]);
      } else {
        const auto before = [&](int kk) {
          if (kk >= left_[a]) return false;
          const double t = boundary(a, kk);
          return a < exit_axis ? t <= exit_t : t < exit_t;
        };
        k = done_[a];
        if (before(k)) {
          const double guess = std::floor((exit_t - t0_[a]) / dt_[a]);
          k = std::clamp(static_cast<int>(std::min(guess, 1e9)), done_[a], left_[a]);
          while (k > done_[a] && !before(k - 1)) --k;
          while (before(k)) ++k;
        }
      }
      cells += k - done_[a];
      cell_[a] += (k - done_[a]) * step_[a];
      linear_ += (k - done_[a]) * stride_[a];
      m_ += k - done_[a];
      done_[a] = k;
    }
    // The exit crossing itself.
    cell_[exit_axis] += step_[exit_axis];
    linear_ += stride_[exit_axis];
    ++done_[exit_axis];
    ++m_;
    for (int a = 0; a < 3; ++a) refresh(a);
    return cells;
  }

 private:
  template <int A>
  [[gnu::always_inline]] void step_along() {
    cell_[A] += step_[A];
    linear_ += stride_[A];
    ++done_[A];
    ++m_;
    refresh(A);
  }
  double boundary(int a, int k) const { return t0_[a] + k * dt_[a]; }
  /// The next boundary of axis a, or infinity when the walk takes no more steps along it.
  void refresh(int a) {
    next_[a] =
        done_[a] < left_[a] ? boundary(a, done_[a]) : std::numeric_limits<double>::infinity();
  }

  Index3 cell_ = Index3::Zero();
  Eigen::Vector3d t0_ = Eigen::Vector3d::Zero();  ///< the first boundary's parameter per axis
  Eigen::Vector3d dt_ = Eigen::Vector3d::Zero();  ///< parameter between boundaries per axis
  Index3 step_ = Index3::Ones();                  ///< +1 or -1 per axis
  Index3 left_ = Index3::Zero();          ///< crossings from the origin's cell to the target
  Index3 done_ = Index3::Zero();          ///< crossings taken
  double next_[3] = {0.0, 0.0, 0.0};      ///< refresh(): the next boundary per axis
  std::ptrdiff_t stride_[3] = {0, 0, 0};  ///< linear step per axis, signed
  std::ptrdiff_t linear_ = 0;
  std::ptrdiff_t target_linear_ = -1;
  int m_ = 0;
  int octant_ = 0;
  bool entered_ = false;
};

}  // namespace vantage
