// The data `vantage view` puts into its page, checked against the folder it came from: cells by
// brute force, the even thinning under a cap, the decisions and the chosen views.

#include "vantage/experiment/viewer.hpp"

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <set>
#include <string>
#include <tuple>

#include "tests/experiment/test_scene.hpp"
#include "tests/io/temp_dir.hpp"
#include "vantage/experiment/results.hpp"
#include "vantage/io/octomap_io.hpp"

namespace vantage {
namespace {

using nlohmann::json;
using test::TempDir;
using test::write_file;
using Cell = std::tuple<int, int, int>;

const GridSpec kSpec{Eigen::Vector3d(0.0, 0.0, 0.0), 0.1, Index3(6, 5, 4)};

/// A map whose occupied cells are every cell with x + 2y + 3z divisible by 5 (24 of 120), free
/// cells where x < 2 and not occupied, and the rest unobserved.
OccupancyGrid test_map() {
  OccupancyGrid grid(kSpec);
  for (std::size_t i = 0; i < grid.size(); ++i) {
    const Index3 c = kSpec.unravel(i);
    if ((c.x() + 2 * c.y() + 3 * c.z()) % 5 == 0) {
      grid.set_probability(i, 0.97);
    } else if (c.x() < 2) {
      grid.set_probability(i, 0.12);
    }
  }
  return grid;
}

json pose(double x, double y, double z) {
  return {{"position", {x, y, z}}, {"quaternion_xyzw", {0.0, 0.0, 0.0, 1.0}}};
}

json grid_json() { return {{"origin", {0.0, 0.0, 0.0}}, {"resolution", 0.1}, {"dims", {6, 5, 4}}}; }

/// An explore folder of two scans: the second scan's decision weighed views 1, 2 and 5, took 5.
json run_json() {
  json scan1 = {{"scan", 1},
                {"view", 2},
                {"pose", pose(1, 0, 1)},
                {"path", json::array()},
                {"actual_gain", 40},
                {"unobserved", 80},
                {"coverage", 0.25},
                {"predicted_gain", nullptr},
                {"considered", json::array()}};
  json scan2 = scan1;
  scan2["scan"] = 2;
  scan2["view"] = 5;
  scan2["pose"] = pose(0, 1, 1);
  scan2["predicted_gain"] = 7.5;
  scan2["considered"] = {{{"view", 1},
                          {"pose", pose(-1, 0, 1)},
                          {"predicted_gain", 2.0},
                          {"greedy_predicted_gain", 9}},
                         {{"view", 3},
                          {"pose", pose(0, -1, 1)},
                          {"predicted_gain", 3.0},
                          {"greedy_predicted_gain", 8}},
                         {{"view", 5},
                          {"pose", pose(0, 1, 1)},
                          {"predicted_gain", 7.5},
                          {"greedy_predicted_gain", 7}}};
  return {
      {"scene",
       {{"name", "test"},
        {"kind", "tabletop"},
        {"grid", grid_json()},
        {"sensor",
         {{"h_fov_rad", 1.0}, {"v_fov_rad", 0.75}, {"min_range_m", 0.1}, {"max_range_m", 3.0}}}}},
      {"config", {{"method", "probabilistic"}}},
      {"gain_units", {{"predicted_gain", "bits"}, {"greedy_predicted_gain", "cells"}}},
      {"scans", {scan1, scan2}}};
}

/// A stand-in for the fetched three.js: the page only inlines it.
void fake_three(const std::filesystem::path& web, const std::string& version) {
  write_file(web / "three" / "package.json", json{{"version", version}}.dump());
  write_file(web / "three" / "build" / "three.module.min.js", "export const REVISION = '170';\n");
  write_file(web / "three" / "examples" / "jsm" / "controls" / "OrbitControls.js",
             "import { EventDispatcher } from 'three';\nexport { EventDispatcher };\n");
}

/// The JSON the page carries in #vantage-data.
json page_data(const std::string& page) {
  const std::string open = R"(<script type="application/json" id="vantage-data">)";
  const std::size_t begin = page.find(open);
  EXPECT_NE(begin, std::string::npos);
  const std::size_t end = page.find("</script>", begin);
  return json::parse(page.substr(begin + open.size(), end - begin - open.size()));
}

std::set<Cell> cells_of(const json& flat) {
  std::set<Cell> cells;
  for (std::size_t i = 0; i + 2 < flat.size(); i += 3) {
    cells.insert({flat[i].get<int>(), flat[i + 1].get<int>(), flat[i + 2].get<int>()});
  }
  return cells;
}

class ViewerTest : public ::testing::Test {
 protected:
  void SetUp() override {
    fake_three(tmp_ / "web", kThreeVersion);
    config_.web_dir = tmp_ / "web";
    write_octomap(tmp_ / "run" / "map.bt", map_);
    write_file(tmp_ / "run" / "run.json", run_json().dump());
  }
  TempDir tmp_;
  OccupancyGrid map_ = test_map();
  ViewerConfig config_;
};

TEST_F(ViewerTest, DrawsEveryOccupiedCellAndTheSurfaceOfTheUnknown) {
  const json data = page_data(build_view_page(tmp_ / "run", config_));
  std::set<Cell> occupied, surface;
  std::size_t unobserved = 0;
  for (std::size_t i = 0; i < map_.size(); ++i) {
    const Index3 c = kSpec.unravel(i);
    if (map_.state(i) == CellState::kOccupied) occupied.insert({c.x(), c.y(), c.z()});
    if (map_.state(i) != CellState::kUnobserved) continue;
    ++unobserved;
    for (int axis = 0; axis < 3; ++axis) {  // brute force: any known 6-neighbour
      for (int step : {-1, 1}) {
        Index3 n = c;
        n[axis] += step;
        if (kSpec.contains(n) && map_.state(kSpec.linear(n)) != CellState::kUnobserved) {
          surface.insert({c.x(), c.y(), c.z()});
        }
      }
    }
  }
  ASSERT_EQ(occupied.size(), 24u);
  EXPECT_EQ(data["occupied"]["total"], occupied.size());
  EXPECT_EQ(cells_of(data["occupied"]["cells"]), occupied);
  EXPECT_EQ(data["unobserved"]["total"], surface.size());
  EXPECT_EQ(data["unobserved"]["all"], unobserved);
  EXPECT_EQ(cells_of(data["unobserved"]["cells"]), surface);
  EXPECT_LT(surface.size(), unobserved);  // the test map has unknown cells inside the unknown
}

TEST_F(ViewerTest, DecisionsPointAtTheViewTaken) {
  const json data = page_data(build_view_page(tmp_ / "run", config_));
  EXPECT_EQ(data["source"], "explore");
  EXPECT_EQ(data["units"]["gain"], "bits");
  EXPECT_EQ(data["units"]["greedy"], "cells");
  ASSERT_EQ(data["scans"].size(), 2u);
  ASSERT_EQ(data["decisions"].size(), 1u);  // the first scan had no decision
  const json& d = data["decisions"][0];
  EXPECT_EQ(d["after_scan"], 1);
  ASSERT_EQ(d["candidates"].size(), 3u);
  EXPECT_EQ(d["chosen"], 2);
  EXPECT_EQ(d["candidates"][2]["view"], 5);
  EXPECT_EQ(d["candidates"][2]["gain"], 7.5);
  EXPECT_EQ(d["candidates"][0]["greedy"], 9);
  EXPECT_DOUBLE_EQ(data["sensor"]["h_fov"].get<double>(), 1.0);
}

TEST_F(ViewerTest, ACapThinsTheCellsEvenly) {
  for (const std::size_t cap : {1u, 5u, 7u, 23u, 24u}) {
    config_.max_cells = cap;
    const json data = page_data(build_view_page(tmp_ / "run", config_));
    const std::set<Cell> drawn = cells_of(data["occupied"]["cells"]);
    EXPECT_EQ(data["occupied"]["total"], 24u);
    EXPECT_EQ(drawn.size(), cap);
    EXPECT_EQ(data["max_cells"], cap);
    // Spread over the whole map, not its first cells: the last drawn cell lies in the last
    // 24 / cap of the occupied cells (in the grid's order).
    std::set<std::size_t> order;
    for (std::size_t i = 0; i < map_.size(); ++i) {
      if (map_.state(i) == CellState::kOccupied) order.insert(i);
    }
    std::size_t rank = 0, last_rank = 0;
    for (const std::size_t i : order) {
      const Index3 c = kSpec.unravel(i);
      if (drawn.count({c.x(), c.y(), c.z()})) last_rank = rank;
      ++rank;
    }
    EXPECT_GE(last_rank + 24 / cap, 24u) << "cap " << cap;
  }
}

TEST_F(ViewerTest, PlanFolderShowsItsRankingAndTheNextBestView) {
  const json plan = {
      {"map", {{"grid", grid_json()}}},
      {"method", "greedy"},
      {"next_best_view", {{"index", 4}}},
      {"candidates",
       {{{"index", 4}, {"sensor", pose(1, 1, 1)}, {"predicted_gain", 30}, {"greedy_gain", 30}},
        {{"index", 0}, {"sensor", pose(1, 0, 1)}, {"predicted_gain", 10}, {"greedy_gain", 10}}}}};
  write_octomap(tmp_ / "plan" / "map.bt", map_);
  write_file(tmp_ / "plan" / "plan.json", plan.dump());
  const json data = page_data(build_view_page(tmp_ / "plan", config_));
  EXPECT_EQ(data["source"], "plan");
  EXPECT_EQ(data["units"]["gain"], "cells");  // greedy counts cells
  ASSERT_EQ(data["decisions"].size(), 1u);
  EXPECT_EQ(data["decisions"][0]["chosen"], 0);
  EXPECT_EQ(data["occupied"]["total"], 24u);
  EXPECT_FALSE(data.contains("sensor"));  // not recorded: the page says so
  EXPECT_EQ(data["notes"].size(), 1u);
}

TEST_F(ViewerTest, TextFromTheFolderCannotCloseThePagesScripts) {
  json run = run_json();
  run["scene"]["name"] = "a</script><script>alert(1)</script>";
  write_file(tmp_ / "run" / "run.json", run.dump());
  const std::string page = build_view_page(tmp_ / "run", config_);
  const json data = page_data(page);  // parses: the data's element was not closed early
  EXPECT_NE(data["title"].get<std::string>().find("a</script>"), std::string::npos);
  EXPECT_EQ(page.find("<script>alert"), std::string::npos);
}

TEST_F(ViewerTest, MissingOrWrongThreeNamesTheFetchScript) {
  config_.web_dir = tmp_ / "nowhere";
  try {
    build_view_page(tmp_ / "run", config_);
    FAIL() << "no error without three.js";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("fetch-web.sh"), std::string::npos) << e.what();
  }
  fake_three(tmp_ / "old", "0.160.0");
  config_.web_dir = tmp_ / "old";
  EXPECT_THROW(build_view_page(tmp_ / "run", config_), std::runtime_error);
}

TEST_F(ViewerTest, ScansWhoseDecisionLacksTheViewTakenAreRejected) {
  json run = run_json();
  run["scans"][1]["view"] = 7;
  write_file(tmp_ / "run" / "run.json", run.dump());
  try {
    build_view_page(tmp_ / "run", config_);
    FAIL() << "no error";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("run.json"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("considered"), std::string::npos) << e.what();
  }
}

/// A real run records, with each scan, the candidates of the decision that chose it: their number
/// is the decision's, the view taken is among them with the scan's own predictions, and (without
/// revisits) no view taken before is offered again. The page of that run draws them.
TEST_F(ViewerTest, ARunRecordsEveryDecisionsCandidatesForThePage) {
  for (const char* file :
       {"tests/experiment/small_tabletop.yaml", "tests/experiment/small_office.yaml"}) {
    SCOPED_TRACE(file);
    const sim::Scene scene = sim::load_scene((testing::source_dir() / file).string());
    ExplorationConfig config;
    config.scans = 2;
    config.seed = 3;
    config.mapper = default_mapper_config(scene);
    Mapper mapper(scene.grid, config.mapper);
    const ExplorationResult result = explore(scene, config, mapper);
    ASSERT_EQ(result.scans.size(), 2u);
    EXPECT_TRUE(result.scans[0].considered.empty());
    const ScanRecord& second = result.scans[1];
    ASSERT_EQ(second.considered.size(), static_cast<std::size_t>(second.candidates));
    int taken = 0;
    for (const CandidateRecord& c : second.considered) {
      if (c.view != second.view) continue;
      ++taken;
      EXPECT_EQ(c.predicted_gain, second.predicted_gain.value());
      EXPECT_EQ(c.greedy_predicted_gain, second.greedy_predicted_gain.value());
      // Table top: the view is the ring's pose (an office scans where the drive ended).
      if (scene.kind == sim::SceneKind::kTableTop) {
        EXPECT_TRUE(c.T_world_sensor.isApprox(second.T_world_sensor, 1e-12));
      }
    }
    EXPECT_EQ(taken, 1);
    if (scene.kind == sim::SceneKind::kTableTop) {
      for (const CandidateRecord& c : second.considered) EXPECT_NE(c.view, result.scans[0].view);
    }

    const std::filesystem::path dir = tmp_ / scene.name;
    std::filesystem::create_directories(dir);
    write_run_files(dir, scene, config, result, mapper);
    const json data = page_data(build_view_page(dir, config_));
    ASSERT_EQ(data["decisions"].size(), 1u);
    const json& d = data["decisions"][0];
    EXPECT_EQ(d["candidates"].size(), second.considered.size());
    EXPECT_EQ(d["candidates"][d["chosen"].get<std::size_t>()]["view"], second.view);
    EXPECT_EQ(data["occupied"]["total"], mapper.grid().counts().occupied);
    EXPECT_EQ(data["office"], scene.kind == sim::SceneKind::kOffice);
    EXPECT_DOUBLE_EQ(data["sensor"]["h_fov"].get<double>(), scene.fov().h_fov);
  }
}

}  // namespace
}  // namespace vantage
