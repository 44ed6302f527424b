#include "bench/fixtures.hpp"

#include <map>
#include <mutex>

namespace vantage::bench {

const World& table_top_after_one_scan() {
  static const World world = [] {
    const std::vector<Frustum> views = synthetic::ring_views();
    const Frustum& view = views[static_cast<std::size_t>(synthetic::kScanOrder[0])];
    PointCloud points = synthetic::scan(synthetic::table_top(0), view, 640, 480);
    OccupancyGrid grid(synthetic::grid_spec(129));
    integrate_scan(grid, Scan{points, view}, IntegrationConfig{});
    return World{std::move(grid), views, std::move(points), view};
  }();
  return world;
}

std::vector<Frustum> candidates(int n, int scale) {
  std::vector<Frustum> views = synthetic::ring_views(scale, (n + 2) / 3);
  views.resize(static_cast<std::size_t>(n), views.front());
  return views;
}

const World& scaled_world(int cells) {
  static std::mutex mutex;
  static std::map<int, World> worlds;
  const std::lock_guard lock(mutex);
  auto it = worlds.find(cells);
  if (it == worlds.end()) {
    const int scale = (cells - 1) / 128;
    const std::vector<Frustum> views = candidates(300, scale);
    const Frustum view =
        synthetic::ring_views(scale)[static_cast<std::size_t>(synthetic::kScanOrder[0])];
    PointCloud points = synthetic::scan(synthetic::table_top(0, scale), view, 640, 480);
    OccupancyGrid grid(synthetic::grid_spec(cells));
    IntegrationConfig integration;
    integration.mode = IntegrationMode::kEndpoint;
    integrate_scan(grid, Scan{points, view}, integration);
    it = worlds.emplace(cells, World{std::move(grid), views, std::move(points), view}).first;
  }
  return it->second;
}

}  // namespace vantage::bench
