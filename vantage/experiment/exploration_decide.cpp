// The explorer's decisions (detail/explorer.hpp): the planner's view with its prediction and
// greedy's reference for it, or the greedy oracle's view from the true hit sets.

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "vantage/experiment/decision_cost.hpp"
#include "vantage/experiment/detail/explorer.hpp"
#include "vantage/experiment/exploration.hpp"
#include "vantage/gain/view_gain.hpp"
#include "vantage/util/text.hpp"

namespace vantage::detail {

std::optional<double> Explorer::greedy_of(const Plan& plan, const Candidate& chosen,
                                          std::size_t best, Decision& d) const {
  if (!plan.greedy_gains.empty()) return plan.greedy_gains[best];
  if (!config_.planner.greedy_reference) return std::nullopt;
  const auto start = Clock::now();
  std::vector<Frustum> views{chosen.view};
  views.insert(views.end(), chosen.more_views.begin(), chosen.more_views.end());
  GainConfig greedy = planner_.gain;
  greedy.method = GainMethod::kGreedy;
  double sum = 0.0;
  for (const ViewGain& g : evaluate_views(mapper_.grid(), views, greedy)) sum += g.gain;
  d.reference_seconds += seconds_since(start);
  return sum;
}

void Explorer::record_prediction(const Plan& plan, const Candidate& chosen, std::size_t best,
                                 Decision& d) const {
  d.predicted = plan.gains[best].gain;
  d.predicted_cells = plan.gains[best].cells;
  d.greedy_predicted = greedy_of(plan, chosen, best, d);
  d.search = plan.sequence.empty() ? std::string(to_string(plan.search)) : "sequence";
  if (has_observability(planner_.method)) d.alpha = planner_.gain.alpha;
  if (surface_fit_) d.surface_rates = planner_.gain.surface_rates;
}

CandidateRecord Explorer::considered(const Plan& plan, std::size_t j, int view,
                                     const Eigen::Isometry3d& pose, const Decision& d) const {
  CandidateRecord r{view, pose, plan.gains[j].gain, std::nullopt, plan.gains[j].cells};
  if (!plan.greedy_gains.empty()) {
    r.greedy_predicted_gain = plan.greedy_gains[j];
  } else if (j == plan.best) {
    r.greedy_predicted_gain = d.greedy_predicted;
  }
  r.estimated = plan.is_estimate(j);
  return r;
}

Decision Explorer::plan_view(const ScanRecord& current, std::uint64_t seed) {
  const Eigen::Vector3d here = current.T_world_sensor.translation();
  std::vector<Candidate> open;  // the ring's views still to take, and their ring indices
  std::vector<std::size_t> index;
  for (std::size_t i = 0; i < ring_.size(); ++i) {
    if (!config_.revisit && taken_[i]) continue;
    open.push_back(ring_[i]);
    open.back().travel = planner_.sequence.travel(here, ring_[i].view.origin());
    index.push_back(i);
  }
  Decision d;
  d.candidates = static_cast<int>(open.size());
  if (open.empty()) {
    d.stop = true;
    d.stop_reason = cat("every candidate view has been taken after scan ", current.scan);
    return d;
  }
  if (config_.greedy_oracle) return oracle_view(current, open, index, std::move(d));
  check_decision_on(mapper_.grid(), open, planner_, config_.budget);
  const Plan plan = plan_next_view(mapper_.grid(), open, planner_, seed);
  double best_gain = 0.0;  // of any candidate, whichever the method chose
  for (const ViewGain& g : plan.gains) best_gain = std::max(best_gain, g.gain);
  if (best_gain < config_.min_gain) {
    d.stop = true;
    d.stop_reason = cat("best predicted gain ", best_gain, " fell below ", config_.min_gain,
                        " after scan ", current.scan);
  }
  const std::size_t view = index[plan.best];
  d.view = static_cast<int>(view);
  d.pose = result_.candidates[view];
  record_prediction(plan, open[plan.best], plan.best, d);
  d.seconds = plan.seconds + d.reference_seconds;  // the whole plan step, reference included
  d.travel = open[plan.best].travel;
  for (std::size_t j = 0; j < open.size(); ++j) {
    d.considered.push_back(
        considered(plan, j, static_cast<int>(index[j]), result_.candidates[index[j]], d));
  }
  return d;
}

Decision Explorer::oracle_view(const ScanRecord& current, const std::vector<Candidate>& open,
                               const std::vector<std::size_t>& index, Decision d) const {
  const auto start = Clock::now();
  std::vector<double> gains(open.size());
  std::size_t best = 0;
  for (std::size_t j = 0; j < open.size(); ++j) {
    const std::vector<std::uint32_t>& hits = surface_->candidate_hits[index[j]];
    gains[j] = static_cast<double>(hits.size() - count_common(hits, truly_hit_));
    // NOTE: ties go to the shorter travel, then to the lower index (open is in index order).
    if (gains[j] > gains[best] || (gains[j] == gains[best] && open[j].travel < open[best].travel))
      best = j;
  }
  if (gains[best] < config_.min_gain) {
    d.stop = true;
    d.stop_reason = cat("best true gain ", gains[best], " fell below ", config_.min_gain,
                        " after scan ", current.scan);
  }
  const std::size_t view = index[best];
  d.view = static_cast<int>(view);
  d.pose = result_.candidates[view];
  d.predicted = gains[best];
  d.predicted_cells = gains[best];
  d.travel = open[best].travel;
  for (std::size_t j = 0; j < open.size(); ++j) {
    d.considered.push_back({static_cast<int>(index[j]), result_.candidates[index[j]], gains[j],
                            std::nullopt, gains[j]});
  }
  d.seconds = seconds_since(start);
  return d;
}

}  // namespace vantage::detail
