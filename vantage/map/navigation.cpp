#include "vantage/map/navigation.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <numbers>
#include <queue>
#include <stdexcept>
#include <utility>

#include "vantage/util/text.hpp"

namespace vantage {
namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();
constexpr std::uint32_t kNoParent = std::numeric_limits<std::uint32_t>::max();

/// The z layers whose cell centres lie in [lo, hi], as [first, last].
std::pair<int, int> layers(const GridSpec& spec, double lo, double hi) {
  const double top = spec.dims.z() - 1;
  const double a = std::ceil((lo - spec.origin.z()) / spec.resolution - 0.5);
  const double b = std::floor((hi - spec.origin.z()) / spec.resolution - 0.5);
  return {static_cast<int>(std::clamp(a, 0.0, top + 1.0)),
          static_cast<int>(std::clamp(b, -1.0, top))};
}

/// Obstacle columns of a 3D grid: a column is one where `is_obstacle(linear)` holds for a cell
/// of the band.
template <typename IsObstacle>
std::vector<std::uint8_t> obstacle_columns(const GridSpec& spec, const NavigationConfig& config,
                                           IsObstacle is_obstacle) {
  const std::size_t nx = static_cast<std::size_t>(spec.dims.x());
  const std::size_t ny = static_cast<std::size_t>(spec.dims.y());
  std::vector<std::uint8_t> columns(nx * ny, 0);
  const auto [first, last] = layers(spec, config.min_height, config.max_height);
  for (int z = first; z <= last; ++z) {
    const std::size_t base = nx * ny * static_cast<std::size_t>(z);
    for (std::size_t i = 0; i < nx * ny; ++i) {
      if (columns[i] == 0 && is_obstacle(base + i)) columns[i] = 1;
    }
  }
  return columns;
}

/// The 8 moves: (dx, dy) and their length in cells.
struct Move {
  int dx, dy;
  double length;
};
constexpr Move kMoves[8] = {{1, 0, 1.0},
                            {-1, 0, 1.0},
                            {0, 1, 1.0},
                            {0, -1, 1.0},
                            {1, 1, std::numbers::sqrt2},
                            {1, -1, std::numbers::sqrt2},
                            {-1, 1, std::numbers::sqrt2},
                            {-1, -1, std::numbers::sqrt2}};

/// Which cells a robot standing at `start` may enter.
std::vector<std::uint8_t> passable_cells(const NavigationGrid& nav, const Eigen::Vector2d& start,
                                         std::size_t start_cell) {
  std::vector<std::uint8_t> passable(nav.size());
  for (std::size_t i = 0; i < nav.size(); ++i) passable[i] = !nav.blocked(i);
  const double r = nav.footprint() / 2.0;
  const int reach = static_cast<int>(std::ceil(r / nav.resolution())) + 1;
  const Index2 s = nav.unravel(start_cell);
  for (int dy = -reach; dy <= reach; ++dy) {
    for (int dx = -reach; dx <= reach; ++dx) {
      const Index2 c = s + Index2(dx, dy);
      if (!nav.contains(c)) continue;
      const std::size_t i = nav.linear(c);
      if (!nav.obstacle(i) && (nav.center(c) - start).norm() <= r) passable[i] = 1;
    }
  }
  passable[start_cell] = 1;
  return passable;
}

std::size_t start_cell(const NavigationGrid& nav, const Eigen::Vector2d& start) {
  if (!start.allFinite()) throw std::invalid_argument("navigation: the start is not finite");
  const Eigen::Vector2d cells = (start - nav.origin()) / nav.resolution();
  const Index2 c(static_cast<int>(std::clamp(std::floor(cells.x()), 0.0, nav.dims().x() - 1.0)),
                 static_cast<int>(std::clamp(std::floor(cells.y()), 0.0, nav.dims().y() - 1.0)));
  return nav.linear(c);
}

/// Best-first search from `start` over passable cells: Dijkstra without a goal, A* with one
/// (octile distance, consistent for these moves, so each cell is settled once). Returns whether
/// the goal was settled; `distance` and `parent` hold what was settled.
bool search(const NavigationGrid& nav, const std::vector<std::uint8_t>& passable, std::size_t start,
            std::optional<std::size_t> goal, std::vector<double>& distance,
            std::vector<std::uint32_t>& parent) {
  distance.assign(nav.size(), kInfinity);
  parent.assign(nav.size(), kNoParent);
  std::vector<std::uint8_t> settled(nav.size(), 0);
  const double res = nav.resolution();
  const Index2 target = goal ? nav.unravel(*goal) : Index2::Zero();
  auto heuristic = [&](const Index2& c) {
    if (!goal) return 0.0;
    const Index2 d = (c - target).cwiseAbs();
    const int lo = std::min(d.x(), d.y()), hi = std::max(d.x(), d.y());
    return res * (hi - lo + std::numbers::sqrt2 * lo);
  };
  // NOTE: ties in the queue go to the lower cell index, so the search is deterministic.
  using Entry = std::pair<double, std::uint32_t>;
  std::priority_queue<Entry, std::vector<Entry>, std::greater<>> open;
  distance[start] = 0.0;
  open.emplace(heuristic(nav.unravel(start)), static_cast<std::uint32_t>(start));
  while (!open.empty()) {
    const std::size_t i = open.top().second;
    open.pop();
    if (settled[i] != 0) continue;
    settled[i] = 1;
    if (goal && i == *goal) return true;
    const Index2 c = nav.unravel(i);
    for (const Move& m : kMoves) {
      const Index2 n = c + Index2(m.dx, m.dy);
      if (!nav.contains(n)) continue;
      const std::size_t j = nav.linear(n);
      if (passable[j] == 0 || settled[j] != 0) continue;
      if (m.dx != 0 && m.dy != 0 &&
          (passable[nav.linear(c + Index2(m.dx, 0))] == 0 ||
           passable[nav.linear(c + Index2(0, m.dy))] == 0)) {
        continue;  // no corner cutting
      }
      const double d = distance[i] + m.length * res;
      if (d < distance[j]) {
        distance[j] = d;
        parent[j] = static_cast<std::uint32_t>(i);
        open.emplace(d + heuristic(n), static_cast<std::uint32_t>(j));
      }
    }
  }
  // Only settled cells hold final distances.
  for (std::size_t i = 0; i < nav.size(); ++i) {
    if (settled[i] == 0) distance[i] = kInfinity;
  }
  return false;
}

std::vector<Eigen::Vector2d> trace(const NavigationGrid& nav,
                                   const std::vector<std::uint32_t>& parent, std::size_t start,
                                   std::size_t end) {
  std::vector<Eigen::Vector2d> points;
  for (std::size_t i = end;; i = parent[i]) {
    points.push_back(nav.center(nav.unravel(i)));
    if (i == start) break;
  }
  std::reverse(points.begin(), points.end());
  return points;
}

}  // namespace

void NavigationConfig::validate() const {
  if (!(footprint > 0.0 && std::isfinite(footprint))) {
    throw std::invalid_argument(cat("navigation.footprint must be > 0 m, got ", footprint));
  }
  if (!std::isfinite(min_height) || !std::isfinite(max_height) || !(min_height <= max_height)) {
    throw std::invalid_argument(cat("navigation.min_height (", min_height,
                                    " m) must be finite and not exceed navigation.max_height (",
                                    max_height, " m)"));
  }
}

NavigationGrid::NavigationGrid(const Eigen::Vector2d& origin, double resolution, const Index2& dims,
                               std::vector<std::uint8_t> obstacles, double footprint)
    : origin_(origin),
      resolution_(resolution),
      dims_(dims),
      footprint_(footprint),
      obstacle_(std::move(obstacles)) {
  if (!origin_.allFinite()) throw std::invalid_argument("navigation grid: origin is not finite");
  if (!(resolution_ > 0.0 && std::isfinite(resolution_))) {
    throw std::invalid_argument(
        cat("navigation grid: resolution must be > 0 m, got ", resolution_));
  }
  if (dims_.x() < 1 || dims_.y() < 1) {
    throw std::invalid_argument(
        cat("navigation grid: dims must be positive, got ", dims_.x(), " x ", dims_.y()));
  }
  if (obstacle_.size() != static_cast<std::size_t>(dims_.x()) * dims_.y()) {
    throw std::invalid_argument(cat("navigation grid: ", obstacle_.size(), " obstacle flags for ",
                                    dims_.x(), " x ", dims_.y(), " cells"));
  }
  if (!(footprint_ > 0.0 && std::isfinite(footprint_))) {
    throw std::invalid_argument(cat("navigation grid: footprint must be > 0 m, got ", footprint_));
  }
  // Inflation: stamp a disc of radius footprint / 2 (centre to centre) around every obstacle.
  const double r = footprint_ / 2.0;
  const int reach = static_cast<int>(std::floor(r / resolution_));
  std::vector<Index2> disc;
  for (int dy = -reach; dy <= reach; ++dy) {
    for (int dx = -reach; dx <= reach; ++dx) {
      if ((dx * dx + dy * dy) * resolution_ * resolution_ <= r * r) disc.emplace_back(dx, dy);
    }
  }
  blocked_.assign(obstacle_.size(), 0);
  for (std::size_t i = 0; i < obstacle_.size(); ++i) {
    if (obstacle_[i] == 0) continue;
    const Index2 c = unravel(i);
    for (const Index2& d : disc) {
      const Index2 n = c + d;
      if (contains(n)) blocked_[linear(n)] = 1;
    }
  }
}

NavigationGrid NavigationGrid::from_map(const OccupancyGrid& grid, const NavigationConfig& config) {
  config.validate();
  const GridSpec& spec = grid.spec();
  std::vector<std::uint8_t> columns = obstacle_columns(spec, config, [&](std::size_t i) {
    const CellState s = grid.state(i);
    return s == CellState::kOccupied || (config.unknown_blocks && s == CellState::kUnobserved);
  });
  return {spec.origin.head<2>(), spec.resolution, spec.dims.head<2>(), std::move(columns),
          config.footprint};
}

NavigationGrid NavigationGrid::from_occupancy(const GridSpec& spec,
                                              std::span<const std::uint8_t> occupied,
                                              const NavigationConfig& config) {
  config.validate();
  if (occupied.size() != spec.num_cells()) {
    throw std::invalid_argument(cat("navigation grid: ", occupied.size(),
                                    " occupancy flags for a grid of ", spec.num_cells(), " cells"));
  }
  std::vector<std::uint8_t> columns =
      obstacle_columns(spec, config, [&](std::size_t i) { return occupied[i] != 0; });
  return {spec.origin.head<2>(), spec.resolution, spec.dims.head<2>(), std::move(columns),
          config.footprint};
}

NavigationGrid NavigationGrid::combine(const NavigationGrid& a, const NavigationGrid& b) {
  if (a.dims_ != b.dims_ || a.resolution_ != b.resolution_ || a.origin_ != b.origin_) {
    throw std::invalid_argument("navigation grid: cannot combine grids of different geometry");
  }
  std::vector<std::uint8_t> obstacles(a.obstacle_.size());
  for (std::size_t i = 0; i < obstacles.size(); ++i) {
    obstacles[i] = a.obstacle_[i] != 0 || b.obstacle_[i] != 0;
  }
  return {a.origin_, a.resolution_, a.dims_, std::move(obstacles), a.footprint_};
}

std::optional<Index2> NavigationGrid::cell_of(const Eigen::Vector2d& p) const {
  if (!p.allFinite()) return std::nullopt;
  const Eigen::Vector2d cells = (p - origin_) / resolution_;
  const Eigen::Vector2d floors = cells.array().floor();
  if ((floors.array() < 0.0).any() || floors.x() >= dims_.x() || floors.y() >= dims_.y()) {
    return std::nullopt;
  }
  return Index2(static_cast<int>(floors.x()), static_cast<int>(floors.y()));
}

TravelMap::TravelMap(const NavigationGrid& nav, const Eigen::Vector2d& start)
    : nav_(nav), start_(start_cell(nav, start)) {
  search(nav_, passable_cells(nav_, start, start_), start_, std::nullopt, distance_, parent_);
}

bool TravelMap::reachable(const Index2& c) const {
  return nav_.contains(c) && std::isfinite(distance_[nav_.linear(c)]);
}

std::vector<Eigen::Vector2d> TravelMap::path_to(const Index2& c) const {
  if (!reachable(c)) return {};
  return trace(nav_, parent_, start_, nav_.linear(c));
}

Index2 TravelMap::nearest_reachable(const Eigen::Vector2d& p) const {
  std::size_t best = start_;
  double best_d2 = kInfinity;
  for (std::size_t i = 0; i < distance_.size(); ++i) {
    if (!std::isfinite(distance_[i])) continue;
    const double d2 = (nav_.center(nav_.unravel(i)) - p).squaredNorm();
    if (d2 < best_d2) {
      best_d2 = d2;
      best = i;
    }
  }
  return nav_.unravel(best);
}

std::optional<Index2> TravelMap::nearest_reachable_among(std::span<const Eigen::Vector2d> places,
                                                         const Eigen::Vector2d& p) const {
  std::optional<Index2> best;
  double best_d2 = kInfinity;
  for (const Eigen::Vector2d& place : places) {
    const std::optional<Index2> cell = nav_.cell_of(place);
    if (!cell || !reachable(*cell)) continue;
    const double d2 = (nav_.center(*cell) - p).squaredNorm();
    if (d2 < best_d2) {
      best_d2 = d2;
      best = cell;
    }
  }
  return best;
}

NavigationPath find_path(const NavigationGrid& nav, const Eigen::Vector2d& start,
                         const Eigen::Vector2d& goal) {
  if (!goal.allFinite()) throw std::invalid_argument("navigation: the goal is not finite");
  const std::size_t s = start_cell(nav, start);
  const std::vector<std::uint8_t> passable = passable_cells(nav, start, s);
  NavigationPath path;
  const std::optional<Index2> g = nav.cell_of(goal);
  if (g && passable[nav.linear(*g)] != 0) {
    std::vector<double> distance;
    std::vector<std::uint32_t> parent;
    if (search(nav, passable, s, nav.linear(*g), distance, parent)) {
      path.reached = true;
      path.end = goal;
      path.points = trace(nav, parent, s, nav.linear(*g));
      path.length = distance[nav.linear(*g)];
      return path;
    }
  }
  // The fallback (§5.3.1): as close to the goal as the robot can get.
  const TravelMap travel(nav, start);
  const Index2 end = travel.nearest_reachable(goal);
  path.end = nav.center(end);
  path.points = travel.path_to(end);
  path.length = travel.distance(end);
  return path;
}

}  // namespace vantage
