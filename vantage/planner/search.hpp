#pragma once
/// @file
/// One interface for the searches (docs/architecture.md, "Add a search"): each search is one file
/// under searches/ that defines its SearchTraits, and one row of the registry (search.cpp) lists
/// it. plan_next_view (planner.hpp) asks resolve_decider which search decides and runs it; what the
/// searches share (the candidates' views, Latombe's factor, the chosen view's report) is here.

#include <chrono>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <string_view>
#include <vector>

#include "vantage/gain/types.hpp"
#include "vantage/map/occupancy_grid.hpp"
#include "vantage/planner/types.hpp"
#include "vantage/views/frustum.hpp"

namespace vantage {

/// Every candidate's views in one list; candidate c's are [first[c], first[c + 1]).
struct CandidateViews {
  std::vector<Frustum> frusta;
  std::vector<std::size_t> first;

  CandidateViews() = default;
  explicit CandidateViews(std::span<const Candidate> candidates);

  std::size_t size() const { return first.size() - 1; }
  /// The views of candidates `among`, in that order.
  CandidateViews subset(const std::vector<std::size_t>& among) const;
  /// The candidate whose views hold view `v`.
  std::size_t candidate_of(std::size_t v) const;
  /// Per-view values summed per candidate, in the order of its views.
  std::vector<double> sums(const std::vector<double>& per_view) const;
  /// Per-view gains summed per candidate.
  std::vector<ViewGain> sums(const std::vector<ViewGain>& per_view) const;
};

/// What a search is handed.
struct SearchInput {
  const OccupancyGrid& grid;
  std::span<const Candidate> candidates;
  const CandidateViews& views;
  const PlannerConfig& config;
  GainConfig gain;  ///< config.gain with the method's gain method (PlannerMethod::gain)
  std::chrono::steady_clock::time_point start;
  std::uint64_t seed = 0;  ///< PlannerMethod::kRandom's

  /// What Latombe multiplies candidate c's gain by, exp(-lambda * travel); 1 for the others.
  double travel_factor(std::size_t c) const;
  /// Every candidate's travel_factor.
  std::vector<double> travel_factors() const;
  /// Seconds since `start`.
  double seconds() const;
  /// Which quantity the decision computes and ranks by (decision_quantity, types.hpp).
  GainQuantity quantity() const { return decision_quantity(config); }
};

/// A search: its name, what it guarantees, which decisions it serves and how it runs.
struct SearchTraits {
  DecisionSearch search;       ///< its name, as --search spells it
  std::string_view guarantee;  ///< one line for --help and messages
  /// Whether it serves the decision `config` asks for (the method and what it ranks by).
  bool (*serves)(const PlannerConfig& config);
  /// Decides: Plan::best, gains, scores, estimated, evaluated, seconds; the chosen candidate's
  /// full prediction and greedy's reference as report_choice() gives them.
  Plan (*run)(const SearchInput& input);
};

/// The registered searches, fastest first (search.cpp).
std::span<const SearchTraits> decision_searches();
/// The traits of `search`; throws std::invalid_argument when no registered search has its name.
const SearchTraits& search_traits(DecisionSearch search);
/// What decides a decision: the sequence (sequence.hpp) when one is planned, else a search.
struct Decider {
  std::optional<DecisionSearch> search;  ///< the search that decides; none: the sequence
  /// As the reports name it: the search's name, or "sequence".
  std::string_view name() const { return search ? search->name : "sequence"; }
};

/// What decides `config`, worked out here alone: the sequence when it plans one (sequence_of),
/// else config.search, or the first registered search that serves it. Throws
/// std::invalid_argument when config.search does not serve it, naming those that do.
/// plan_next_view runs what it names; the settings builder, the reports and the decision's cost
/// ask it, never the registry.
Decider resolve_decider(const PlannerConfig& config);

/// Candidate `c`'s exact prediction: its views' gains under `gain.method`, summed.
ViewGain full_prediction(const OccupancyGrid& grid, const CandidateViews& views, std::size_t c,
                         const GainConfig& gain);

/// Greedy's count on every candidate's poses, the reference of the other methods' predictions
/// (Fig. 11), into Plan::greedy_gains, and its time into Plan::reference_seconds.
void add_greedy_reference(const SearchInput& input, Plan& plan);

/// What a search that decided on estimates or bounds reports after the decision (not part of
/// Plan::seconds): the chosen candidate's exact prediction (also what an online fit of a compares
/// with the scan's outcome), and greedy's reference (a counting method's own gains; else every
/// candidate's count when PlannerConfig::greedy_reference asks for it, counted in the decision's
/// seconds as the exhaustive search counts it).
void report_choice(const SearchInput& input, Plan& plan);

}  // namespace vantage
