#pragma once
// The decision oracles' states (prune_scenes_test.cpp, swept_scenes_test.cpp): a built-in table
// top after 1, 3 and 6 paper-mode scans with its ring views not yet taken (and on tabletop-4 its
// arm's hemisphere views), travel from the last scan's pose, and every candidate's exact sums to
// hold a search's choice to.

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "vantage/gain/evaluators/hierarchy.hpp"
#include "vantage/map/integrate.hpp"
#include "vantage/planner/observability.hpp"
#include "vantage/planner/planner.hpp"
#include "vantage/sim/world.hpp"
#include "vantage/util/text.hpp"
#include "vantage/views/hemisphere.hpp"
#include "vantage/views/sphere.hpp"

namespace vantage::oracle {

/// Every candidate's exact sums: the survival reading's cells and greedy's count, by the
/// evaluation the exhaustive exact search's sums equal bit for bit (hierarchy_test.cpp).
struct Reference {
  std::vector<ViewGain> survival, greedy;
};

inline Reference reference_of(const OccupancyGrid& grid, const std::vector<Candidate>& cands) {
  std::vector<Frustum> views;
  for (const Candidate& c : cands) views.push_back(c.view);
  const GainMap map(grid, 0);
  const ClassBlocks blocks = summarize_classes(map, views, 0);
  GainConfig gain;
  gain.alpha = kSurvivalAlpha;
  gain.method = GainMethod::kSurvival;
  Reference r;
  r.survival = count_view_gains(map, &blocks, views, GainQuantity::kSurvivalCells, gain);
  gain.method = GainMethod::kGreedy;
  r.greedy = count_view_gains(map, &blocks, views, GainQuantity::kCount, gain);
  return r;
}

/// The exhaustive exact search's score of every candidate under `config`: from `reference` for the
/// survival reading, greedy and Latombe; the paper's model has no cheap exact reference, so its
/// scores are the exhaustive search's own, by the exact evaluation.
inline std::vector<double> exact_scores(const OccupancyGrid& grid,
                                        const std::vector<Candidate>& cands,
                                        const Reference& reference, const PlannerConfig& config) {
  if (config.method == PlannerMethod::kProbabilistic) {
    PlannerConfig exhaustive = config;
    exhaustive.search = DecisionSearch::kExhaustive;
    exhaustive.gain.evaluation = GainEvaluation::kExact;
    return plan_next_view(grid, cands, exhaustive).scores;
  }
  std::vector<double> scores;
  for (std::size_t c = 0; c < cands.size(); ++c) {
    if (config.method == PlannerMethod::kSurvival) {
      scores.push_back(reference.survival[c].cells);
    } else if (config.method == PlannerMethod::kLatombe) {
      scores.push_back(reference.greedy[c].gain * std::exp(-config.lambda * cands[c].travel));
    } else {
      scores.push_back(reference.greedy[c].gain);
    }
  }
  return scores;
}

/// Calls `f(state, grid, ring, scans, last_pose)` for table top `name` after 1, 3 and 6 scans
/// (a fixed order of start poses, fixed seeds): the ring views not yet taken, travel from the
/// last scan's pose.
template <typename F>
void for_each_state(const sim::World& world, const std::string& name, F&& f) {
  constexpr int kOrder[6] = {0, 5, 2, 7, 3, 8};
  const sim::Scene& scene = world.scene();
  OccupancyGrid grid(scene.grid);
  std::vector<Eigen::Isometry3d> taken;
  for (int k = 0; k < 6; ++k) {
    const Eigen::Isometry3d& pose = scene.start_poses[static_cast<std::size_t>(kOrder[k])];
    const sim::SimulatedScan scan = world.scan(pose, 1000 + k);
    integrate_scan(grid, Scan{scan.points_world(), scan.view()}, IntegrationConfig{});
    taken.push_back(pose);
    if (k != 0 && k != 2 && k != 5) continue;
    const Eigen::Vector3d here = pose.translation();
    std::vector<Candidate> ring;
    for (const Eigen::Isometry3d& c : scene.candidate_poses()) {
      const bool was_taken = std::any_of(taken.begin(), taken.end(),
                                         [&](const auto& t) { return t.isApprox(c, 1e-9); });
      if (!was_taken) ring.push_back({Frustum(c, scene.fov()), (c.translation() - here).norm()});
    }
    f(cat(name, " after ", k + 1, " scans, ring"), grid, ring, k + 1, pose);
  }
}

/// An arm's hemisphere views over the scene's target (as explore's --candidates hemisphere takes
/// them: HemisphereConfig's defaults, the scene's arm), travel the straight line from `here`.
inline std::vector<Candidate> hemisphere_candidates(const sim::Scene& scene,
                                                    const Eigen::Vector3d& here) {
  HemisphereConfig hemisphere;
  hemisphere.center = scene.mount.target;
  if (scene.arm) {
    hemisphere.base = scene.arm->base;
    hemisphere.reach = scene.arm->reach;
  }
  std::vector<Candidate> views;
  for (const Eigen::Isometry3d& p : hemisphere_poses(hemisphere)) {
    views.push_back({Frustum(p, scene.fov()), (p.translation() - here).norm()});
  }
  return views;
}

/// `n` sphere views around the scene's ring centre at the ring's radius, travel from `here`.
inline std::vector<Candidate> sphere_candidates(const sim::Scene& scene, int n,
                                                const Eigen::Vector3d& here) {
  SphereConfig sphere;
  sphere.center = scene.ring.center;
  sphere.radius = scene.ring.radius;
  sphere.views = n;
  std::vector<Candidate> views;
  for (const Eigen::Isometry3d& p : sphere_poses(sphere)) {
    views.push_back({Frustum(p, scene.fov()), (p.translation() - here).norm()});
  }
  return views;
}

}  // namespace vantage::oracle
