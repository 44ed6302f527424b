#include "vantage/planner/search.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>
#include <string>

#include "vantage/gain/evaluators/exact.hpp"
#include "vantage/gain/view_gain.hpp"
#include "vantage/util/clock.hpp"
#include "vantage/util/text.hpp"

namespace vantage {

// The searches, each defined in its own file under searches/.
extern const SearchTraits kSweptSearch;
extern const SearchTraits kPrunedSearch;
extern const SearchTraits kExhaustiveSearch;

namespace {

// NOTE: the registry. Fastest first: a decision that names no search takes the first row that
// serves it. The rows' order is also the order names are listed in messages.
const std::array<const SearchTraits*, 3> kSearches = {&kSweptSearch, &kPrunedSearch,
                                                      &kExhaustiveSearch};

}  // namespace

std::span<const SearchTraits> decision_searches() {
  static const std::vector<SearchTraits> rows = [] {
    std::vector<SearchTraits> out;
    for (const SearchTraits* s : kSearches) out.push_back(*s);
    return out;
  }();
  return rows;
}

const SearchTraits& search_traits(DecisionSearch search) {
  for (const SearchTraits& s : decision_searches()) {
    if (s.search == search) return s;
  }
  throw std::invalid_argument(cat("no decision search '", search.name, "' is registered"));
}

DecisionSearch parse_decision_search(std::string_view name) {
  std::string names;
  for (const SearchTraits& s : decision_searches()) {
    if (s.search.name == name) return s.search;
    names += cat(names.empty() ? "" : ", ", s.search.name);
  }
  throw std::invalid_argument(cat("unknown decision search '", name, "' (expected ", names, ")"));
}

Decider resolve_decider(const PlannerConfig& config) {
  if (sequence_of(config).active()) return {};
  std::string serving;
  for (const SearchTraits& s : decision_searches()) {
    if (!s.serves(config)) continue;
    if (!config.search || *config.search == s.search) return {s.search};
    serving += cat(serving.empty() ? "" : ", ", s.search.name);
  }
  const std::string what = has_observability(config.method)
                               ? cat(to_string(config.method), " by ", to_string(config.objective))
                               : std::string(to_string(config.method));
  if (!config.search) {
    throw std::invalid_argument(cat("no registered search serves ", what));
  }
  throw std::invalid_argument(cat("the ", to_string(*config.search), " search does not serve ",
                                  what, "; ", serving.empty() ? "none does" : cat("use ", serving),
                                  " or leave the search to the default"));
}

CandidateViews::CandidateViews(std::span<const Candidate> candidates) {
  for (const Candidate& c : candidates) {
    first.push_back(frusta.size());
    frusta.push_back(c.view);
    frusta.insert(frusta.end(), c.more_views.begin(), c.more_views.end());
  }
  first.push_back(frusta.size());
}

CandidateViews CandidateViews::subset(const std::vector<std::size_t>& among) const {
  CandidateViews out;
  for (const std::size_t c : among) {
    out.first.push_back(out.frusta.size());
    out.frusta.insert(out.frusta.end(), frusta.begin() + static_cast<std::ptrdiff_t>(first[c]),
                      frusta.begin() + static_cast<std::ptrdiff_t>(first[c + 1]));
  }
  out.first.push_back(out.frusta.size());
  return out;
}

std::size_t CandidateViews::candidate_of(std::size_t v) const {
  return static_cast<std::size_t>(std::upper_bound(first.begin(), first.end(), v) - first.begin()) -
         1;
}

std::vector<double> CandidateViews::sums(const std::vector<double>& per_view) const {
  std::vector<double> out(size(), 0.0);
  for (std::size_t c = 0; c < size(); ++c) {
    for (std::size_t v = first[c]; v < first[c + 1]; ++v) out[c] += per_view[v];
  }
  return out;
}

std::vector<ViewGain> CandidateViews::sums(const std::vector<ViewGain>& per_view) const {
  std::vector<ViewGain> out(size());
  for (std::size_t c = 0; c < size(); ++c) {
    for (std::size_t v = first[c]; v < first[c + 1]; ++v) out[c] += per_view[v];
  }
  return out;
}

double SearchInput::travel_factor(std::size_t c) const {
  return config.method.ranking == Ranking::kTravel ? std::exp(-config.lambda * candidates[c].travel)
                                                   : 1.0;
}

std::vector<double> SearchInput::travel_factors() const {
  std::vector<double> out;
  for (std::size_t c = 0; c < candidates.size(); ++c) out.push_back(travel_factor(c));
  return out;
}

double SearchInput::seconds() const { return seconds_since(start); }

ViewGain full_prediction(const OccupancyGrid& grid, const CandidateViews& views, std::size_t c,
                         const GainConfig& gain) {
  const std::span<const Frustum> chosen(views.frusta.data() + views.first[c],
                                        views.first[c + 1] - views.first[c]);
  ViewGain full;
  for (const ViewGain& g : exact_view_gains(grid, chosen, gain)) full += g;
  return full;
}

void add_greedy_reference(const SearchInput& input, Plan& plan) {
  const auto start = std::chrono::steady_clock::now();
  GainConfig greedy = input.config.gain;
  greedy.method = GainMethod::kGreedy;
  std::vector<double> counts;
  for (const ViewGain& g : evaluate_views(input.grid, input.views.frusta, greedy)) {
    counts.push_back(g.gain);
  }
  plan.greedy_gains = input.views.sums(counts);
  plan.reference_seconds = seconds_since(start);
}

void report_choice(const SearchInput& input, Plan& plan) {
  if (!input.config.predict_chosen) {
    plan.bits_predicted = !plan.bits_of_chosen_only;
  } else if (plan.bits_of_chosen_only || plan.is_estimate(plan.best)) {
    // NOTE: the search decided on estimates, bounds or cells; the bits of eq. (4) and the exact
    // cells are the chosen view's report, not the choice.
    const auto predict_start = std::chrono::steady_clock::now();
    plan.gains[plan.best] = full_prediction(input.grid, input.views, plan.best, input.gain);
    if (!plan.estimated.empty()) plan.estimated[plan.best] = false;
    plan.prediction_seconds = seconds_since(predict_start);
  }
  if (input.quantity() == GainQuantity::kCount) {
    // A counting method's gains are greedy's: the reference costs nothing.
    plan.greedy_gains.clear();
    for (const ViewGain& g : plan.gains) plan.greedy_gains.push_back(g.gain);
  } else if (input.config.greedy_reference) {
    add_greedy_reference(input, plan);
    plan.seconds += plan.reference_seconds;
  }
}

}  // namespace vantage
