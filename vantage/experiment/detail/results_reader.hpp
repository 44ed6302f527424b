#pragma once
/// @file
/// What `vantage view` reads (viewer.hpp): a results file (run.json, plan.json) checked field by
/// field with one-line errors that say where (Field), its candidates streamed, its grid, the
/// map's layers for the page, and the page's data from a results folder. Included by the viewer's
/// .cpp files only.

#include <fmt/core.h>

#include <cstddef>
#include <filesystem>
#include <functional>
#include <nlohmann/json.hpp>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>

#include "vantage/experiment/viewer.hpp"
#include "vantage/map/grid_spec.hpp"

namespace vantage::detail {

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

/// Called with each candidate of a results file (its list: 0 for plan.json, the scan's index
/// for run.json; its index in the list; the candidate), which is then dropped from the document.
using CandidateVisit = std::function<void(std::size_t, std::size_t, json&)>;

/// The bytes of a results file: a regular file (a FIFO would block, a device never end) of at
/// most kMaxViewerFileBytes, after the memory budget has room for them.
std::string read_results_file(const fs::path& file, const ViewerConfig& config);

/// Parses a results file's text with its candidates handed to `visit` one at a time instead of
/// kept: plan.json's `candidates`, run.json's `scans[i].considered`. run.json's own `candidates`
/// (the ring, which the page does not draw) are skipped. A million candidates cost the memory of
/// one, not a document of gigabytes. Without `visit` the candidates are skipped unbuilt (the
/// lists stay, empty): the document's skeleton, at a fraction of the time.
json parse_results(const std::string& text, const fs::path& file, bool plan,
                   const CandidateVisit& visit);

std::string read_text(const fs::path& file, std::string_view what);

GridSpec grid_spec(const Field& grid);

json grid_json(const GridSpec& spec);

json pose_of(const Field& pose);

/// The occupied cells, and the unobserved cells that touch observed space (the surface of what is
/// still unknown; cells deeper inside it would be hidden behind those anyway). Counted first and
/// drawn second, so that what the page holds is bounded by the cap whatever the grid's size.
json map_layers(const fs::path& map_file, const GridSpec& spec, const ViewerConfig& config);

/// The page's data for an explore folder (run.json and map.bt): the scans, each decision's
/// candidates, the map's layers and the notes (detail/viewer_data.cpp).
json explore_data(const fs::path& dir, const ViewerConfig& config);

/// The same for a plan folder (plan.json and map.bt): its one decision.
json plan_data(const fs::path& dir, const ViewerConfig& config);

}  // namespace vantage::detail
