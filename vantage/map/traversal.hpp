#pragma once
/// @file
/// Exact 6-connected grid traversal (Amanatides & Woo, 1987): one walker, `GridWalk`, used by
/// every ray in the project, with one jump policy (leave a box of cells in one step), and
/// `traverse`, the walker between two points clipped to the grid, as a visitor that can stop
/// early.

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdlib>
#include <limits>
#include <type_traits>
#include <utility>

#include "vantage/map/grid_spec.hpp"

namespace vantage {

/// Number of lattice cells a 6-connected traversal from cell a to cell b visits.
inline int lattice_cells_between(const Index3& a, const Index3& b) {
  return (b - a).cwiseAbs().sum() + 1;
}

/// Upper bound on the lattice steps from `origin` to any cell of the grid, plus one.
inline int max_ray_cells(const GridSpec& spec, const Eigen::Vector3d& origin) {
  const Eigen::Vector3d lo = (spec.origin - origin).cwiseAbs();
  const Eigen::Vector3d hi = (spec.max_corner() - origin).cwiseAbs();
  return static_cast<int>(lo.cwiseMax(hi).sum() / spec.resolution) + 4;
}

/// Where the ray o + s * dir lies in the closed box [lo, hi] (slab test): [s_in, s_out], empty
/// (s_in > s_out) when the ray misses it.
inline std::pair<double, double> clip_to_box(const Eigen::Vector3d& lo, const Eigen::Vector3d& hi,
                                             const Eigen::Vector3d& o, const Eigen::Vector3d& dir) {
  constexpr double kInf = std::numeric_limits<double>::infinity();
  double s_in = -kInf, s_out = kInf;
  for (int a = 0; a < 3; ++a) {
    if (dir[a] == 0.0) {
      if (o[a] < lo[a] || o[a] > hi[a]) return {kInf, -kInf};
      continue;
    }
    double t0 = (lo[a] - o[a]) / dir[a], t1 = (hi[a] - o[a]) / dir[a];
    if (t0 > t1) std::swap(t0, t1);
    s_in = std::max(s_in, t0);
    s_out = std::min(s_out, t1);
  }
  return {s_in, s_out};
}

/// Clips the ray o + s * dir, s in [s_in, s_out] as passed in, to the grid's box (slab test).
/// False when the ray runs parallel to a face outside the box; otherwise the caller compares
/// s_in with s_out (they cross when the ray misses the box).
inline bool clip_to_grid(const GridSpec& spec, const Eigen::Vector3d& o, const Eigen::Vector3d& dir,
                         double& s_in, double& s_out) {
  const Eigen::Vector3d lo = spec.origin, hi = spec.max_corner();
  for (int a = 0; a < 3; ++a) {
    if (dir[a] == 0.0) {
      if (o[a] < lo[a] || o[a] >= hi[a]) return false;
      continue;
    }
    double t0 = (lo[a] - o[a]) / dir[a];
    double t1 = (hi[a] - o[a]) / dir[a];
    if (t0 > t1) std::swap(t0, t1);
    s_in = std::max(s_in, t0);
    s_out = std::min(s_out, t1);
  }
  return true;
}

/// The one grid walker (Amanatides & Woo, 1987), used by every ray in the project: the segment
/// from `from` to `to`, from the cell of `from` to the cell of `to`, on the grid's lattice
/// extended to all of space, started at the first grid cell it crosses, with m counted from the
/// cell of `from` (c_m of docs/model.md). Every cell the segment passes through with positive
/// length is visited once and consecutive cells share a face; where it runs exactly through an
/// edge or a corner, one of the touching cells is visited as the step between them (the lower
/// axis first).
///
/// The k-th boundary of an axis lies at t0 + k * dt, computed afresh rather than by adding dt k
/// times, so the one jump policy, `leave_box` (a block of one class, a free cube: the callers say
/// which box), crosses a whole box in one step and lands, to the last bit and ties between axes
/// included, where stepping cell by cell lands (tests/map/traversal_test.cpp).
class GridWalk {
 public:
  GridWalk() = default;
  /// The walk along the segment; entered() is false when it never crosses the grid.
  GridWalk(const GridSpec& spec, const Eigen::Vector3d& from, const Eigen::Vector3d& to) {
    const Index3 first = spec.lattice_index(from);
    const Index3 last = spec.lattice_index(to);
    const Eigen::Vector3d dir = to - from;
    skipped_ = lattice_cells_between(first, last);
    end_ = last;
    end_linear_ = spec.contains(last) ? static_cast<std::ptrdiff_t>(spec.linear(last)) : -1;
    double t_enter = 0.0, t_exit = 1.0;
    if (!clip_to_grid(spec, from, dir, t_enter, t_exit) || t_enter > t_exit) return;
    for (int a = 0; a < 3; ++a) {
      step_[a] = dir[a] > 0.0 ? 1 : -1;
      left_[a] = std::max(0, (last[a] - first[a]) * step_[a]);
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
      // Jump to the cell holding the entry point, pulled onto the grid where rounding put it a
      // hair outside, and never past the segment's own index range.
      const Index3 entry = spec.lattice_index(from + t_enter * dir)
                               .cwiseMax(Index3::Zero())
                               .cwiseMin(spec.dims - Index3::Ones());
      for (int a = 0; a < 3; ++a) {
        done_[a] = std::clamp((entry[a] - first[a]) * step_[a], 0, left_[a]);
        cell_[a] += done_[a] * step_[a];
      }
      if (!spec.contains(cell_)) return;
      t_ = t_enter;
    }
    m_ = done_.sum();
    skipped_ = m_;
    stride_[0] = step_.x();
    stride_[1] = step_.y() * static_cast<std::ptrdiff_t>(spec.dims.x());
    stride_[2] = step_.z() * static_cast<std::ptrdiff_t>(spec.dims.x()) * spec.dims.y();
    linear_ = static_cast<std::ptrdiff_t>(spec.linear(cell_));
    for (int a = 0; a < 3; ++a) refresh(a);
    octant_ = (step_[0] > 0 ? 1 : 0) | (step_[1] > 0 ? 2 : 0) | (step_[2] > 0 ? 4 : 0);
    entered_ = true;
  }
  /// The walk to the centre of `target`, a cell of the grid.
  GridWalk(const GridSpec& spec, const Eigen::Vector3d& from, const Index3& target)
      : GridWalk(spec, from, spec.center(target)) {}

  bool entered() const { return entered_; }
  /// Lattice cells the segment crossed before it entered the grid (docs/model.md counts them as
  /// free); all of them when it never enters.
  int skipped() const { return skipped_; }
  /// The cell of `to` lies outside the grid, so the walk leaves the grid before its end.
  bool ends_outside() const { return end_linear_ < 0; }
  /// The octant of the walk's steps: bit a set when it steps towards higher indices on axis a
  /// (FreeSpace's octants).
  int octant() const { return octant_; }
  /// The cell the walk is in.
  const Index3& cell() const { return cell_; }
  /// Its linear index in the grid (while the walk is in the grid).
  std::size_t linear() const { return static_cast<std::size_t>(linear_); }
  /// Its position along the segment from the cell of `from`: c_m of docs/model.md.
  int m() const { return m_; }
  /// The cell of `to`, where the walk ends (on the lattice extended past the grid).
  const Index3& end() const { return end_; }
  /// In the cell of `to` (never, when that lies outside the grid).
  /// NOTE: by linear index: the walk stays in the grid, where it names the cell.
  bool at_end() const { return linear_ == end_linear_; }
  /// The segment's parameter (0 at `from`, 1 at `to`) where it enters the cell, and where it
  /// leaves it (infinity in the cell of `to`).
  double t() const { return t_; }
  double t_exit() const { return std::min(next_[0], std::min(next_[1], next_[2])); }

  /// Moves to the next cell, along the axis whose boundary comes first (the lower axis on a tie).
  /// Only before the end.
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

  /// The jump: leaves the box [lo, hi] of cells, which holds the walk's cell and not the
  /// segment's end, in one step; afterwards the walk is in the first cell outside the box.
  /// Returns how many cells of the box the walk was in (its cell included).
  int leave_box(const Index3& lo, const Index3& hi) {
    // The crossing that leaves the box first: (parameter, axis), ordered as advance() orders them.
    int exit_axis = -1;
    double exit_t = std::numeric_limits<double>::infinity();
    for (int a = 0; a < 3; ++a) {
      const int inside = step_[a] > 0 ? hi[a] - cell_[a] : cell_[a] - lo[a];  // cells to the face
      const int k = done_[a] + inside;  // the crossing that leaves through the face
      if (k >= left_[a]) continue;      // the end's index is reached first on this axis
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
    t_ = exit_t;
    for (int a = 0; a < 3; ++a) refresh(a);
    return cells;
  }

 private:
  template <int A>
  [[gnu::always_inline]] void step_along() {
    t_ = next_[A];
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
  Index3 left_ = Index3::Zero();          ///< crossings from the cell of `from` to that of `to`
  Index3 done_ = Index3::Zero();          ///< crossings taken
  double next_[3] = {0.0, 0.0, 0.0};      ///< refresh(): the next boundary per axis
  std::ptrdiff_t stride_[3] = {0, 0, 0};  ///< linear step per axis, signed
  std::ptrdiff_t linear_ = 0;
  Index3 end_ = Index3::Zero();
  std::ptrdiff_t end_linear_ = -1;
  double t_ = 0.0;
  int m_ = 0;
  int skipped_ = 0;
  int octant_ = 0;
  bool entered_ = false;
};

/// What one traversal did.
struct TraversalResult {
  /// Lattice cells the segment crossed before it entered the grid. They are not visited;
  /// docs/model.md counts them as free. When the segment never enters the grid, every cell it
  /// crosses counts.
  int skipped = 0;
  int visited = 0;           ///< grid cells handed to the visitor
  bool entered = false;      ///< the segment enters the grid at all
  bool stopped = false;      ///< the visitor asked to stop
  bool reached_end = false;  ///< the cell holding `to` lies in the grid and was visited
  /// The cell holding `to` lies outside the grid, so the walk may leave it.
  bool ends_outside = false;
};

/// Visits, in order, the grid cells that the segment from `from` to `to` crosses: a GridWalk from
/// the cell of `from` to the cell of `to`, which takes exactly |Δi| + |Δj| + |Δk| steps and so
/// always ends in the cell of `to`.
///
/// Cells outside the grid are never visited. Those before the entry are counted in
/// `TraversalResult::skipped` in O(1) (the walk jumps to the entry cell); the walk ends where the
/// segment leaves the grid.
///
/// @param visit  `bool(const Index3& cell, std::size_t linear, int m)` or the same returning void;
///               `m` is the cell's position along the whole segment from `from` (c_m of
///               docs/model.md). Returning false stops the walk.
template <typename Visitor>
TraversalResult traverse(const GridSpec& spec, const Eigen::Vector3d& from,
                         const Eigen::Vector3d& to, Visitor&& visit) {
  TraversalResult result;
  GridWalk walk(spec, from, to);
  result.skipped = walk.skipped();
  result.ends_outside = walk.ends_outside();
  if (!walk.entered()) return result;
  result.entered = true;
  // NOTE: the walk is monotonic along each axis, so it stays in the box of its entry and end
  // cells: only a segment that ends outside the grid can leave it.
  for (;;) {
    ++result.visited;
    if constexpr (std::is_void_v<decltype(visit(walk.cell(), std::size_t{}, walk.m()))>) {
      visit(walk.cell(), walk.linear(), walk.m());
    } else if (!visit(walk.cell(), walk.linear(), walk.m())) {
      result.stopped = true;
      return result;
    }
    if (walk.at_end()) {
      result.reached_end = true;
      return result;
    }
    walk.advance();
    if (result.ends_outside && !spec.contains(walk.cell())) return result;  // left the grid
  }
}

}  // namespace vantage
