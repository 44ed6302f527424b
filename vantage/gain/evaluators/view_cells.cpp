#include "vantage/gain/evaluators/view_cells.hpp"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <optional>
#include <stdexcept>

#include "vantage/gain/evaluators/exact.hpp"
#include "vantage/gain/evaluators/target_sums.hpp"
#include "vantage/gain/evaluators/with_predictor.hpp"
#include "vantage/gain/methods.hpp"
#include "vantage/util/parallel.hpp"
#include "vantage/util/text.hpp"

namespace vantage {
namespace {

/// Adds unobserved cell `cell` to the lists of the members whose frustum holds it, its
/// visibility from `predict` evaluated once for all of them.
template <typename Map, typename Predictor>
void add_target(const Map& map, std::span<const Frustum> views,
                std::span<const std::size_t> members, std::span<const CellBox> boxes,
                const Eigen::Vector3d& origin, const Index3& cell, std::size_t linear,
                const Predictor& predict, std::vector<ViewCells>& out) {
  bool evaluated = false;
  double seen = 0.0;
  detail::for_members_holding(views, members, boxes, cell, map.spec().center(cell),
                              [&](std::size_t m) {
                                if (!evaluated) {
                                  seen = predict(map, origin, cell).seen;
                                  evaluated = true;
                                }
                                ViewCells& list = out[members[m]];
                                ++list.targets;
                                if (seen > 0.0) {
                                  list.cells.push_back(static_cast<std::uint32_t>(linear));
                                  list.seen.push_back(seen);
                                }
                              });
}

/// The lists of every view, each target's visibility from `predict` (target_predictors.hpp).
/// With `sample`, only its cells (unobserved, ascending); else every unobserved cell. `Map` is
/// ClassMap or GainMap.
template <typename Map, typename Predictor>
std::vector<ViewCells> view_cells(const Map& map, std::span<const Frustum> views,
                                  const Predictor& predict,
                                  std::optional<std::span<const std::uint32_t>> sample,
                                  int num_threads) {
  const GridSpec& spec = map.spec();
  std::vector<ViewCells> out(views.size());
  const std::vector<std::vector<std::size_t>> groups = views_by_origin(views);
  run_with_threads(num_threads, [&] {
    tbb::parallel_for(std::size_t{0}, groups.size(), [&](std::size_t g) {
      const std::vector<std::size_t>& members = groups[g];
      const Eigen::Vector3d origin = views[members.front()].origin();
      std::vector<CellBox> boxes;
      const CellBox box = detail::boxes_under(spec, views, members, boxes);
      if (box.empty()) return;
      // NOTE: ascending linear index either way, so every list comes out sorted.
      if (sample) {
        for (const std::uint32_t linear : *sample) {
          const Index3 cell = spec.unravel(linear);
          if ((cell.array() < box.lo.array()).any() || (cell.array() > box.hi.array()).any()) {
            continue;
          }
          add_target(map, views, members, boxes, origin, cell, linear, predict, out);
        }
        return;
      }
      Index3 cell;
      for (cell.z() = box.lo.z(); cell.z() <= box.hi.z(); ++cell.z()) {
        for (cell.y() = box.lo.y(); cell.y() <= box.hi.y(); ++cell.y()) {
          for (cell.x() = box.lo.x(); cell.x() <= box.hi.x(); ++cell.x()) {
            const std::size_t linear = spec.linear(cell);
            if (map.value(linear).state != CellState::kUnobserved) continue;
            add_target(map, views, members, boxes, origin, cell, linear, predict, out);
          }
        }
      }
    });
  });
  return out;
}

}  // namespace

double ViewCells::sum() const {
  double total = 0.0;
  for (const double v : seen) total += v;
  return total;
}

namespace {

std::vector<ViewCells> cells_of(const ClassMap& map, std::span<const Frustum> views,
                                const GainConfig& config,
                                std::optional<std::span<const std::uint32_t>> sample) {
  config.validate();
  // NOTE: the lists sum to the method's quantity in cells, one that reads the cells' classes
  // alone; they hold the cells a view may see, under the paper's model every one.
  const GainQuantity quantity = method_traits(config.method).quantity(GainObjective::kCells);
  if (!counts_classes(quantity)) {
    throw std::invalid_argument(
        cat("exact_view_cells: gain.method must be survival or greedy, got ",
            to_string(config.method)));
  }
  // NOTE: the lists keep v_M only, so the survival reading's rays skip its occupancy filter,
  // and the rays cross free cubes in one step (the same v_M, bit for bit).
  if (quantity == GainQuantity::kSurvivalCells) {
    return view_cells(
        map, views,
        detail::SurvivalVisibilityPredictor{config.alpha, config.epsilon, &map.free_space()},
        sample, config.num_threads);
  }
  return view_cells(map, views, detail::UnblockedPredictor{&map.free_space()}, sample,
                    config.num_threads);
}

}  // namespace

std::vector<ViewCells> exact_view_cells(const ClassMap& map, std::span<const Frustum> views,
                                        const GainConfig& config, int sample_bits) {
  // NOTE: a sample is listed once and read by every view; without one, each view walks its box.
  if (sample_bits <= 0) return cells_of(map, views, config, std::nullopt);
  const std::vector<std::uint32_t> sample = unobserved_sample(map, sample_bits);
  return cells_of(map, views, config, std::span<const std::uint32_t>(sample));
}

std::vector<ViewCells> exact_view_cells(const ClassMap& map, std::span<const Frustum> views,
                                        const GainConfig& config,
                                        std::span<const std::uint32_t> cells) {
  return cells_of(map, views, config, cells);
}

std::vector<ViewCells> paper_view_cells(const GainMap& map, std::span<const Frustum> views,
                                        const GainConfig& config,
                                        std::span<const std::uint32_t> cells) {
  config.validate();
  if (method_traits(config.method).quantity(GainObjective::kCells) != GainQuantity::kPaperCells) {
    throw std::invalid_argument(cat("paper_view_cells: gain.method must be the paper's model, got ",
                                    to_string(config.method)));
  }
  const detail::PaperPredictor<PaperModel> predict{
      RayTables<PaperModel>(config.alpha, map.params().p_min,
                            detail::longest_ray(map.spec(), views)),
      config.epsilon};
  return view_cells(map, views, predict, std::optional(cells), config.num_threads);
}

}  // namespace vantage
