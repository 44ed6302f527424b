// `vantage view`'s page (viewer.hpp): the data of a results folder (detail/viewer_data.cpp)
// and three.js inlined into the page's template.

#include "vantage/experiment/viewer.hpp"

#include <fmt/core.h>

#include <algorithm>
#include <cctype>
#include <cstdlib>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "vantage/experiment/detail/results_reader.hpp"
#include "vantage/experiment/viewer_assets.hpp"

namespace vantage {
namespace {

namespace fs = std::filesystem;
using detail::explore_data;
using detail::plan_data;
using detail::read_text;
using nlohmann::json;

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
