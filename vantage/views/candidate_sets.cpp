// The registry of candidate sets (candidate_sets.hpp): one row a set.

#include "vantage/views/candidate_sets.hpp"

#include <array>
#include <stdexcept>

#include "vantage/util/text.hpp"

namespace vantage {
namespace {

constexpr std::array kRows{
    CandidateSetRow{"ring",
                    "the table top's ring of views (section 5.1), travel the walk around the table",
                    ring_candidates},
    CandidateSetRow{"hemisphere",
                    "an arm's views over the table at several radii and elevations, travel the "
                    "sensor's straight-line path",
                    hemisphere_candidates},
    CandidateSetRow{"sphere",
                    "views spread evenly over a band of a sphere above the region, travel the "
                    "straight-line path",
                    sphere_candidates},
    CandidateSetRow{"view-sphere",
                    "an object's whole view sphere, 32 views evenly spread by default (SCVP, "
                    "MA-SCVP), travel the arc on the sphere",
                    view_sphere_candidates},
    CandidateSetRow{"frontier",
                    "four level views at the centroid of every frontier region of the map "
                    "(Yamauchi), travel the straight-line path",
                    frontier_candidates, /*needs_map=*/true},
    CandidateSetRow{"stops",
                    "an office robot's next stops: the centroids of the map's frontier regions it "
                    "has not visited, travel its drive on the map (section 5.2)",
                    stop_candidates, /*needs_map=*/true, /*needs_list=*/false,
                    /*needs_robot=*/true},
    CandidateSetRow{"file", "the user's own poses, travel the straight-line path",
                    listed_candidates, /*needs_map=*/false, /*needs_list=*/true},
};

}  // namespace

std::span<const CandidateSetRow> candidate_sets() { return kRows; }

bool is_candidate_set(std::string_view name) {
  for (const CandidateSetRow& row : kRows) {
    if (row.name == name) return true;
  }
  return false;
}

std::string candidate_set_names() {
  std::string names;
  for (const CandidateSetRow& row : kRows) {
    if (!names.empty()) names += ", ";
    names += row.name;
  }
  return names;
}

const CandidateSetRow& find_candidate_set(std::string_view name) {
  for (const CandidateSetRow& row : kRows) {
    if (row.name == name) return row;
  }
  throw std::invalid_argument(
      cat("unknown candidate set '", name, "' (expected one of: ", candidate_set_names(), ")"));
}

PlacedViews build_candidates(std::string_view name, const CandidateSite& site,
                             const CandidateParams& params) {
  return find_candidate_set(name).build(site, params);
}

}  // namespace vantage
