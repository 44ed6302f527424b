#include "vantage/experiment/viewer.hpp"

#include <fmt/core.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <functional>
#include <limits>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <queue>
#include <sstream>
#include <stdexcept>
#include <string_view>
#include <vector>

#include "vantage/experiment/viewer_assets.hpp"
#include "vantage/io/format_parsing.hpp"
#include "vantage/io/input_file.hpp"
#include "vantage/io/octomap_io.hpp"
#include "vantage/util/memory.hpp"
#include "vantage/views/frustum.hpp"

namespace vantage {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

/// A value inside a JSON file and where it sits (`scans[1].pose`), for one-line errors.
class Field {
 public:
  Field(const fs::path& file, const json& value, std::string where)
      : file_(&file), value_(&value), where_(std::move(where)) {}

  const json& value() const { return *value_; }
  bool has(std::string_view key) const {
    return value_->is_object() && value_->contains(key) && !(*value_)[std::string(key)].is_null();
  }
  Field operator[](std::string_view key) const {
    if (!value_->is_object()) fail("is not an object");
    const auto it = value_->find(key);
    const std::string where = where_.empty() ? std::string(key) : fmt::format("{}.{}", where_, key);
    if (it == value_->end()) throw error(fmt::format("{} is missing", where));
    return Field(*file_, *it, where);
  }
  Field operator[](std::size_t i) const {
    return Field(*file_, (*value_)[i], fmt::format("{}[{}]", where_, i));
  }
  std::size_t size_of_array() const {
    if (!value_->is_array()) fail("is not an array");
    return value_->size();
  }
  double number() const {
    if (!value_->is_number() || !std::isfinite(value_->get<double>())) fail("is not a number");
    return value_->get<double>();
  }
  std::optional<double> optional_number() const {
    if (value_->is_null()) return std::nullopt;
    return number();
  }
  int integer() const {
    if (!value_->is_number_integer()) fail("is not an integer");
    // NOTE: get<int> of 4294967328 wraps to 32; a value outside int's range is an error.
    const bool fits = value_->is_number_unsigned()
                          ? value_->get<std::uint64_t>() <= std::numeric_limits<int>::max()
                          : value_->get<std::int64_t>() >= std::numeric_limits<int>::min() &&
                                value_->get<std::int64_t>() <= std::numeric_limits<int>::max();
    if (!fits) fail("is out of range");
    return value_->get<int>();
  }
  std::string text() const {
    if (!value_->is_string()) fail("is not a string");
    return value_->get<std::string>();
  }
  /// A fixed-length array of numbers, as a JSON array.
  json numbers(std::size_t n) const {
    if (!value_->is_array() || value_->size() != n) fail(fmt::format("is not {} numbers", n));
    json out = json::array();
    for (std::size_t i = 0; i < n; ++i) out.push_back((*this)[i].number());
    return out;
  }
  std::runtime_error error(const std::string& what) const {
    return std::runtime_error(fmt::format("{}: {}", file_->string(), what));
  }

 private:
  [[noreturn]] void fail(std::string_view what) const {
    throw error(fmt::format("{} {}", where_.empty() ? "the document" : where_, what));
  }
  const fs::path* file_;
  const json* value_;
  std::string where_;
};

/// The bytes of a results file: a regular file (a FIFO would block, a device never end) of at
/// most kMaxViewerFileBytes, after the memory budget has room for them.
std::string read_results_file(const fs::path& file, const ViewerConfig& config) {
  try {
    const std::uintmax_t size = require_input_file(file, InputKind::kResults);
    // NOTE: the text, and the parse's transient copies of a candidate at a time.
    check_memory({0, 0.0, 2.0 * static_cast<double>(size) + kViewerFixedBytes}, config.max_memory,
                 fmt::format("vantage view of {}", file.string()));
    return read_input_file(file, InputKind::kResults);
  } catch (const FormatError& e) {
    throw std::runtime_error(fmt::format("{}: {}", file.string(), e.what()));
  }
}

/// Called with each candidate of a results file (its list: 0 for plan.json, the scan's index
/// for run.json; its index in the list; the candidate), which is then dropped from the document.
using CandidateVisit = std::function<void(std::size_t, std::size_t, json&)>;

/// Parses a results file's text with its candidates handed to `visit` one at a time instead of
/// kept: plan.json's `candidates`, run.json's `scans[i].considered`. run.json's own `candidates`
/// (the ring, which the page does not draw) are skipped. A million candidates cost the memory of
/// one, not a document of gigabytes. Without `visit` the candidates are skipped unbuilt (the
/// lists stay, empty): the document's skeleton, at a fraction of the time.
json parse_results(const std::string& text, const fs::path& file, bool plan,
                   const CandidateVisit& visit) {
  std::array<std::string, 5> keys;  // the key last read at each depth
  std::size_t list = 0, index = 0;
  const auto in_list = [&](int depth) {
    return plan ? depth == 2 && keys[1] == "candidates"
                : depth == 4 && keys[1] == "scans" && keys[3] == "considered";
  };
  const json::parser_callback_t callback = [&](int depth, json::parse_event_t event, json& parsed) {
    switch (event) {
      case json::parse_event_t::key:
        if (depth < static_cast<int>(keys.size())) keys[depth] = parsed.get<std::string>();
        return plan || depth != 1 || parsed != "candidates";
      case json::parse_event_t::array_start:
        if (in_list(depth + 1)) index = 0;
        return true;
      case json::parse_event_t::object_start:
        return visit || !in_list(depth);
      case json::parse_event_t::value:
        if (in_list(depth)) {
          throw std::runtime_error(fmt::format(
              "{}: {}[{}] is not an object", file.string(),
              plan ? std::string("candidates") : fmt::format("scans[{}].considered", list), index));
        }
        return true;
      case json::parse_event_t::object_end:
        if (in_list(depth)) {
          visit(list, index++, parsed);
          return false;
        }
        if (!plan && depth == 2 && keys[1] == "scans") ++list;
        return true;
      default:
        return true;
    }
  };
  try {
    return json::parse(text, callback);
  } catch (const json::parse_error& e) {
    throw std::runtime_error(fmt::format("{}: not valid JSON ({})", file.string(), e.what()));
  } catch (const json::exception& e) {
    throw std::runtime_error(fmt::format("{}: {}", file.string(), e.what()));
  }
}

std::string read_text(const fs::path& file, std::string_view what) {
  std::ifstream in(file, std::ios::binary);
  if (!in) {
    throw std::runtime_error(
        fmt::format("{} not found at {} (run scripts/fetch-web.sh, or set VANTAGE_WEB_DIR)", what,
                    file.string()));
  }
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

GridSpec grid_spec(const Field& grid) {
  GridSpec spec;
  const json origin = grid["origin"].numbers(3);
  spec.origin = {origin[0].get<double>(), origin[1].get<double>(), origin[2].get<double>()};
  spec.resolution = grid["resolution"].number();
  const Field dims = grid["dims"];
  if (dims.size_of_array() != 3) throw dims.error(fmt::format("{} is not 3 integers", "dims"));
  spec.dims = {dims[0].integer(), dims[1].integer(), dims[2].integer()};
  try {
    spec.validate();
  } catch (const std::invalid_argument& e) {
    throw grid.error(fmt::format("grid: {}", e.what()));
  }
  return spec;
}

json grid_json(const GridSpec& spec) {
  return {{"origin", {spec.origin.x(), spec.origin.y(), spec.origin.z()}},
          {"resolution", spec.resolution},
          {"dims", {spec.dims.x(), spec.dims.y(), spec.dims.z()}}};
}

/// Cell indices as one flat array (x0, y0, z0, x1, ...) of the cells `keep` picks, in the grid's
/// order, thinned evenly to at most `cap` of their `n`; a cell's index is the grid's plus `offset`
/// (where the grid's cell (0, 0, 0) lies in the results' grid).
template <typename Keep>
json cell_layer(const OccupancyGrid& grid, const Index3& offset, std::size_t n, std::size_t cap,
                Keep&& keep) {
  json flat = json::array();
  const GridSpec& spec = grid.spec();
  std::size_t k = 0;
  for (std::size_t i = 0; i < grid.size(); ++i) {
    if (!keep(i)) continue;
    // NOTE: keeps the k-th cell where floor(k * cap / n) steps up, so a cut layer stays spread
    // over the whole map instead of ending at some height.
    const bool drawn = n <= cap || (k + 1) * cap / n != k * cap / n;
    ++k;
    if (!drawn) continue;
    const Index3 c = spec.unravel(i) + offset;
    flat.push_back(c.x());
    flat.push_back(c.y());
    flat.push_back(c.z());
  }
  return {{"total", n}, {"cells", flat}};
}

/// The map read for the page: a grid and where its cell (0, 0, 0) lies in the results' grid.
struct MapBox {
  OccupancyGrid grid;
  Index3 offset = Index3::Zero();
};

/// The map in the known voxels' box grown by one cell, when its cells are the results grid's:
/// what the page draws lies there (an occupied cell is known; an unobserved cell drawn touches a
/// known one), so a small map in a large grid costs the map's cells, not the grid's (issue 39:
/// dims of 1024^3 around a 32 x 32 x 17 map took 4.45 GB). Nothing when the box cannot stand for
/// the grid (cells not on OctoMap's lattice, another resolution, a known voxel outside the grid, a
/// file that cannot be read this way): the caller reads the whole grid, which says what is wrong.
std::optional<MapBox> read_map_box(const fs::path& map_file, const GridSpec& spec,
                                   const std::function<void(const GridSpec&)>& budget) {
  if (!octomap_aligned(spec)) return std::nullopt;
  OctomapImportConfig own;
  own.padding = 1;
  own.check_grid = budget;
  std::optional<OctomapImport> imported;
  try {
    imported.emplace(read_octomap(map_file, own));
  } catch (const MemoryBudgetError&) {
    throw;
  } catch (const std::exception&) {
    return std::nullopt;
  }
  const GridSpec& box = imported->grid.spec();
  if (std::abs(box.resolution - spec.resolution) > 1e-5 * spec.resolution) return std::nullopt;
  const Eigen::Vector3d shift = (box.origin - spec.origin) / spec.resolution;
  const Eigen::Vector3d rounded = shift.array().round();
  if ((shift - rounded).cwiseAbs().maxCoeff() > 1e-6) return std::nullopt;
  MapBox map{std::move(imported->grid), rounded.cast<int>()};
  for (std::size_t i = 0; i < map.grid.size(); ++i) {
    if (map.grid.state(i) != CellState::kUnobserved &&
        !spec.contains(Index3(box.unravel(i) + map.offset))) {
      return std::nullopt;  // the whole grid's read names the voxel outside it
    }
  }
  return map;
}

/// The occupied cells, and the unobserved cells that touch observed space (the surface of what is
/// still unknown; cells deeper inside it would be hidden behind those anyway). Counted first and
/// drawn second, so that what the page holds is bounded by the cap whatever the grid's size.
json map_layers(const fs::path& map_file, const GridSpec& spec, const ViewerConfig& config) {
  const auto budget = [&](const GridSpec& g) {
    check_memory(
        {static_cast<std::uint64_t>(g.num_cells()), kViewerBytesPerCell, kViewerFixedBytes},
        config.max_memory,
        fmt::format("vantage view of {} ({} x {} x {} cells)", map_file.string(), g.dims.x(),
                    g.dims.y(), g.dims.z()));
  };
  std::optional<MapBox> map = read_map_box(map_file, spec, budget);
  if (!map) {
    budget(spec);
    OctomapImportConfig import;
    import.grid = spec;
    map = MapBox{read_octomap(map_file, import).grid, Index3::Zero()};
  }
  const OccupancyGrid& grid = map->grid;
  const GridSpec& box = grid.spec();
  const std::array<Index3, 6> steps = {Index3(1, 0, 0),  Index3(-1, 0, 0), Index3(0, 1, 0),
                                       Index3(0, -1, 0), Index3(0, 0, 1),  Index3(0, 0, -1)};
  // NOTE: cells of the box outside the results' grid (its padding) are neither drawn nor counted.
  const auto inside = [&](std::size_t i) {
    return spec.contains(Index3(box.unravel(i) + map->offset));
  };
  const auto occupied = [&](std::size_t i) {
    return grid.state(i) == CellState::kOccupied && inside(i);
  };
  const auto surface = [&](std::size_t i) {
    if (grid.state(i) != CellState::kUnobserved || !inside(i)) return false;
    const Index3 c = box.unravel(i);
    for (const Index3& step : steps) {
      const Index3 n = c + step;
      if (box.contains(n) && spec.contains(Index3(n + map->offset)) &&
          grid.state(box.linear(n)) != CellState::kUnobserved) {
        return true;
      }
    }
    return false;
  };
  std::size_t n_occupied = 0, n_surface = 0, known = 0;
  for (std::size_t i = 0; i < grid.size(); ++i) {
    n_occupied += occupied(i) ? 1 : 0;
    n_surface += surface(i) ? 1 : 0;
    known += grid.state(i) != CellState::kUnobserved && inside(i) ? 1 : 0;
  }
  json layers = {
      {"occupied", cell_layer(grid, map->offset, n_occupied, config.max_cells, occupied)},
      {"unobserved", cell_layer(grid, map->offset, n_surface, config.max_cells, surface)}};
  layers["unobserved"]["all"] = spec.num_cells() - known;
  return layers;
}

json pose_of(const Field& pose) {
  return {{"position", pose["position"].numbers(3)},
          {"quaternion", pose["quaternion_xyzw"].numbers(4)}};
}

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
struct Ranking {
  std::string key;
  std::string unit;
  std::string what;
};

/// The methods that predict with a visibility model: they rank by their objective.
bool has_objective(std::string_view method) {
  return method == "probabilistic" || method == "survival";
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
Ranking ranking_of(const Field& doc, std::string_view method, std::string_view objective,
                   bool scored, std::string_view gain_unit) {
  if (has_objective(method)) {
    if (objective == "cells") {
      return {scored ? "score" : "predicted_cells", "cells", "expected cells seen"};
    }
    return {scored ? "score" : "predicted_gain", "bits", "expected information gain"};
  }
  if (!scored) return {"predicted_gain", std::string(gain_unit), "predicted gain"};
  Ranking r{"score", unit_in(doc, "score"), "score"};
  if (r.unit.empty()) r.unit = gain_unit;
  if (method == "latombe") r.what = "greedy gain × exp(−λ travel)";
  if (method == "yamauchi") r.what = "minus the travel";
  return r;
}

/// A candidate for the page: its pose (under `pose_key`), index, ranking score and predictions.
json candidate_of(const Field& c, std::string_view pose_key, std::string_view index_key,
                  std::string_view greedy_key, const Ranking& ranking) {
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
  std::optional<Ranking> ranking;
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
    json path = json::array();
    const Field p = s["path"];
    for (std::size_t j = 0; j < p.size_of_array(); ++j) path.push_back(p[j].numbers(2));
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
  std::optional<Ranking> ranking;
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

/// Text that goes inside a <script> element as it is: it must not end the element early.
const std::string& script_safe(const std::string& text, const fs::path& from) {
  std::string lower(text.size(), ' ');
  std::transform(text.begin(), text.end(), lower.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  if (lower.find("</script") != std::string::npos || lower.find("<!--") != std::string::npos) {
    throw std::runtime_error(
        fmt::format("{}: holds '</script' or '<!--' and cannot be inlined", from.string()));
  }
  return text;
}

std::string html_escape(std::string_view text) {
  std::string out;
  for (const char c : text) {
    switch (c) {
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      case '&':
        out += "&amp;";
        break;
      default:
        out += c;
    }
  }
  return out;
}

/// Replaces each `@NAME@` marker of the template once, in order.
std::string fill(std::string_view page,
                 const std::vector<std::pair<std::string, std::string>>& parts) {
  std::string out;
  std::size_t at = 0;
  for (const auto& [marker, text] : parts) {
    const std::size_t found = page.find(marker, at);
    if (found == std::string_view::npos) {
      throw std::logic_error(fmt::format("viewer template has no {}", marker));
    }
    out.append(page.substr(at, found - at));
    out.append(text);
    at = found + marker.size();
  }
  out.append(page.substr(at));
  return out;
}

}  // namespace

void ViewerConfig::validate() const {
  if (max_cells == 0) throw std::invalid_argument("ViewerConfig.max_cells must be positive");
  if (max_candidates == 0) {
    throw std::invalid_argument("ViewerConfig.max_candidates must be positive");
  }
}

fs::path web_dir() {
  if (const char* env = std::getenv("VANTAGE_WEB_DIR"); env != nullptr && *env != '\0') return env;
  return VANTAGE_DEFAULT_WEB_DIR;
}

std::string build_view_page(const fs::path& results_dir, const ViewerConfig& config) {
  config.validate();
  std::error_code ec;
  if (!fs::is_directory(results_dir, ec)) {
    throw std::runtime_error(
        fmt::format("{}: {}", results_dir.string(),
                    fs::exists(results_dir, ec) ? "is not a folder" : "no such folder"));
  }
  json data;
  if (fs::exists(results_dir / "run.json")) {
    data = explore_data(results_dir, config);
  } else if (fs::exists(results_dir / "plan.json")) {
    data = plan_data(results_dir, config);
  } else {
    throw std::runtime_error(fmt::format(
        "{}: neither an explore folder (run.json, map.bt) nor a plan folder (plan.json, map.bt)",
        results_dir.string()));
  }
  data["three_version"] = kThreeVersion;

  const fs::path three_dir = (config.web_dir.empty() ? web_dir() : config.web_dir) / "three";
  const fs::path package = three_dir / "package.json";
  const json package_json = json::parse(read_text(package, "three.js"), nullptr, false);
  if (!package_json.is_object() || package_json.value("version", "") != kThreeVersion) {
    throw std::runtime_error(fmt::format("{}: not three.js {} (run scripts/fetch-web.sh)",
                                         package.string(), kThreeVersion));
  }
  const fs::path three_file = three_dir / "build" / "three.module.min.js";
  const fs::path orbit_file = three_dir / "examples" / "jsm" / "controls" / "OrbitControls.js";
  const std::string three = read_text(three_file, "three.js");
  const std::string orbit = read_text(orbit_file, "three.js's OrbitControls");

  // NOTE: '<' appears in the JSON only inside strings, where \u003c means the same and cannot
  // close the <script> element that holds it.
  std::string data_text;
  for (const char c : data.dump()) {
    if (c == '<') {
      data_text += "\\u003c";
    } else {
      data_text += c;
    }
  }
  return fill(viewer_page_template(), {{"@TITLE@", html_escape(data["title"].get<std::string>())},
                                       {"@THREE@", script_safe(three, three_file)},
                                       {"@ORBIT@", script_safe(orbit, orbit_file)},
                                       {"@DATA@", data_text},
                                       {"@APP@", std::string(viewer_app_script())}});
}

}  // namespace vantage
