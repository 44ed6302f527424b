// The page's data for `vantage view` (detail/results_reader.hpp): what an explore folder's
// run.json or a plan folder's plan.json holds, as the page draws it: the scans, each decision's
// candidates (the chosen and the best by score), the sensor, the ranking, and the notes.

#include <fmt/core.h>

#include <algorithm>
#include <functional>
#include <map>
#include <optional>
#include <queue>
#include <string>
#include <string_view>
#include <vector>

#include "vantage/experiment/detail/results_reader.hpp"
#include "vantage/gain/methods.hpp"
#include "vantage/planner/types.hpp"
#include "vantage/views/frustum.hpp"

namespace vantage::detail {
namespace {

/// The sensor's field of view: the file's "sensor" (degrees), else a run.json scene's (radians),
/// else the default one, with a note on the page that the file has none.
void add_sensor(const Field& doc, const std::optional<Field>& older, std::string_view file,
                json& data) {
  constexpr double kDeg = 3.14159265358979323846 / 180.0;
  if (doc.has("sensor")) {
    const Field s = doc["sensor"];
    data["sensor"] = {{"h_fov", s["horizontal_fov_deg"].number() * kDeg},
                      {"v_fov", s["vertical_fov_deg"].number() * kDeg},
                      {"min_range", s["min_range_m"].number()},
                      {"max_range", s["max_range_m"].number()}};
  } else if (older && older->has("sensor")) {
    const Field s = (*older)["sensor"];
    data["sensor"] = {{"h_fov", s["h_fov_rad"].number()},
                      {"v_fov", s["v_fov_rad"].number()},
                      {"min_range", s["min_range_m"].number()},
                      {"max_range", s["max_range_m"].number()}};
  } else {
    const SensorFov fov;
    data["sensor"] = {{"h_fov", fov.h_fov},
                      {"v_fov", fov.v_fov},
                      {"min_range", fov.min_range},
                      {"max_range", fov.max_range}};
    data["notes"].push_back(fmt::format(
        "{} does not record the sensor: views are drawn with the default one ({:.0f}°×{:.0f}°, "
        "{:g} to {:g} m)",
        file, fov.h_fov / kDeg, fov.v_fov / kDeg, fov.min_range, fov.max_range));
  }
}

/// What a method ranks its candidates by, as the page colours them: a candidate's field, its
/// unit, and what it is.
struct RankedBy {
  std::string key;
  std::string unit;
  std::string what;
};

/// The planner a results file names, if this build knows it (a file may come from another).
std::optional<PlannerMethod> planner_of(std::string_view method) {
  try {
    return parse_planner_method(method);
  } catch (const std::invalid_argument&) {
    return std::nullopt;
  }
}

/// The methods that predict with a visibility model: they rank by their objective.
bool has_objective(std::string_view method) {
  const std::optional<PlannerMethod> planner = planner_of(method);
  return planner && has_observability(*planner);
}

/// `units.<key>` of a results file, or "" when it has none.
std::string unit_in(const Field& doc, std::string_view key) {
  if (!doc.has("units") || !doc["units"].has(key)) return {};
  return doc["units"][key].text();
}

/// The ranking of a results file. A candidate's `score` when it carries one (plan.json does);
/// for the methods with a visibility model its unit is the objective's (plan.json before issue
/// 27 said "bits" for the survival reading's score, which is its expected cells seen). Without
/// a score (run.json) the methods with a visibility model ranked by predicted cells for the
/// cells objective and by predicted gain otherwise, the rest by predicted gain.
RankedBy ranking_of(const Field& doc, std::string_view method, std::string_view objective,
                    bool scored, std::string_view gain_unit) {
  if (has_objective(method)) {
    if (objective == "cells") {
      return {scored ? "score" : "predicted_cells", "cells", "expected cells seen"};
    }
    return {scored ? "score" : "predicted_gain", "bits", "expected information gain"};
  }
  if (!scored) return {"predicted_gain", std::string(gain_unit), "predicted gain"};
  RankedBy r{"score", unit_in(doc, "score"), "score"};
  if (r.unit.empty()) r.unit = gain_unit;
  const std::optional<PlannerMethod> planner = planner_of(method);
  if (planner && planner->ranking == Ranking::kTravel) {
    r.what = fmt::format("{} gain × exp(−λ travel)", method_traits(planner->gain).name);
  }
  if (planner && planner->ranking == Ranking::kNearest) r.what = "minus the travel";
  return r;
}

/// A candidate for the page: its pose (under `pose_key`), index, ranking score and predictions.
json candidate_of(const Field& c, std::string_view pose_key, std::string_view index_key,
                  std::string_view greedy_key, const RankedBy& ranking) {
  json candidate = pose_of(c[pose_key]);
  candidate["view"] = c[index_key].integer();
  candidate["score"] = c[ranking.key].number();
  candidate["gain"] = c["predicted_gain"].number();
  const auto optional = [&](std::string_view key) {
    if (!c.has(key)) return json(nullptr);
    const std::optional<double> v = c[key].optional_number();
    return v ? json(*v) : json(nullptr);
  };
  candidate["cells"] = optional("predicted_cells");
  // NOTE: run.json records greedy's gain for the chosen candidate only (and every candidate's
  // where the method scores by it); the page shows the chosen one's.
  candidate["greedy"] = optional(greedy_key);
  candidate["estimated"] = c.has("estimated") && c["estimated"].value().is_boolean() &&
                           c["estimated"].value().get<bool>();
  return candidate;
}

/// The candidates of each list the page draws: the chosen one and the best by score (ties: the
/// earlier) up to `cap` in all, in their order in the file; and how many there were.
class CandidatePicker {
 public:
  /// `chosen(list, candidate)`: whether the candidate is the list's chosen view.
  CandidatePicker(std::size_t cap, std::function<bool(std::size_t, const json&)> chosen)
      : cap_(cap), chosen_(std::move(chosen)) {}

  void add(std::size_t list, std::size_t index, double score, json candidate) {
    List& l = lists_[list];
    ++l.total;
    if (!l.chosen && chosen_(list, candidate)) {
      l.chosen = Kept{score, index, std::move(candidate)};
      return;
    }
    l.best.push({score, index, std::move(candidate)});
    if (l.best.size() > cap_) l.best.pop();
  }

  /// The list's decision for the page: its kept candidates in the file's order, the chosen one's
  /// place among them (null when the list does not hold it) and the count before the cut.
  json decision(std::size_t list, std::size_t after_scan) {
    List& l = lists_[list];
    json d = {{"after_scan", after_scan},
              {"chosen", nullptr},
              {"candidates", json::array()},
              {"total", l.total}};
    std::vector<Kept> kept;
    if (l.chosen) {
      kept.push_back(std::move(*l.chosen));
      // NOTE: the chosen one counts against the cap: the page holds at most `cap` candidates.
      if (l.best.size() == cap_) l.best.pop();
    }
    for (; !l.best.empty(); l.best.pop()) kept.push_back(l.best.top());
    std::sort(kept.begin(), kept.end(),
              [](const Kept& a, const Kept& b) { return a.index < b.index; });
    for (Kept& k : kept) {
      if (l.chosen && k.index == l.chosen->index) d["chosen"] = d["candidates"].size();
      d["candidates"].push_back(std::move(k.candidate));
    }
    return d;
  }

  std::size_t total(std::size_t list) const {
    const auto it = lists_.find(list);
    return it == lists_.end() ? 0 : it->second.total;
  }

 private:
  struct Kept {
    double score;
    std::size_t index;
    json candidate;
  };
  /// Orders a heap with the worst on top: the lower score, then the later candidate.
  struct Better {
    bool operator()(const Kept& a, const Kept& b) const {
      return a.score != b.score ? a.score > b.score : a.index < b.index;
    }
  };
  struct List {
    std::size_t total = 0;
    std::optional<Kept> chosen;
    std::priority_queue<Kept, std::vector<Kept>, Better> best;
  };
  std::size_t cap_;
  std::function<bool(std::size_t, const json&)> chosen_;
  std::map<std::size_t, List> lists_;
};

/// The page's notes on the candidates cut and on estimated gains.
void note_candidates(const json& decisions, std::size_t cap, json& data) {
  std::size_t cut = 0, most = 0, estimated = 0;
  for (const json& d : decisions) {
    cut += d["total"].get<std::size_t>() - d["candidates"].size();
    most = std::max(most, d["total"].get<std::size_t>());
    for (const json& c : d["candidates"]) estimated += c["estimated"].get<bool>() ? 1 : 0;
  }
  if (cut > 0) {
    data["notes"].push_back(fmt::format(
        "drawn: the chosen view and the best by score, {} a decision; {} candidates of up to {} "
        "a decision not drawn (vantage view --max-candidates)",
        cap, cut, most));
  }
  if (estimated > 0) {
    data["notes"].push_back(fmt::format(
        "{} candidates' gains are the deciding search's estimates (swept: rays cast outward) or "
        "upper bounds (pruned: the map's blocks), not full evaluations",
        estimated));
  }
}

/// A scan of run.json for the page: its pose, view, path, gains and coverage.
json scan_of(const Field& s) {
  json path = json::array();
  const Field p = s["path"];
  // NOTE: run.json before the sensor's path (2026-12) held an office's floor path, [x, y].
  for (std::size_t j = 0; j < p.size_of_array(); ++j) {
    path.push_back(p[j].numbers(p[j].size_of_array() == 2 ? 2 : 3));
  }
  json scan = pose_of(s["pose"]);
  scan["scan"] = s["scan"].integer();
  scan["view"] = s["view"].integer();
  scan["path"] = path;
  scan["actual_gain"] = s["actual_gain"].number();
  scan["unobserved"] = s["unobserved"].number();
  scan["coverage"] = s["coverage"].number();
  const auto optional = [&](std::string_view key) {
    const std::optional<double> v = s.has(key) ? s[key].optional_number() : std::nullopt;
    return v ? json(*v) : json(nullptr);
  };
  scan["predicted_gain"] = optional("predicted_gain");
  scan["predicted_cells"] = optional("predicted_cells");
  scan["greedy_predicted_gain"] = optional("greedy_predicted_gain");
  return scan;
}

}  // namespace

json explore_data(const fs::path& dir, const ViewerConfig& config) {
  const fs::path file = dir / "run.json";
  const std::string text = read_results_file(file, config);
  const json doc = parse_results(text, file, false, nullptr);
  const Field run(file, doc, "");
  const Field scene = run["scene"];
  const GridSpec spec = grid_spec(scene["grid"]);
  const std::string method = run["config"]["method"].text();
  json data = {
      {"source", "explore"},
      {"title", fmt::format("{} · {} · {}", scene["name"].text(), method, dir.filename().string())},
      {"office", scene.has("kind") && scene["kind"].text() == "office"},
      {"method", method},
      {"grid", grid_json(spec)},
      {"max_cells", config.max_cells},
      {"notes", json::array()},
      {"scans", json::array()},
      {"decisions", json::array()}};
  std::string gain_unit = has_objective(method) ? "bits" : "cells";
  if (run.has("gain_units")) gain_unit = run["gain_units"]["predicted_gain"].text();
  if (const std::string u = unit_in(run, "predicted_gain"); !u.empty()) gain_unit = u;
  std::string objective = run.has("objective") ? run["objective"].text() : std::string();
  if (objective.empty() && run["config"].has("objective")) {
    objective = run["config"]["objective"].text();
  }
  add_sensor(run, scene, "run.json", data);
  const Field scans = run["scans"];

  // The candidates, a second time through the text: with the ranking and the views taken
  // known, the best of each decision are kept.
  std::vector<int> taken;
  for (std::size_t i = 0; i < scans.size_of_array(); ++i) {
    taken.push_back(scans[i]["view"].integer());
  }
  std::optional<RankedBy> ranking;
  CandidatePicker picker(config.max_candidates, [&](std::size_t list, const json& c) {
    return list < taken.size() && c["view"] == taken[list];
  });
  parse_results(text, file, false, [&](std::size_t list, std::size_t j, json& c) {
    const Field candidate(file, c, fmt::format("scans[{}].considered[{}]", list, j));
    if (!ranking) ranking = ranking_of(run, method, objective, candidate.has("score"), gain_unit);
    json drawn = candidate_of(candidate, "pose", "view", "greedy_predicted_gain", *ranking);
    const double score = drawn["score"].get<double>();
    picker.add(list, j, score, std::move(drawn));
  });
  if (!ranking) ranking = ranking_of(run, method, objective, false, gain_unit);
  data["units"] = {
      {"score", ranking->unit}, {"gain", gain_unit}, {"cells", "cells"}, {"greedy", "cells"}};
  data["ranked_by"] = ranking->what;

  bool decisions_recorded = true;
  for (std::size_t i = 0; i < scans.size_of_array(); ++i) {
    const Field s = scans[i];
    const json scan = scan_of(s);
    data["scans"].push_back(scan);
    if (i == 0) continue;
    if (!s.has("considered")) {
      decisions_recorded = false;
      continue;
    }
    json decision = picker.decision(i, i);
    if (decision["chosen"].is_null() && picker.total(i) > 0) {
      throw s["considered"].error(fmt::format(
          "scans[{}].considered does not hold the view taken ({})", i, scan["view"].get<int>()));
    }
    data["decisions"].push_back(decision);
  }
  if (!decisions_recorded) {
    data["notes"].push_back(
        "run.json does not record the candidates' gains (made before vantage view): only the "
        "views taken are shown");
  }
  note_candidates(data["decisions"], config.max_candidates, data);
  data["notes"].push_back(
      "the map is the one after the last scan (map.bt); the slider steps through the views and "
      "decisions");
  data.update(map_layers(dir / "map.bt", spec, config));
  return data;
}

json plan_data(const fs::path& dir, const ViewerConfig& config) {
  const fs::path file = dir / "plan.json";
  const std::string text = read_results_file(file, config);
  const json doc = parse_results(text, file, true, nullptr);
  const Field plan(file, doc, "");
  const GridSpec spec = grid_spec(plan["map"]["grid"]);
  const std::string method = plan["method"].text();
  std::string gain_unit = unit_in(plan, "predicted_gain");
  if (gain_unit.empty()) gain_unit = has_objective(method) ? "bits" : "cells";
  const std::string objective = plan.has("objective") ? plan["objective"].text() : "bits";
  // The clouds mapped: plan.json's own count, else its map's (0 for a plan on --map alone).
  json clouds = nullptr;
  if (plan.has("clouds")) {
    clouds = plan["clouds"].integer();
  } else if (plan["map"].has("clouds")) {
    clouds = plan["map"]["clouds"].integer();
  }
  json data = {{"source", "plan"},
               {"title", fmt::format("plan · {} · {}", method, dir.filename().string())},
               {"office", false},
               {"method", method},
               {"grid", grid_json(spec)},
               {"max_cells", config.max_cells},
               {"clouds", clouds},
               {"notes", json::array()},
               {"scans", json::array()}};
  add_sensor(plan, std::nullopt, "plan.json", data);
  const int best = plan["next_best_view"]["index"].integer();
  CandidatePicker picker(config.max_candidates,
                         [&](std::size_t, const json& c) { return c["view"] == best; });
  // NOTE: plan.json of format 1 had no scores: its first candidate says which it is.
  std::optional<RankedBy> ranking;
  parse_results(text, file, true, [&](std::size_t, std::size_t j, json& c) {
    const Field candidate(file, c, fmt::format("candidates[{}]", j));
    if (!ranking) ranking = ranking_of(plan, method, objective, candidate.has("score"), gain_unit);
    json drawn = candidate_of(candidate, "sensor", "index", "greedy_gain", *ranking);
    const double score = drawn["score"].get<double>();
    picker.add(0, j, score, std::move(drawn));
  });
  if (!ranking) ranking = ranking_of(plan, method, objective, true, gain_unit);
  data["units"] = {
      {"score", ranking->unit}, {"gain", gain_unit}, {"cells", "cells"}, {"greedy", "cells"}};
  data["ranked_by"] = ranking->what;
  json decision = picker.decision(0, 0);
  if (decision["chosen"].is_null()) {
    throw plan["candidates"].error(
        fmt::format("candidates does not hold the next best view (index {})", best));
  }
  data["decisions"] = json::array({decision});
  note_candidates(data["decisions"], config.max_candidates, data);
  data.update(map_layers(dir / "map.bt", spec, config));
  return data;
}

}  // namespace vantage::detail
