// The user's own candidate poses (CandidateParams::listed), read by the caller from a pose file.

#include <stdexcept>

#include "vantage/views/candidate_set.hpp"

namespace vantage {

PlacedViews listed_candidates(const CandidateSite& /*site*/, const CandidateParams& params) {
  if (params.listed.empty()) throw std::invalid_argument("file: the pose list holds no pose");
  return {.poses = params.listed, .travel = TravelRule{}};
}

}  // namespace vantage
