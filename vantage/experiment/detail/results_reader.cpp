#include "vantage/experiment/detail/results_reader.hpp"

#include <fstream>
#include <sstream>
#include <vector>

#include "vantage/io/format_parsing.hpp"
#include "vantage/io/input_file.hpp"
#include "vantage/util/memory.hpp"

namespace vantage::detail {

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

json pose_of(const Field& pose) {
  return {{"position", pose["position"].numbers(3)},
          {"quaternion", pose["quaternion_xyzw"].numbers(4)}};
}

}  // namespace vantage::detail
