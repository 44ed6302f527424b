#include "vantage/planner/observability.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <stdexcept>
#include <vector>

namespace vantage {
namespace {

/// A stand-in for a view's expected cells seen: monotone in a, as the model's E is (a larger a
/// keeps rays visible longer), over 200 unobserved cells 150 cells from the sensor.
double expected(double a) { return 200.0 * std::pow(a, 150.0); }

std::vector<double> predictions(const ObservabilityFit& fit, double scale = 1.0) {
  std::vector<double> e;
  for (const double a : fit.alphas()) e.push_back(scale * expected(a));
  return e;
}

/// Distance between two values of a on the fit's scale, ln(1 - a).
double apart(double a, double b) { return std::abs(std::log1p(-a) - std::log1p(-b)); }

TEST(ObservabilityFit, PriorUntilTheFirstOutcome) {
  ObservabilityFitConfig config;
  config.prior = 0.998;
  const ObservabilityFit fit(config);
  EXPECT_EQ(fit.outcomes(), 0u);
  EXPECT_DOUBLE_EQ(fit.alpha(), 0.998);
}

TEST(ObservabilityFit, FindsTheAThatPredictedTheOutcome) {
  // On the evaluated values and between them (the fit interpolates ln E against ln(1 - a)):
  // the a it finds predicts what the true a did, to 2.5% (the interpolation between evaluated
  // values of a costs up to 2% where E changes fast). Where E barely changes with a the a
  // itself is poorly determined, and does not need to be.
  for (const double truth : {0.99, 0.995, 0.996, 0.999, 0.9993, 0.9999, 0.99997}) {
    ObservabilityFit fit;
    fit.record(predictions(fit), expected(truth));
    EXPECT_NEAR(expected(fit.alpha()) / expected(truth), 1.0, 0.025)
        << "truth " << truth << ", fit " << fit.alpha();
    if (truth <= 0.9999) {
      EXPECT_LT(apart(fit.alpha(), truth), 0.1) << "truth " << truth;
    }
  }
}

TEST(ObservabilityFit, RecentOutcomesOutweighOldOnes) {
  // Three scans that a = 0.9999 predicted, then two that a = 0.997 did: the scene got harder to
  // see into. With recency 0.5 the fit follows the change; weighing all scans alike it does not.
  for (const double recency : {0.5, 1.0}) {
    ObservabilityFitConfig config;
    config.recency = recency;
    ObservabilityFit fit(config);
    for (int i = 0; i < 3; ++i) fit.record(predictions(fit), expected(0.9999));
    for (int i = 0; i < 2; ++i) fit.record(predictions(fit), expected(0.997));
    const double want = recency < 1.0 ? 0.997 : 0.9999;
    EXPECT_LT(apart(fit.alpha(), want), 0.05) << "recency " << recency << ", fit " << fit.alpha();
  }
}

TEST(ObservabilityFit, ErrorIsARatioSoLargeAndSmallScansCountAlike) {
  // The same relative miss on a 1000x larger scan adds the same error (to the +1 that keeps an
  // empty view finite).
  ObservabilityFit small, large;
  small.record(predictions(small, 100.0), 2.0 * 100.0 * expected(0.999) + 1.0);
  large.record(predictions(large, 1e5), 2.0 * 1e5 * expected(0.999) + 1.0);
  for (const double a : small.alphas()) {
    EXPECT_NEAR(small.error(a), large.error(a), 1e-2) << "a = " << a;
  }
  EXPECT_LT(apart(small.alpha(), large.alpha()), 0.05);
}

TEST(ObservabilityFit, TiesGoToTheLowerA) {
  ObservabilityFitConfig config;
  config.alphas = {0.99, 0.999};
  ObservabilityFit fit(config);
  fit.record(std::vector<double>{50.0, 50.0}, 50.0);
  EXPECT_DOUBLE_EQ(fit.alpha(), 0.99);
}

TEST(ObservabilityFit, RejectsBadSettingsAndOutcomes) {
  ObservabilityFitConfig unsorted;
  unsorted.alphas = {0.999, 0.99};
  EXPECT_THROW(ObservabilityFit{unsorted}, std::invalid_argument);
  ObservabilityFitConfig zero;
  zero.alphas = {0.0, 0.5};
  EXPECT_THROW(ObservabilityFit{zero}, std::invalid_argument);
  ObservabilityFitConfig one;  // ln(1 - a) has no value at a = 1
  one.alphas = {0.999, 1.0};
  EXPECT_THROW(ObservabilityFit{one}, std::invalid_argument);
  ObservabilityFitConfig single;  // nothing to fit between
  single.alphas = {0.999};
  EXPECT_THROW(ObservabilityFit{single}, std::invalid_argument);
  ObservabilityFitConfig recency;
  recency.recency = 0.0;
  EXPECT_THROW(ObservabilityFit{recency}, std::invalid_argument);

  ObservabilityFit fit;
  EXPECT_THROW(fit.record(std::vector<double>{1.0}, 1.0), std::invalid_argument);
  std::vector<double> e = predictions(fit);
  EXPECT_THROW(fit.record(e, -1.0), std::invalid_argument);
  EXPECT_THROW(fit.record(e, std::numeric_limits<double>::quiet_NaN()), std::invalid_argument);
  e[3] = std::numeric_limits<double>::infinity();
  EXPECT_THROW(fit.record(e, 10.0), std::invalid_argument);
  EXPECT_EQ(fit.outcomes(), 0u);  // nothing recorded by a rejected outcome
}

TEST(AlphaSetting, ParsesNumbersAndAuto) {
  EXPECT_EQ(parse_alpha_setting("0.9999"), (AlphaSetting{false, 0.9999}));
  EXPECT_EQ(parse_alpha_setting("auto", 0.9999), (AlphaSetting{true, 0.9999}));
  EXPECT_EQ(parse_alpha_setting("0.997").label(), "0.997");
  EXPECT_EQ(parse_alpha_setting("auto").label(), "auto");
  for (const char* bad : {"0", "1.5", "-0.1", "nan", "0.9x", "", "Auto"}) {
    EXPECT_THROW(parse_alpha_setting(bad), std::invalid_argument) << bad;
  }
}

}  // namespace
}  // namespace vantage
