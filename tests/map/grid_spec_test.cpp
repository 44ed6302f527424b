#include "vantage/map/grid_spec.hpp"

#include <gtest/gtest.h>

#include <stdexcept>

namespace vantage {
namespace {

TEST(GridSpec, WorldIndexRoundTrip) {
  const GridSpec spec = GridSpec::centered({0.0, 0.0, 0.25}, 1.0 / 128.0, {129, 129, 65});
  for (const Index3& cell : {Index3(0, 0, 0), Index3(128, 128, 64), Index3(64, 3, 17)}) {
    EXPECT_EQ(spec.index_of(spec.center(cell)), cell);
    EXPECT_EQ(spec.unravel(spec.linear(cell)), cell);
  }
  EXPECT_EQ(spec.num_cells(), 129u * 129u * 65u);
}

TEST(GridSpec, RejectsPointsOutsideAndNaN) {
  const GridSpec spec = GridSpec::centered({0, 0, 0}, 0.1, {10, 10, 10});
  EXPECT_FALSE(spec.find({0.5, 0.0, 0.0}));  // the max face is outside: cells are half-open
  EXPECT_TRUE(spec.find({-0.5, 0.0, 0.0}));
  EXPECT_FALSE(spec.find({std::nan(""), 0.0, 0.0}));
  EXPECT_THROW(spec.index_of({2.0, 0.0, 0.0}), std::out_of_range);
  EXPECT_FALSE(spec.find({1e300, 0.0, 0.0}));  // no integer overflow
}

TEST(GridSpec, ValidateNamesTheField) {
  GridSpec spec;
  spec.resolution = 0.0;
  try {
    spec.validate();
    FAIL() << "zero resolution accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("grid.resolution"), std::string::npos);
  }
  spec.resolution = -0.1;
  EXPECT_THROW(spec.validate(), std::invalid_argument);
  spec.resolution = 0.1;
  spec.dims = {10, 0, 10};
  EXPECT_THROW(spec.validate(), std::invalid_argument);
  spec.dims = {4096, 4096, 4096};  // 2^36 cells
  EXPECT_THROW(spec.validate(), std::invalid_argument);
}

}  // namespace
}  // namespace vantage
