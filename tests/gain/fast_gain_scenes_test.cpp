// The oracle of the fast gain evaluation on the built-in table tops of vantage::sim: after 1, 3
// and 6 paper-mode scans from the scene's start poses, the fast gain of each of the 30 ring
// candidates against the exact evaluation of the literal model (docs/model.md).

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <string>
#include <vector>

#include "vantage/gain/exact.hpp"
#include "vantage/gain/fast.hpp"
#include "vantage/gain/view_gain.hpp"
#include "vantage/map/integrate.hpp"
#include "vantage/planner/choose.hpp"
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
    const auto fast = fast_view_gains(grid, views, GainConfig{});
    // The exact mode's own early stop (a ray hidden below epsilon) against the
    // literal model.
    const auto exact_default = exact_view_gains(grid, views, exact_defaults());
    // Auto is the exact evaluation, bit for bit, whatever the thread count: it costs as little as
    // the fast one or less in every state measured (BENCHMARK.md, "One planner").
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
    std::vector<double> errors, exact_gains, fast_gains;
    for (std::size_t v = 0; v < views.size(); ++v) {
      ASSERT_GT(exact[v].gain, 0.0) << state << ", view " << v;
      errors.push_back(std::abs(fast[v].gain - exact[v].gain) / exact[v].gain);
      exact_gains.push_back(exact[v].gain);
      fast_gains.push_back(fast[v].gain);
    }
    std::sort(errors.begin(), errors.end());
    EXPECT_LE(errors[errors.size() / 2], 0.02) << state << ": median relative error";
    EXPECT_LE(errors.back(), 0.05) << state << ": worst relative error";
    // E in cells (docs/model.md): tighter bounds than the bits, ~10x the worst measured (median
    // <= 7.8e-6, worst <= 4.4e-5 over the 12 states).
    std::vector<double> cell_errors;
    for (std::size_t v = 0; v < views.size(); ++v) {
      ASSERT_GT(exact[v].cells, 0.0) << state << ", view " << v;
      cell_errors.push_back(std::abs(fast[v].cells - exact[v].cells) / exact[v].cells);
    }
    std::sort(cell_errors.begin(), cell_errors.end());
    EXPECT_LE(cell_errors[cell_errors.size() / 2], 1e-4) << state << ": median error of E";
    EXPECT_LE(cell_errors.back(), 5e-4) << state << ": worst error of E";
    std::printf("%s: E median %.2e, worst %.2e; bits median %.2e, worst %.2e\n", state.c_str(),
                cell_errors[cell_errors.size() / 2], cell_errors.back(), errors[errors.size() / 2],
                errors.back());
    const double best = exact_gains[choose_best(exact_gains)];
    const double chosen = exact_gains[choose_best(fast_gains)];
    EXPECT_GE(chosen, 0.99 * best) << state << ": exact gain of the fast choice";
  }
}

TEST(FastGainScenes, Tabletop1) { check_scene("tabletop-1"); }
TEST(FastGainScenes, Tabletop2) { check_scene("tabletop-2"); }
TEST(FastGainScenes, Tabletop3) { check_scene("tabletop-3"); }
TEST(FastGainScenes, Tabletop4) { check_scene("tabletop-4"); }

TEST(FastGainScenes, EveryBuiltInTableTopIsCovered) {
  std::vector<std::string> table_tops;
  for (const std::string& name : sim::builtin_scene_names()) {
    if (name.rfind("tabletop-", 0) == 0) table_tops.push_back(name);
  }
  EXPECT_EQ(table_tops,
            (std::vector<std::string>{"tabletop-1", "tabletop-2", "tabletop-3", "tabletop-4"}));
}

}  // namespace
}  // namespace vantage
