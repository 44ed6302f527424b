// The sequence decision (vantage/planner/sequence.hpp) and the per-cell visibilities it plans
// with (vantage/gain/evaluators/view_cells.hpp), on a small seeded cluttered grid: each view's
// cells against the exact evaluation, the joint value against a brute-force union, its monotone and
// submodular shape, the tour against Held-Karp, horizon 1 against today's decision, and thread
// counts.

#include "vantage/planner/sequence.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <map>
#include <set>
#include <vector>

#include "vantage/gain/class_map.hpp"
#include "vantage/gain/evaluators/exact.hpp"
#include "vantage/gain/evaluators/metric_evaluator.hpp"
#include "vantage/gain/evaluators/view_cells.hpp"
#include "vantage/gain/methods.hpp"
#include "vantage/gain/models/metrics/shared.hpp"
#include "vantage/gain/snapshot.hpp"
#include "vantage/planner/planner.hpp"
#include "vantage/views/ring.hpp"

namespace vantage {
namespace {

std::uint64_t mix(std::uint64_t z) {
  z += 0x9E3779B97F4A7C15ULL;
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
  return z ^ (z >> 31);
}

/// A 24 x 24 x 12 grid: a free shell around the edge, inside it seeded clutter (8 % occupied,
/// 30 % free, the rest unobserved), and eight views around it.
struct Clutter {
  OccupancyGrid grid{GridSpec::centered({0, 0, 0}, 0.05, {24, 24, 12})};
  std::vector<Frustum> views;
  std::vector<Candidate> candidates;

  explicit Clutter(std::uint64_t seed = 7) {
    for (std::size_t i = 0; i < grid.size(); ++i) {
      const Index3 c = grid.spec().unravel(i);
      const bool edge = c.x() < 2 || c.y() < 2 || c.x() > 21 || c.y() > 21;
      const std::uint64_t r = mix(seed * 1000003 + i) % 100;
      if (edge || (r >= 8 && r < 38)) {
        grid.miss(i);
      } else if (r < 8) {
        grid.hit(i);
      }
    }
    for (int k = 0; k < 8; ++k) {
      const double a = k * M_PI / 4;
      const Eigen::Vector3d eye(1.2 * std::cos(a), 1.2 * std::sin(a), 0.4);
      views.emplace_back(look_at(eye, Eigen::Vector3d::Zero()),
                         SensorFov{deg2rad(50), deg2rad(40), 0.2, 4.0});
      candidates.push_back({views.back(), 0.3 * k, true});
    }
  }

  GainConfig gain(GainMethod method, int threads = 0) const {
    GainConfig g;
    g.method = method;
    g.alpha = 0.9;
    g.evaluation = GainEvaluation::kExact;
    g.num_threads = threads;
    return g;
  }
};

double joint_of(const std::vector<ViewCells>& lists, const std::vector<std::size_t>& set) {
  std::vector<const ViewCells*> views;
  for (const std::size_t i : set) views.push_back(&lists[i]);
  return joint_cells(views);
}

TEST(ViewCells, SumToTheExactEvaluationsCellsViewByView) {
  const Clutter s;
  const GainMap map(s.grid, 0);
  for (const GainMethod method : {GainMethod::kGreedy, GainMethod::kSurvival}) {
    const GainConfig gain = s.gain(method);
    const std::vector<ViewCells> lists = exact_view_cells(ClassMap(s.grid), s.views, gain);
    const std::vector<ViewGain> exact = exact_view_gains(map, s.views, gain);
    ASSERT_EQ(lists.size(), s.views.size());
    for (std::size_t v = 0; v < s.views.size(); ++v) {
      EXPECT_EQ(lists[v].targets, exact[v].targets) << to_string(method) << " view " << v;
      EXPECT_NEAR(lists[v].sum(), exact[v].cells, 1e-9 * (1.0 + exact[v].cells));
      EXPECT_GT(lists[v].sum(), 0.0);
      EXPECT_TRUE(std::is_sorted(lists[v].cells.begin(), lists[v].cells.end()));
      for (const double seen : lists[v].seen) {
        EXPECT_GT(seen, 0.0);
        EXPECT_LE(seen, 1.0);
      }
    }
  }
}

// A sample's lists are the full lists cut to the sampled cells, values unchanged; a sequence
// planned on it values each view at 2^k times its sampled sum, the same for any thread count.
TEST(ViewCells, ASampleKeepsTheSampledCellsOfTheFullLists) {
  const Clutter s;
  const ClassMap map(s.grid);
  const GainConfig gain = s.gain(GainMethod::kSurvival);
  const std::vector<ViewCells> full = exact_view_cells(map, s.views, gain);
  const std::vector<ViewCells> sample = exact_view_cells(map, s.views, gain, 2);
  std::size_t kept = 0;
  for (std::size_t v = 0; v < s.views.size(); ++v) {
    ViewCells cut;
    for (std::size_t k = 0; k < full[v].cells.size(); ++k) {
      if (!in_cell_sample(full[v].cells[k], 2)) continue;
      cut.cells.push_back(full[v].cells[k]);
      cut.seen.push_back(full[v].seen[k]);
    }
    EXPECT_EQ(sample[v].cells, cut.cells) << "view " << v;
    EXPECT_EQ(sample[v].seen, cut.seen) << "view " << v;
    EXPECT_LT(sample[v].targets, full[v].targets);
    kept += cut.cells.size();
  }
  EXPECT_GT(kept, 0u);
  SequenceConfig config;
  config.horizon = 3;
  config.sample_bits = 2;
  const std::vector<double> travel(s.views.size(), 0.0);
  const SequencePlan one =
      plan_sequence(s.grid, s.views, travel, s.gain(GainMethod::kSurvival, 1), config);
  const SequencePlan two =
      plan_sequence(s.grid, s.views, travel, s.gain(GainMethod::kSurvival, 2), config);
  EXPECT_EQ(one.tour, two.tour);
  EXPECT_EQ(one.value, two.value);
  for (std::size_t v = 0; v < s.views.size(); ++v) {
    EXPECT_DOUBLE_EQ(one.gains[v].cells, 4.0 * sample[v].sum()) << "view " << v;
  }
  EXPECT_EQ(one.chosen.size(), 3u);
}

TEST(ViewCells, RefusesAModelWithoutPerCellVisibilities) {
  const Clutter s;
  EXPECT_THROW(exact_view_cells(ClassMap(s.grid), s.views, s.gain(GainMethod::kProbabilistic)),
               std::invalid_argument);
}

// The paper's model's lists (the race's values under it) over every unobserved cell: each view's
// v_M summed is the exact evaluation's E; another model is refused.
TEST(ViewCells, ThePaperModelsListsSumToTheExactEvaluationsCells) {
  const Clutter s;
  const GainMap map(s.grid, 0);
  const GainConfig gain = s.gain(GainMethod::kProbabilistic);
  const std::vector<std::vector<std::uint32_t>> every =
      unobserved_by_sample(ClassMap(s.grid), s.grid.size());
  ASSERT_EQ(every.size(), 1u);  // one level: all the unobserved cells, ascending
  const std::vector<ViewCells> lists = paper_view_cells(map, s.views, gain, every[0]);
  const std::vector<ViewGain> exact = exact_view_gains(map, s.views, gain);
  ASSERT_EQ(lists.size(), s.views.size());
  for (std::size_t v = 0; v < s.views.size(); ++v) {
    EXPECT_EQ(lists[v].targets, exact[v].targets) << "view " << v;
    EXPECT_NEAR(lists[v].sum(), exact[v].cells, 1e-9 * (1.0 + exact[v].cells)) << "view " << v;
    EXPECT_GT(lists[v].sum(), 0.0);
  }
  EXPECT_THROW(paper_view_cells(map, s.views, s.gain(GainMethod::kSurvival), every[0]),
               std::invalid_argument);
}

TEST(JointValue, GreedyIsTheSizeOfTheUnionOfWhatEachViewSeesAlone) {
  const Clutter s;
  const GainConfig gain = s.gain(GainMethod::kGreedy);
  const std::vector<ViewCells> lists = exact_view_cells(ClassMap(s.grid), s.views, gain);
  // Brute force: every unobserved cell in each frustum, judged on its own by exact_cell_gain.
  std::vector<std::set<std::size_t>> seen(s.views.size());
  for (std::size_t v = 0; v < s.views.size(); ++v) {
    for (std::size_t i = 0; i < s.grid.size(); ++i) {
      const Index3 c = s.grid.spec().unravel(i);
      if (s.grid.state(i) != CellState::kUnobserved ||
          !s.views[v].contains(s.grid.spec().center(c))) {
        continue;
      }
      if (exact_cell_gain(s.grid, s.views[v].origin(), c, gain) > 0.0) seen[v].insert(i);
    }
  }
  for (const std::vector<std::size_t>& set : std::vector<std::vector<std::size_t>>{
           {0}, {0, 1}, {0, 4}, {1, 2, 3}, {0, 2, 4, 6}, {0, 1, 2, 3, 4, 5, 6, 7}}) {
    std::set<std::size_t> all;
    for (const std::size_t v : set) all.insert(seen[v].begin(), seen[v].end());
    EXPECT_EQ(joint_of(lists, set), static_cast<double>(all.size()));
  }
}

TEST(JointValue, SurvivalCountsEachCellOnceAtOneMinusTheChanceNoViewSeesIt) {
  const Clutter s;
  const std::vector<ViewCells> lists =
      exact_view_cells(ClassMap(s.grid), s.views, s.gain(GainMethod::kSurvival));
  const std::vector<std::size_t> set = {0, 1, 3};
  std::map<std::uint32_t, double> missed;
  for (const std::size_t v : set) {
    for (std::size_t k = 0; k < lists[v].cells.size(); ++k) {
      auto [it, fresh] = missed.try_emplace(lists[v].cells[k], 1.0);
      it->second *= 1.0 - lists[v].seen[k];
    }
  }
  double expected = 0.0;
  for (const auto& [cell, m] : missed) expected += 1.0 - m;
  EXPECT_NEAR(joint_of(lists, set), expected, 1e-9 * expected);
  // Overlapping views: less than the sum of their values, more than the best of them.
  const double sum = lists[0].sum() + lists[1].sum() + lists[3].sum();
  EXPECT_LT(expected, sum - 1.0);
  EXPECT_GT(expected, std::max({lists[0].sum(), lists[1].sum(), lists[3].sum()}));
}

TEST(JointValue, IsMonotoneAndSubmodular) {
  const Clutter s;
  for (const GainMethod method : {GainMethod::kGreedy, GainMethod::kSurvival}) {
    const std::vector<ViewCells> lists =
        exact_view_cells(ClassMap(s.grid), s.views, s.gain(method));
    // Random A within B, x outside B: J(A) <= J(B), J(A + x) - J(A) >= J(B + x) - J(B).
    int strict = 0;
    for (std::uint64_t t = 0; t < 200; ++t) {
      std::vector<std::size_t> a, b;
      const std::size_t x = mix(t) % 8;
      for (std::size_t v = 0; v < 8; ++v) {
        if (v == x) continue;
        const std::uint64_t r = mix(t * 17 + v) % 3;
        if (r == 0) a.push_back(v);
        if (r <= 1) b.push_back(v);
      }
      std::vector<std::size_t> ax = a, bx = b;
      ax.push_back(x);
      bx.push_back(x);
      const double ja = joint_of(lists, a), jb = joint_of(lists, b);
      const double gain_a = joint_of(lists, ax) - ja, gain_b = joint_of(lists, bx) - jb;
      EXPECT_LE(ja, jb + 1e-9);
      EXPECT_GE(gain_a, gain_b - 1e-9) << to_string(method) << " trial " << t;
      strict += gain_a > gain_b + 1e-6 ? 1 : 0;
    }
    EXPECT_GT(strict, 20) << "the views should overlap: " << to_string(method);
  }
}

/// Held-Karp: the shortest open path from the start through every point, by dynamic programming.
double held_karp(const std::vector<double>& start, const std::vector<double>& d) {
  const std::size_t n = start.size();
  const double inf = std::numeric_limits<double>::infinity();
  std::vector<double> best((std::size_t{1} << n) * n, inf);  // [set][last]
  for (std::size_t i = 0; i < n; ++i) best[(std::size_t{1} << i) * n + i] = start[i];
  for (std::size_t set = 1; set < (std::size_t{1} << n); ++set) {
    for (std::size_t last = 0; last < n; ++last) {
      const double here = best[set * n + last];
      if (!(set >> last & 1) || here == inf) continue;
      for (std::size_t next = 0; next < n; ++next) {
        if (set >> next & 1) continue;
        double& to = best[(set | std::size_t{1} << next) * n + next];
        to = std::min(to, here + d[last * n + next]);
      }
    }
  }
  return *std::min_element(best.end() - static_cast<std::ptrdiff_t>(n), best.end());
}

TEST(OpenTour, IsTheShortestOrderAsHeldKarpFindsIt) {
  for (std::uint64_t t = 0; t < 30; ++t) {
    const std::size_t n = 1 + mix(t) % 7;
    std::vector<Eigen::Vector3d> p;
    for (std::size_t i = 0; i <= n; ++i) {
      p.emplace_back(static_cast<double>(mix(t * 100 + 3 * i) % 1000) / 100.0,
                     static_cast<double>(mix(t * 100 + 3 * i + 1) % 1000) / 100.0, 0.0);
    }
    std::vector<double> start(n), d(n * n);
    for (std::size_t i = 0; i < n; ++i) {
      start[i] = (p[i + 1] - p[0]).norm();
      for (std::size_t j = 0; j < n; ++j) d[i * n + j] = (p[j + 1] - p[i + 1]).norm();
    }
    const OpenTour tour = shortest_open_tour(start, d);
    ASSERT_EQ(tour.order.size(), n);
    double length = start[tour.order[0]];
    for (std::size_t i = 1; i < n; ++i) length += d[tour.order[i - 1] * n + tour.order[i]];
    EXPECT_DOUBLE_EQ(tour.length, length);
    EXPECT_NEAR(tour.length, held_karp(start, d), 1e-9) << "trial " << t;
  }
  // Points on a line ahead of the start: visited in order of distance.
  const std::vector<double> start = {3.0, 1.0, 2.0}, d = {0, 2, 1, 2, 0, 1, 1, 1, 0};
  EXPECT_EQ(shortest_open_tour(start, d).order, (std::vector<std::size_t>{1, 2, 0}));
  EXPECT_THROW(shortest_open_tour(start, std::vector<double>(4)), std::invalid_argument);
}

TEST(RingWalk, IsTheArcBetweenBearingsPlusTheChangeInRadius) {
  const TravelRule walk{TravelRule::Kind::kRingWalk, Eigen::Vector3d(1, 1, 0), 2.0};
  EXPECT_NEAR(walk({3, 1, 0}, {1, 3, 5}), M_PI, 1e-12);               // a quarter turn at r = 2
  EXPECT_NEAR(walk({3, 1, 0}, {-1.5, 1, 0}), 2 * M_PI + 0.5, 1e-12);  // half, and 0.5 m out
  EXPECT_NEAR(TravelRule{}({0, 0, 0}, {3, 4, 0}), 5.0, 1e-12);
}

TEST(Sequence, HorizonOneWithoutTravelWeightIsTodaysDecision) {
  for (std::uint64_t seed : {3u, 7u, 11u}) {
    const Clutter s(seed);
    for (const PlannerMethod method :
         {PlannerMethod::kSurvival, PlannerMethod::kGreedy, PlannerMethod{GainMethod::kSurface}}) {
      const GainQuantity quantity = method_traits(method.gain).quantity(GainObjective::kCells);
      PlannerConfig today;
      today.method = method;
      today.objective = GainObjective::kCells;
      today.gain = s.gain(method.gain);
      today.search = DecisionSearch::kExhaustive;
      const Plan plan = plan_next_view(s.grid, s.candidates, today);
      std::vector<double> travel;
      for (const Candidate& c : s.candidates) travel.push_back(c.travel);
      const SequencePlan sequence =
          plan_sequence(s.grid, s.views, travel, today.gain, SequenceConfig{});
      EXPECT_EQ(sequence.first, plan.best) << to_string(method) << " seed " << seed;
      EXPECT_EQ(sequence.tour, std::vector<std::size_t>{plan.best});
      for (std::size_t c = 0; c < s.candidates.size(); ++c) {
        EXPECT_EQ(sequence.gains[c].value(quantity), plan.gains[c].value(quantity))
            << to_string(method) << " candidate " << c;
      }
      // ... and the pruned search, which proves its choice, agrees (the swept for a metric).
      today.search =
          quantity == GainQuantity::kMetric ? DecisionSearch::kSwept : DecisionSearch::kPruned;
      EXPECT_EQ(plan_next_view(s.grid, s.candidates, today).best, sequence.first);
    }
  }
}

TEST(Sequence, PlansKViewsThatJointlySeeMoreThanTheBestViewTwice) {
  const Clutter s;
  std::vector<double> travel(s.views.size(), 0.0);
  SequenceConfig config;
  config.horizon = 3;
  const GainConfig gain = s.gain(GainMethod::kGreedy);
  const SequencePlan plan = plan_sequence(s.grid, s.views, travel, gain, config);
  ASSERT_EQ(plan.chosen.size(), 3u);
  const std::vector<ViewCells> lists = exact_view_cells(ClassMap(s.grid), s.views, gain);
  EXPECT_EQ(plan.value, joint_of(lists, plan.chosen));
  // Greedy selection: no single swap of the last view chosen does better.
  for (std::size_t v = 0; v < s.views.size(); ++v) {
    if (std::count(plan.chosen.begin(), plan.chosen.end(), v) > 0) continue;
    std::vector<std::size_t> other = {plan.chosen[0], plan.chosen[1], v};
    EXPECT_LE(joint_of(lists, other), plan.value);
  }
  // The tour starts at the chosen view nearest the start along the ring of views.
  std::set<std::size_t> a(plan.tour.begin(), plan.tour.end()),
      b(plan.chosen.begin(), plan.chosen.end());
  EXPECT_EQ(a, b);
}

// The surface model's sequence: a cell's credit is v(x) r(x), the chance that the view's ray
// reaches it times the chance that it holds a surface, which all views share; so the joint value
// is sum_x r(x) [1 - prod_k (1 - v_k(x))], and a cell two views would both reach counts once.
double surface_joint(const std::vector<ViewCells>& lists, const std::vector<std::size_t>& set,
                     const std::vector<float>& near, const SurfaceRates& rates) {
  std::map<std::uint32_t, double> missed;
  for (const std::size_t v : set) {
    for (std::size_t k = 0; k < lists[v].cells.size(); ++k) {
      const std::uint32_t c = lists[v].cells[k];
      const double r = rates[surface_class(near[c])];
      missed.try_emplace(c, 1.0).first->second *= 1.0 - lists[v].seen[k] / r;
    }
  }
  double total = 0.0;
  for (const auto& [c, m] : missed) total += rates[surface_class(near[c])] * (1.0 - m);
  return total;
}

TEST(Sequence, TheSurfaceModelsSequenceCountsACellsSurfaceOnce) {
  const Clutter s;
  std::vector<double> travel(s.views.size(), 0.0);
  SequenceConfig config;
  config.horizon = 3;
  GainConfig gain = s.gain(GainMethod::kSurface);
  gain.surface_rates = {0.3, 0.2, 0.1, 0.05, 0.01};
  const SequencePlan plan = plan_sequence(s.grid, s.views, travel, gain, config);
  ASSERT_EQ(plan.chosen.size(), 3u);
  const MetricEvaluator evaluator(s.grid, gain);
  const std::vector<ViewCells> lists = evaluator.cells(s.views, evaluator.creditable());
  const std::vector<float> near = occupied_distance(GainMap(s.grid), kProximityCells);
  const auto joint = [&](const std::vector<std::size_t>& set) {
    return surface_joint(lists, set, near, gain.surface_rates);
  };
  EXPECT_NEAR(plan.value, joint(plan.chosen), 1e-9 * plan.value);
  double singles = 0.0;
  for (const std::size_t v : plan.chosen) singles += plan.gains[v].gain;
  EXPECT_LT(plan.value, singles);  // the views overlap: some cells are not counted twice
  EXPECT_GT(plan.value, plan.gains[plan.chosen[0]].gain);
  for (std::size_t v = 0; v < s.views.size(); ++v) {  // no swap of the last view does better
    if (std::count(plan.chosen.begin(), plan.chosen.end(), v) > 0) continue;
    EXPECT_LE(joint({plan.chosen[0], plan.chosen[1], v}), plan.value * (1 + 1e-12));
  }
}

TEST(Sequence, ATravelWeightTradesValueForAShorterTour) {
  const Clutter s;
  std::vector<double> travel;
  for (const Candidate& c : s.candidates) travel.push_back(c.travel);
  SequenceConfig config;
  config.horizon = 3;
  const GainConfig gain = s.gain(GainMethod::kSurvival);
  const SequencePlan free = plan_sequence(s.grid, s.views, travel, gain, config);
  config.travel_weight = 5.0;
  const SequencePlan costly = plan_sequence(s.grid, s.views, travel, gain, config);
  EXPECT_LT(costly.tour_length, free.tour_length);
  EXPECT_LE(costly.value, free.value);
}

TEST(Sequence, TheSameForOneAndTwoThreads) {
  const Clutter s;
  std::vector<double> travel;
  for (const Candidate& c : s.candidates) travel.push_back(c.travel);
  SequenceConfig config;
  config.horizon = 4;
  config.travel_weight = 0.1;
  config.shortlist = 6;
  for (const GainMethod method : {GainMethod::kSurvival, GainMethod::kGreedy}) {
    const SequencePlan one = plan_sequence(s.grid, s.views, travel, s.gain(method, 1), config);
    const SequencePlan two = plan_sequence(s.grid, s.views, travel, s.gain(method, 2), config);
    EXPECT_EQ(one.tour, two.tour);
    EXPECT_EQ(one.chosen, two.chosen);
    EXPECT_EQ(one.value, two.value);
    EXPECT_EQ(one.tour_length, two.tour_length);
    EXPECT_EQ(one.shortlisted, 6u);
    for (const std::size_t v : one.chosen) {
      EXPECT_LT(v, s.views.size());
    }
  }
}

TEST(Sequence, BadSettingsAreRefusedByName) {
  const auto refuses = [](auto change, const char* field) {
    SequenceConfig config;
    change(config);
    try {
      config.validate();
      ADD_FAILURE() << "accepted a bad " << field;
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find(field), std::string::npos) << e.what();
    }
  };
  refuses([](SequenceConfig& c) { c.horizon = 0; }, "planner.sequence.horizon");
  refuses([](SequenceConfig& c) { c.horizon = 7; }, "planner.sequence.horizon");
  refuses([](SequenceConfig& c) { c.travel_weight = -1.0; }, "planner.sequence.travel_weight");
  refuses([](SequenceConfig& c) { c.travel_weight = NAN; }, "planner.sequence.travel_weight");
  refuses([](SequenceConfig& c) { c.shortlist = 0; }, "planner.sequence.shortlist");
  PlannerConfig planner;
  planner.method = PlannerMethod::kProbabilistic;
  planner.sequence.horizon = 2;
  EXPECT_THROW(planner.validate(), std::invalid_argument);
  planner.method = PlannerMethod::kSurvival;
  planner.objective = GainObjective::kBits;
  EXPECT_THROW(planner.validate(), std::invalid_argument);
  planner.objective = GainObjective::kCells;
  EXPECT_NO_THROW(planner.validate());
}

TEST(Sequence, ThePlannerTakesTheToursFirstView) {
  const Clutter s;
  PlannerConfig config;
  config.method = PlannerMethod::kGreedy;
  config.gain = s.gain(GainMethod::kGreedy);
  config.sequence.horizon = 3;
  const Plan plan = plan_next_view(s.grid, s.candidates, config);
  ASSERT_EQ(plan.sequence.size(), 3u);
  EXPECT_EQ(plan.best, plan.sequence.front());
  EXPECT_GT(plan.sequence_value, 0.0);
  EXPECT_GE(plan.tour_length, s.candidates[plan.best].travel);
}

}  // namespace
}  // namespace vantage
