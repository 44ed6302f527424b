#pragma once
/// @file
/// The one switch over the target models (methods.hpp, MethodKind::kTargetModel): the predictor
/// of a method's ray (models/target_predictors.hpp), handed to a traversal strategy.

#include "vantage/gain/methods.hpp"
#include "vantage/gain/models/target_predictors.hpp"

namespace vantage::detail {

/// Calls `f` with the predictor of `config.method`'s ray, for rays of at most `longest` cells from
/// a map with minimum probability `p_min`; returns what `f` returns. The one switch over the
/// target models.
template <typename Model = PaperModel, typename F>
decltype(auto) with_predictor(const GainConfig& config, double p_min, int longest, F&& f) {
  const TargetRay ray = method_traits(config.method).ray;
  if (ray == TargetRay::kUnblocked) return f(UnblockedPredictor{});
  if (ray == TargetRay::kSurvival) {
    return f(SurvivalPredictor{SurvivalModel(config.alpha, p_min, longest), config.epsilon});
  }
  return f(PaperPredictor<Model>{RayTables<Model>(config.alpha, p_min, longest), config.epsilon});
}

}  // namespace vantage::detail
