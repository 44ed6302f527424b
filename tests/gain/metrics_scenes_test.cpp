// The oracle of the metrics' jumping walk on a built-in table top (issue 36, item 4): tabletop-4
// after 1, 3 and 6 paper-mode scans, its 187 hemisphere views (radii 0.9, 1.1 and 1.3 m, 0.3 m
// apart: the issue-26 sweeps' candidates, bench/metric_bench.cpp's), every metric by
// metric_view_gains against the reference walk that hands every cell to the metric.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "vantage/gain/methods.hpp"
#include "vantage/gain/metrics.hpp"
#include "vantage/map/integrate.hpp"
#include "vantage/sim/world.hpp"
#include "vantage/util/text.hpp"
#include "vantage/views/hemisphere.hpp"
#include "vantage/views/ring.hpp"

namespace vantage {
namespace {

/// Scans from these start poses, in this order (as the other scene oracles take them).
constexpr int kScanOrder[] = {0, 5, 2, 7, 3, 8};

std::size_t best_of(const std::vector<ViewGain>& gains) {
  return static_cast<std::size_t>(
      std::max_element(gains.begin(), gains.end(),
                       [](const ViewGain& a, const ViewGain& b) { return a.gain < b.gain; }) -
      gains.begin());
}

TEST(MetricsScenes, TheJumpingWalkDecidesAsTheReferenceOnTheHemisphere) {
  const sim::World world(sim::load_scene("tabletop-4"));
  const sim::Scene& scene = world.scene();
  HemisphereConfig hemisphere;
  hemisphere.center = scene.mount.target;
  hemisphere.radii = {0.9, 1.1, 1.3};
  hemisphere.spacing = 0.3;
  const std::vector<Frustum> views = make_views(hemisphere_poses(hemisphere), scene.fov());
  ASSERT_EQ(views.size(), 187u);
  OccupancyGrid grid(scene.grid);
  for (int k = 0; k < 6; ++k) {
    const sim::SimulatedScan scan =
        world.scan(scene.start_poses[static_cast<std::size_t>(kScanOrder[k])], 1000 + k);
    integrate_scan(grid, Scan{scan.points_world(), scan.view()}, IntegrationConfig{});
    if (k != 0 && k != 2 && k != 5) continue;
    const GainMap map(grid, 0);
    for (const MethodTraits& method : gain_methods()) {
      if (method.kind != MethodKind::kMetric) continue;
      GainConfig config;
      config.method = method.method;
      const std::vector<ViewGain> fast = metric_view_gains(grid, views, config);
      const std::vector<ViewGain> reference = metric_view_gains_reference(map, views, config);
      const std::string what = cat("tabletop-4 after ", k + 1, " scans, ", method.name);
      EXPECT_EQ(best_of(fast), best_of(reference)) << what;
      // As in metrics_test.cpp: a tie at a free cube's edge, or a cell past the visibility floor.
      const bool floored = config.method == GainMethod::kRearSideEntropy;
      for (std::size_t v = 0; v < views.size(); ++v) {
        EXPECT_NEAR(fast[v].gain, reference[v].gain,
                    1e-3 * std::abs(reference[v].gain) + (floored ? 1e-4 : 0.0))
            << what << ", view " << v;
        EXPECT_NEAR(fast[v].cells, reference[v].cells, 1e-3 * reference[v].cells)
            << what << ", view " << v;
      }
    }
  }
}

}  // namespace
}  // namespace vantage
