// The paper's ray model: docs/model.md's worked example, pinned, and the properties the paper asks
// of it (§3.1.1, §3.2.2).

#include "vantage/gain/ray_model.hpp"

#include <gtest/gtest.h>

#include <random>
#include <vector>

namespace vantage {
namespace {

TEST(RayModel, WorkedExampleOfModel) {
  // a = 0.997, cells [0.12, 0.12, 0.5, 0.5, 0.97, 0.5]. Expected values computed once by an
  // independent implementation (a few lines of Python following docs/model.md).
  const RayModel model(0.997);
  const std::vector<double> cells = {0.12, 0.12, 0.5, 0.5, 0.97, 0.5};
  const auto states = model.trace(cells);
  const double visibility[] = {1.0,
                               0.9995898464202707,
                               0.9991282570004986,
                               0.9902502264739204,
                               0.9793955677542567,
                               0.47427131583438575};
  const double posterior[] = {0.12,
                              0.018282034169898334,
                              0.01870196843434485,
                              0.023394515240657922,
                              0.5262545341824687,
                              0.5124517724733383};
  const double gain[] = {0.0,
                         0.39767800907352396,
                         0.8659108962037153,
                         0.8399026256972619,
                         -0.8036183261778592,
                         0.00044741628433397906};
  ASSERT_EQ(states.size(), 6u);
  for (std::size_t m = 0; m < 6; ++m) {
    EXPECT_EQ(states[m].m, static_cast<int>(m));
    EXPECT_NEAR(states[m].visibility, visibility[m], 1e-9) << "v_" << m;
    EXPECT_NEAR(states[m].posterior, posterior[m], 1e-9) << "q_" << m;
    EXPECT_NEAR(states[m].gain(), gain[m], 1e-9) << "g_" << m;
  }
}

TEST(RayModel, EntropyInBits) {
  EXPECT_DOUBLE_EQ(entropy_bits(0.5), 1.0);
  EXPECT_DOUBLE_EQ(entropy_bits(0.0), 0.0);
  EXPECT_DOUBLE_EQ(entropy_bits(1.0), 0.0);
  EXPECT_NEAR(entropy_bits(0.12), 0.5293608652873644, 1e-12);
}

TEST(RayModel, RejectsBadInput) {
  EXPECT_THROW(RayModel(0.0), std::invalid_argument);
  EXPECT_THROW(RayModel(1.0001), std::invalid_argument);
  EXPECT_THROW(RayModel(std::nan("")), std::invalid_argument);
  const RayModel model(0.997);
  EXPECT_THROW(model.trace(std::vector<double>{}), std::invalid_argument);
  EXPECT_THROW(model.trace(std::vector<double>{0.5, 1.5}), std::invalid_argument);
  EXPECT_THROW(model.trace(std::vector<double>{0.5, std::nan("")}), std::invalid_argument);
}

std::vector<double> random_ray(std::mt19937_64& rng, int length) {
  std::uniform_int_distribution<int> kind(0, 2);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::vector<double> cells;
  for (int i = 0; i < length; ++i) {
    switch (kind(rng)) {
      case 0:
        cells.push_back(0.12 + 0.28 * u(rng));
        break;  // free
      case 1:
        cells.push_back(0.6 + 0.37 * u(rng));
        break;  // occupied
      default:
        cells.push_back(0.41 + 0.18 * u(rng));
        break;  // unobserved
    }
  }
  return cells;
}

TEST(RayModel, VisibilityAndPosteriorStayProbabilities) {
  std::mt19937_64 rng(1);
  for (const double alpha : {0.5, 0.9, 0.997, 0.9999, 1.0}) {
    const RayModel model(alpha);
    for (int i = 0; i < 300; ++i) {
      for (const RayState& s : model.trace(random_ray(rng, 200))) {
        ASSERT_GE(s.visibility, 0.0);
        ASSERT_LE(s.visibility, 1.0);
        ASSERT_GE(s.posterior, 0.0);
        ASSERT_LE(s.posterior, 1.0);
      }
    }
  }
}

TEST(RayModel, VisibilityNeverRisesThroughUnobservedCells) {
  for (const double alpha : {0.9, 0.997, 0.9999}) {
    const auto states = RayModel(alpha).trace(std::vector<double>(300, 0.5));
    for (std::size_t m = 1; m < states.size(); ++m) {
      ASSERT_LE(states[m].visibility, states[m - 1].visibility) << "a=" << alpha << " m=" << m;
    }
    EXPECT_LT(states.back().visibility, states[1].visibility);  // eq. (8): it really falls
  }
}

TEST(RayModel, VisibilityDropsBehindAnOccupiedCell) {
  std::mt19937_64 rng(3);
  std::uniform_int_distribution<int> where(1, 80);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const RayModel model(0.997);
  for (int i = 0; i < 500; ++i) {
    // Free and unobserved cells with one occupied cell at k.
    std::vector<double> cells;
    for (int j = 0; j < 100; ++j) cells.push_back(u(rng) < 0.5 ? 0.12 : 0.5);
    const int k = where(rng);
    cells[static_cast<std::size_t>(k)] = 0.6 + 0.37 * u(rng);
    const auto states = model.trace(cells);
    ASSERT_LT(states[static_cast<std::size_t>(k) + 1].visibility,
              states[static_cast<std::size_t>(k)].visibility)
        << "ray " << i << ", occupied cell " << k;
  }
}

/// Gains of the unobserved cells that follow `free_cells` free cells, as each in turn is the
/// target.
std::vector<double> unobserved_gains(double alpha, int free_cells, int unobserved) {
  std::vector<double> cells(static_cast<std::size_t>(free_cells), 0.12);
  cells.insert(cells.end(), static_cast<std::size_t>(unobserved), 0.5);
  const auto states = RayModel(alpha).trace(cells);
  std::vector<double> gains;
  for (std::size_t m = static_cast<std::size_t>(free_cells); m < states.size(); ++m) {
    gains.push_back(states[m].gain());
  }
  return gains;
}

TEST(RayModel, GainFallsWithDepthAndFasterForSmallerAlpha) {
  for (const int free_cells : {1, 10, 40}) {
    const auto g09 = unobserved_gains(0.9, free_cells, 30);
    const auto g0997 = unobserved_gains(0.997, free_cells, 30);
    const auto g09999 = unobserved_gains(0.9999, free_cells, 30);
    // Deep in unobserved space the posterior pins at exactly 0.5 and the gain at 0; until then it
    // falls strictly.
    constexpr double kPinned = 1e-12;
    for (const auto* g : {&g09, &g0997, &g09999}) {
      ASSERT_GT((*g)[0], 0.0);
      for (std::size_t d = 1; d < g->size(); ++d) {
        ASSERT_LE((*g)[d], (*g)[d - 1]);
        if ((*g)[d - 1] > kPinned) {
          ASSERT_LT((*g)[d], (*g)[d - 1]);
        }
      }
    }
    // Relative to the first unobserved cell, deeper cells keep less of their gain for smaller a.
    for (std::size_t d = 1; d < g09.size(); ++d) {
      if (g09[d] > kPinned) {
        ASSERT_LT(g09[d] / g09[0], g0997[d] / g0997[0]) << "free " << free_cells << " d " << d;
      }
      if (g0997[d] > kPinned) {
        ASSERT_LT(g0997[d] / g0997[0], g09999[d] / g09999[0])
            << "free " << free_cells << " d " << d;
      }
    }
    EXPECT_LT(g09[3] / g09[0], 0.5);        // a = 0.9 loses most of it within three cells ...
    EXPECT_GT(g09999[3] / g09999[0], 0.9);  // ... a = 0.9999 hardly any
  }
}

TEST(UniformPrefix, MatchesStepping) {
  const RayModel model(0.997);
  const UniformPrefix prefix(model, 0.12, 50);
  const auto states = model.trace(std::vector<double>(50, 0.12));
  for (int k = 1; k <= 50; ++k) {
    EXPECT_EQ(prefix.at(k).visibility, states[static_cast<std::size_t>(k - 1)].visibility);
    EXPECT_EQ(prefix.at(k).posterior, states[static_cast<std::size_t>(k - 1)].posterior);
    EXPECT_EQ(prefix.at(k).m, k - 1);
  }
}

TEST(Greedy, BlockedByAnOccupiedCellBeforeTheTarget) {
  EXPECT_TRUE(greedy_visible(std::vector<double>{0.12, 0.5, 0.5}));
  EXPECT_FALSE(greedy_visible(std::vector<double>{0.12, 0.6, 0.5}));
  EXPECT_TRUE(greedy_visible(std::vector<double>{0.12, 0.59, 0.97}));  // the target itself
}

}  // namespace
}  // namespace vantage
