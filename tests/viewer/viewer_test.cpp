// The data `vantage view` puts into its page, checked against the folder it came from: cells by
// brute force, the even thinning under a cap, the decisions and the chosen views.

#include "vantage/experiment/viewer.hpp"

#include <gtest/gtest.h>
#include <sys/stat.h>

#include <algorithm>
#include <cmath>
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

/// The one line build_view_page fails with on `dir`; fails the test when it succeeds.
std::string view_error(const std::filesystem::path& dir, const ViewerConfig& config) {
  try {
    build_view_page(dir, config);
  } catch (const std::runtime_error& e) {
    return e.what();
  }
  ADD_FAILURE() << "no error for " << dir;
  return {};
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
  // Not recorded: the default sensor, and the page says so.
  EXPECT_DOUBLE_EQ(data["sensor"]["h_fov"].get<double>(), SensorFov{}.h_fov);
  ASSERT_EQ(data["notes"].size(), 1u);
  EXPECT_NE(data["notes"][0].get<std::string>().find("does not record the sensor"),
            std::string::npos);
}

/// A survival plan as `vantage plan` writes it (issue 27's contract): the score is the expected
/// cells seen, predicted_gain is in bits, and the two disagree on the order; the chosen view,
/// index 2, has the most cells and the fewest bits.
json survival_plan() {
  json candidates = json::array();
  const std::array<std::array<double, 3>, 4> gains = {
      {{2, 100.0, 5000.0}, {3, 700.0, 300.0}, {1, 800.0, 200.0}, {0, 900.0, 100.0}}};
  for (const auto& [index, bits, cells] : gains) {
    candidates.push_back({{"index", static_cast<int>(index)},
                          {"sensor", pose(index, 0, 1)},
                          {"predicted_gain", bits},
                          {"predicted_cells", cells},
                          {"greedy_gain", cells + 1},
                          {"score", cells}});
  }
  return {{"map", {{"grid", grid_json()}, {"clouds", 1}}},
          {"method", "survival"},
          {"objective", "cells"},
          {"clouds", 1},
          {"sensor",
           {{"horizontal_fov_deg", 63.0},
            {"vertical_fov_deg", 49.0},
            {"min_range_m", 0.4},
            {"max_range_m", 3.0}}},
          {"units",
           {{"predicted_gain", "bits"},
            {"predicted_cells", "cells"},
            {"greedy_gain", "cells"},
            {"score", "cells"},
            {"travel", "m"}}},
          {"next_best_view", candidates[0]},
          {"candidates", candidates}};
}

TEST_F(ViewerTest, APlanIsColouredByItsScoreInItsUnit) {
  // plan.json before issue 27 said "bits" for the survival reading's score: the objective wins.
  for (const char* said : {"cells", "bits"}) {
    SCOPED_TRACE(said);
    json plan = survival_plan();
    plan["units"]["score"] = said;
    write_octomap(tmp_ / "plan" / "map.bt", map_);
    write_file(tmp_ / "plan" / "plan.json", plan.dump());
    const json data = page_data(build_view_page(tmp_ / "plan", config_));
    EXPECT_EQ(data["units"]["score"], "cells");
    EXPECT_EQ(data["units"]["gain"], "bits");
    EXPECT_EQ(data["ranked_by"], "expected cells seen");
    const json& d = data["decisions"][0];
    ASSERT_EQ(d["candidates"].size(), 4u);
    const json& chosen = d["candidates"][d["chosen"].get<std::size_t>()];
    EXPECT_EQ(chosen["view"], 2);
    EXPECT_EQ(chosen["score"], 5000.0);
    EXPECT_EQ(chosen["gain"], 100.0);
    EXPECT_EQ(chosen["cells"], 5000.0);
    EXPECT_EQ(chosen["greedy"], 5001.0);
    for (const json& c : d["candidates"]) EXPECT_LE(c["score"], chosen["score"]);
  }
}

TEST_F(ViewerTest, APlanDrawsTheRecordedSensorAndCountsItsClouds) {
  write_octomap(tmp_ / "plan" / "map.bt", map_);
  json plan = survival_plan();
  write_file(tmp_ / "plan" / "plan.json", plan.dump());
  json data = page_data(build_view_page(tmp_ / "plan", config_));
  EXPECT_NEAR(data["sensor"]["h_fov"].get<double>(), 63.0 * M_PI / 180.0, 1e-12);
  EXPECT_NEAR(data["sensor"]["v_fov"].get<double>(), 49.0 * M_PI / 180.0, 1e-12);
  EXPECT_EQ(data["sensor"]["min_range"], 0.4);
  EXPECT_EQ(data["sensor"]["max_range"], 3.0);
  EXPECT_EQ(data["clouds"], 1);
  EXPECT_TRUE(data["notes"].empty()) << data["notes"];
  // A plan.json without the top-level count: its map's.
  plan.erase("clouds");
  plan["map"]["clouds"] = 0;
  write_file(tmp_ / "plan" / "plan.json", plan.dump());
  data = page_data(build_view_page(tmp_ / "plan", config_));
  EXPECT_EQ(data["clouds"], 0);
}

TEST_F(ViewerTest, AnExploreRunOfTheSurvivalReadingIsInCells) {
  json run = run_json();
  run["config"]["method"] = "survival";
  run["config"]["objective"] = "cells";
  // Cells disagree with bits: view 1 has the most bits, view 5 (taken) the most cells.
  const std::array<double, 3> cells = {300.0, 200.0, 11536.0};
  for (std::size_t j = 0; j < 3; ++j)
    run["scans"][1]["considered"][j]["predicted_cells"] = cells[j];
  run["scans"][1]["considered"][0]["predicted_gain"] = 9000.0;
  write_file(tmp_ / "run" / "run.json", run.dump());
  const json data = page_data(build_view_page(tmp_ / "run", config_));
  EXPECT_EQ(data["units"]["score"], "cells");
  const json& d = data["decisions"][0];
  const json& chosen = d["candidates"][d["chosen"].get<std::size_t>()];
  EXPECT_EQ(chosen["view"], 5);
  EXPECT_EQ(chosen["score"], 11536.0);  // the terminal's "predicted 11536 cells"
  EXPECT_EQ(chosen["cells"], 11536.0);
  EXPECT_EQ(d["candidates"][0]["score"], 300.0);
}

TEST_F(ViewerTest, ManyCandidatesAreCutToTheBestAndTheChosen) {
  json plan = survival_plan();
  json candidates = json::array();
  for (int i = 0; i < 50; ++i) {
    candidates.push_back({{"index", i},
                          {"sensor", pose(i * 0.01, 0, 1)},
                          {"predicted_gain", 1.0},
                          {"score", static_cast<double>((i * 7) % 50)}});
  }
  plan["candidates"] = candidates;
  plan["next_best_view"] = candidates[0];  // score 0: the worst, still drawn
  write_octomap(tmp_ / "plan" / "map.bt", map_);
  write_file(tmp_ / "plan" / "plan.json", plan.dump());
  config_.max_candidates = 10;
  const json data = page_data(build_view_page(tmp_ / "plan", config_));
  const json& d = data["decisions"][0];
  EXPECT_EQ(d["total"], 50);
  ASSERT_EQ(d["candidates"].size(), 10u);
  EXPECT_EQ(d["candidates"][d["chosen"].get<std::size_t>()]["view"], 0);
  std::set<double> scores;
  int previous = -1;
  for (const json& c : d["candidates"]) {
    scores.insert(c["score"].get<double>());
    EXPECT_GT(c["view"].get<int>(), previous);  // in the file's order
    previous = c["view"].get<int>();
  }
  EXPECT_EQ(scores, (std::set<double>{0, 41, 42, 43, 44, 45, 46, 47, 48, 49}));
  bool noted = false;
  for (const json& n : data["notes"])
    noted |= n.get<std::string>().find("40 candidates") != std::string::npos;
  EXPECT_TRUE(noted) << data["notes"];
}

TEST_F(ViewerTest, ResultsFilesThatAreNotRegularFilesAreRefused) {
  const std::filesystem::path fifo_dir = tmp_ / "fifo";
  std::filesystem::create_directories(fifo_dir);
  ASSERT_EQ(mkfifo((fifo_dir / "run.json").c_str(), 0600), 0);
  write_octomap(fifo_dir / "map.bt", map_);
  const std::filesystem::path zero_dir = tmp_ / "zero";
  std::filesystem::create_directories(zero_dir);
  std::filesystem::create_symlink("/dev/zero", zero_dir / "plan.json");
  for (const auto& [dir, what] :
       {std::pair{fifo_dir, "FIFO"}, std::pair{zero_dir, "character device"}}) {
    const std::string error = view_error(dir, config_);
    EXPECT_NE(error.find(what), std::string::npos) << error;
  }
}

TEST_F(ViewerTest, AnOversizedResultsFileIsRefusedUnread) {
  // Sparse: larger than the cap on paper, nothing on disk.
  const std::filesystem::path file = tmp_ / "run" / "run.json";
  std::filesystem::resize_file(file, kMaxViewerFileBytes + 1);
  const std::string error = view_error(tmp_ / "run", config_);
  EXPECT_NE(error.find("more than the 1 GiB a results file may have"), std::string::npos) << error;
}

// issue 39: a run.json whose grid says 1024^3 around a small map allocated the grid (4 GiB of
// log-odds); the page needs only the map's box, so that is what is held, and what the budget
// weighs. The layers are those of the true grid, and the count of unobserved cells the big one's.
TEST_F(ViewerTest, ASmallMapInAHugeGridCostsTheMapNotTheGrid) {
  const json small = page_data(build_view_page(tmp_ / "run", config_));
  json run = run_json();
  run["scene"]["grid"]["dims"] = {1024, 1024, 1024};
  write_file(tmp_ / "run" / "run.json", run.dump());
  config_.max_memory = std::uint64_t{1} << 30;  // the grid would need 8 GiB
  const json huge = page_data(build_view_page(tmp_ / "run", config_));
  EXPECT_EQ(cells_of(huge["occupied"]["cells"]), cells_of(small["occupied"]["cells"]));
  const std::size_t known = kSpec.num_cells() - small["unobserved"]["all"].get<std::size_t>();
  EXPECT_EQ(huge["unobserved"]["all"].get<std::size_t>(), (std::size_t{1} << 30) - known);
  // The true grid's surface, and the cells at its far faces that now border unknown cells.
  const std::set<Cell> before = cells_of(small["unobserved"]["cells"]);
  const std::set<Cell> after = cells_of(huge["unobserved"]["cells"]);
  EXPECT_TRUE(std::includes(after.begin(), after.end(), before.begin(), before.end()));
  EXPECT_GT(after.size(), before.size());
}

TEST_F(ViewerTest, DimsBeyondAnIntAreRefusedNotWrapped) {
  json run = run_json();
  run["scene"]["grid"]["dims"] = {4294967328ULL, 32, 17};  // once read as 32 (issue 27)
  write_file(tmp_ / "run" / "run.json", run.dump());
  const std::string error = view_error(tmp_ / "run", config_);
  EXPECT_NE(error.find("dims[0] is out of range"), std::string::npos) << error;
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
    config.planner.greedy_reference = true;  // the chosen candidate's record carries it too
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
