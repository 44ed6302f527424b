#include "vantage/experiment/viewer.hpp"

#include <fmt/core.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <nlohmann/json.hpp>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <string_view>
#include <vector>

#include "vantage/experiment/viewer_assets.hpp"
#include "vantage/io/octomap_io.hpp"

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

json read_json(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  if (!in) throw std::runtime_error(fmt::format("{}: cannot be read", file.string()));
  std::ostringstream text;
  text << in.rdbuf();
  try {
    return json::parse(text.str());
  } catch (const json::parse_error& e) {
    throw std::runtime_error(fmt::format("{}: not valid JSON ({})", file.string(), e.what()));
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

/// Cell indices as one flat array (x0, y0, z0, x1, ...), thinned evenly to at most `cap`.
json cell_layer(const std::vector<std::size_t>& cells, const GridSpec& spec, std::size_t cap) {
  json flat = json::array();
  const std::size_t n = cells.size();
  for (std::size_t k = 0; k < n; ++k) {
    // NOTE: keeps the k-th cell where floor(k * cap / n) steps up, so a cut layer stays spread
    // over the whole map instead of ending at some height.
    if (n > cap && (k + 1) * cap / n == k * cap / n) continue;
    const Index3 c = spec.unravel(cells[k]);
    flat.push_back(c.x());
    flat.push_back(c.y());
    flat.push_back(c.z());
  }
  return {{"total", n}, {"cells", flat}};
}

/// The occupied cells, and the unobserved cells that touch observed space (the surface of what is
/// still unknown; cells deeper inside it would be hidden behind those anyway).
json map_layers(const fs::path& map_file, const GridSpec& spec, std::size_t cap) {
  if (!fs::exists(map_file))
    throw std::runtime_error(fmt::format("{}: missing", map_file.string()));
  OctomapImportConfig import;
  import.grid = spec;
  const OccupancyGrid grid = read_octomap(map_file, import).grid;
  std::vector<std::size_t> occupied, surface;
  std::size_t unobserved = 0;
  const std::array<Index3, 6> steps = {Index3(1, 0, 0),  Index3(-1, 0, 0), Index3(0, 1, 0),
                                       Index3(0, -1, 0), Index3(0, 0, 1),  Index3(0, 0, -1)};
  for (std::size_t i = 0; i < grid.size(); ++i) {
    const CellState state = grid.state(i);
    if (state == CellState::kOccupied) occupied.push_back(i);
    if (state != CellState::kUnobserved) continue;
    ++unobserved;
    const Index3 c = spec.unravel(i);
    for (const Index3& step : steps) {
      const Index3 n = c + step;
      if (spec.contains(n) && grid.state(spec.linear(n)) != CellState::kUnobserved) {
        surface.push_back(i);
        break;
      }
    }
  }
  json layers = {{"occupied", cell_layer(occupied, spec, cap)},
                 {"unobserved", cell_layer(surface, spec, cap)}};
  layers["unobserved"]["all"] = unobserved;
  return layers;
}

json pose_of(const Field& pose) {
  return {{"position", pose["position"].numbers(3)},
          {"quaternion", pose["quaternion_xyzw"].numbers(4)}};
}

/// The sensor's field of view from `holder`'s "sensor", or a note on the page that `file` has
/// none and the frusta show the default one (the page draws SensorFov's defaults then).
void add_sensor(const Field& holder, std::string_view file, json& data) {
  if (!holder.has("sensor")) {
    data["notes"].push_back(fmt::format(
        "{} does not record the sensor's field of view: views are drawn as 57°×43° frusta", file));
    return;
  }
  const Field s = holder["sensor"];
  data["sensor"] = {{"h_fov", s["h_fov_rad"].number()},
                    {"v_fov", s["v_fov_rad"].number()},
                    {"min_range", s["min_range_m"].number()},
                    {"max_range", s["max_range_m"].number()}};
}

/// One candidate for the page: its pose (under `pose_key`), its index and both gains.
json candidate_of(const Field& c, std::string_view pose_key, std::string_view index_key,
                  std::string_view greedy_key) {
  json candidate = pose_of(c[pose_key]);
  candidate["view"] = c[index_key].integer();
  candidate["gain"] = c["predicted_gain"].number();
  // NOTE: run.json records greedy's gain for the chosen candidate only (and every candidate's
  // where the method scores by it); the page shows the chosen one's.
  const std::optional<double> greedy = c[greedy_key].optional_number();
  candidate["greedy"] = greedy ? json(*greedy) : json(nullptr);
  return candidate;
}

/// What a method's predicted gain is counted in (docs/model.md, "Bits are not cells").
std::string gain_unit_of(std::string_view method) {
  return method == "probabilistic" ? "bits" : "cells";
}

json explore_data(const fs::path& dir, std::size_t cap) {
  const fs::path file = dir / "run.json";
  const json doc = read_json(file);
  const Field run(file, doc, "");
  const Field scene = run["scene"];
  const GridSpec spec = grid_spec(scene["grid"]);
  const std::string method = run["config"]["method"].text();
  json data = {
      {"source", "explore"},
      {"title", fmt::format("{} · {} · {}", scene["name"].text(), method, dir.filename().string())},
      {"office", scene.has("kind") && scene["kind"].text() == "office"},
      {"grid", grid_json(spec)},
      {"max_cells", cap},
      {"notes", json::array()},
      {"scans", json::array()},
      {"decisions", json::array()}};
  data["units"] = {{"gain", gain_unit_of(method)}, {"greedy", "cells"}};
  if (run.has("gain_units")) {
    data["units"] = {{"gain", run["gain_units"]["predicted_gain"].text()},
                     {"greedy", run["gain_units"]["greedy_predicted_gain"].text()}};
  }
  add_sensor(scene, "run.json (made before vantage view)", data);
  const Field scans = run["scans"];
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
    const std::optional<double> predicted = s["predicted_gain"].optional_number();
    scan["predicted_gain"] = predicted ? json(*predicted) : json(nullptr);
    data["scans"].push_back(scan);
    if (i == 0) continue;
    if (!s.has("considered")) {
      decisions_recorded = false;
      continue;
    }
    const Field considered = s["considered"];
    json decision = {{"after_scan", i}, {"chosen", nullptr}, {"candidates", json::array()}};
    for (std::size_t j = 0; j < considered.size_of_array(); ++j) {
      const json candidate = candidate_of(considered[j], "pose", "view", "greedy_predicted_gain");
      if (candidate["view"] == scan["view"]) decision["chosen"] = j;
      decision["candidates"].push_back(candidate);
    }
    if (decision["chosen"].is_null() && !decision["candidates"].empty()) {
      throw considered.error(fmt::format("scans[{}].considered does not hold the view taken ({})",
                                         i, scan["view"].get<int>()));
    }
    data["decisions"].push_back(decision);
  }
  if (!decisions_recorded) {
    data["notes"].push_back(
        "run.json does not record the candidates' gains (made before vantage view): only the "
        "views taken are shown");
  }
  data["notes"].push_back(
      "the map is the one after the last scan (map.bt); the slider steps through the views and "
      "decisions");
  data.update(map_layers(dir / "map.bt", spec, cap));
  return data;
}

json plan_data(const fs::path& dir, std::size_t cap) {
  const fs::path file = dir / "plan.json";
  const json doc = read_json(file);
  const Field plan(file, doc, "");
  const GridSpec spec = grid_spec(plan["map"]["grid"]);
  const std::string method = plan["method"].text();
  json data = {{"source", "plan"},
               {"title", fmt::format("plan · {} · {}", method, dir.filename().string())},
               {"office", false},
               {"grid", grid_json(spec)},
               {"max_cells", cap},
               {"units", {{"gain", gain_unit_of(method)}, {"greedy", "cells"}}},
               {"notes", json::array()},
               {"scans", json::array()}};
  add_sensor(plan, "plan.json", data);
  const int best = plan["next_best_view"]["index"].integer();
  const Field candidates = plan["candidates"];
  json decision = {{"after_scan", 0}, {"chosen", nullptr}, {"candidates", json::array()}};
  for (std::size_t j = 0; j < candidates.size_of_array(); ++j) {
    const json candidate = candidate_of(candidates[j], "sensor", "index", "greedy_gain");
    if (candidate["view"] == best) decision["chosen"] = j;
    decision["candidates"].push_back(candidate);
  }
  if (decision["chosen"].is_null()) {
    throw candidates.error(
        fmt::format("candidates does not hold the next best view (index {})", best));
  }
  data["decisions"] = json::array({decision});
  data.update(map_layers(dir / "map.bt", spec, cap));
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
    data = explore_data(results_dir, config.max_cells);
  } else if (fs::exists(results_dir / "plan.json")) {
    data = plan_data(results_dir, config.max_cells);
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
