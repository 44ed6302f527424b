// The oracle of the metrics' jumping walk on a built-in table top (issue 36, item 4): tabletop-4
// in the decision oracles' states (after 1, 3 and 6 paper-mode scans, tests/planner/
// oracle_states.hpp) and its 187 hemisphere views (radii 0.9, 1.1 and 1.3 m, 0.3 m apart: the
// issue-26 sweeps' candidates, bench/metric_bench.cpp's), every metric by metric_view_gains and by
// MetricEvaluator without the cells counted against the reference walk that hands every cell to the
// metric (metric_oracle.hpp).

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "metric_oracle.hpp"
#include "tests/planner/oracle_states.hpp"
#include "vantage/gain/methods.hpp"
#include "vantage/util/text.hpp"
#include "vantage/views/ring.hpp"

namespace vantage {
namespace {

TEST(MetricsScenes, TheJumpingWalkDecidesAsTheReferenceOnTheHemisphere) {
  const sim::World world(sim::load_scene("tabletop-4"));
  const sim::Scene& scene = world.scene();
  HemisphereConfig hemisphere;
  hemisphere.center = scene.mount.target;
  hemisphere.radii = {0.9, 1.1, 1.3};
  hemisphere.spacing = 0.3;
  const std::vector<Frustum> views = make_views(hemisphere_poses(hemisphere), scene.fov());
  ASSERT_EQ(views.size(), 187u);
  oracle::for_each_state(
      world, "tabletop-4", [&](const std::string& state, const OccupancyGrid& grid, auto&&...) {
        const GainMap map(grid, 0);
        for (const MethodTraits& method : gain_methods()) {
          if (method.kind != MethodKind::kMetric) continue;
          GainConfig config;
          config.method = method.method;
          const std::string what = cat(state, ", hemisphere, ", method.name);
          const std::vector<ViewGain> reference = metric_view_gains_reference(map, views, config);
          test::expect_like_reference(metric_view_gains(grid, views, config), reference, what);
          // Without the cells counted (the swept search's race), the proximity count crosses
          // cubes of the unobserved cells it leaves unchanged too.
          const std::vector<ViewGain> uncounted =
              MetricEvaluator(grid, config).gains(views, 1, /*count_cells=*/false);
          for (std::size_t v = 0; v < views.size(); ++v) {
            EXPECT_EQ(uncounted[v].gain, reference[v].gain) << what << ", view " << v;
          }
        }
      });
}

}  // namespace
}  // namespace vantage
