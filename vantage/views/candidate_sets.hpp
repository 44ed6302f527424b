#pragma once
/// @file
/// The candidate sets, by name: the one registry that the CLI (explore, bench, plan), the
/// experiment layer, the viewer and Python read. A new set is a builder in its own file and one
/// row in candidate_sets.cpp (docs/architecture.md, "Adding a candidate set").

#include <span>
#include <string>
#include <string_view>

#include "vantage/views/candidate_set.hpp"

namespace vantage {

/// One candidate set: its name, a line of help, and its builder.
struct CandidateSetRow {
  std::string_view name;
  std::string_view help;
  /// Builds the views; throws std::invalid_argument naming the field for bad parameters and
  /// std::runtime_error when the world offers no view (a map with no frontier).
  PlacedViews (*build)(const CandidateSite& site, const CandidateParams& params);
  bool needs_map = false;    ///< found in the map (CandidateSite::grid), not placed around it
  bool needs_list = false;   ///< the user's poses (CandidateParams::listed)
  bool needs_robot = false;  ///< a ground robot that drives to them (CandidateSite::robot)
};

/// Every candidate set, in the order help lists them.
std::span<const CandidateSetRow> candidate_sets();

/// The row named `name`; throws std::invalid_argument naming it and the sets there are.
const CandidateSetRow& find_candidate_set(std::string_view name);

/// Whether a set of that name exists.
bool is_candidate_set(std::string_view name);

/// "ring, hemisphere, ...": the names, for messages and help.
std::string candidate_set_names();

/// Builds the set `name` (find_candidate_set(name).build).
PlacedViews build_candidates(std::string_view name, const CandidateSite& site,
                             const CandidateParams& params);

}  // namespace vantage
