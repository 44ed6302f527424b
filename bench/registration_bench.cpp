// Scan-to-map registration, ours against PCL's point-to-plane ICP
// (pcl::IterativeClosestPointWithNormals) and GICP (pcl::GeneralizedIterativeClosestPoint) on the
// same pairs (BENCHMARK.md, "Registration"). Cases 0-11: the built-in table tops 1-4 after 1, 3
// and 6 scans: the reference is the objects of the first N scans of a typical exploration (ring
// views 1, 16, 24, 7, 10, 22 at their true poses), the scan the objects seen from the next view
// (16, the far side, after 1; 7 after 3; 4 after 6). Case 12: the large office
// (office-large-cluttered), the sweep at its first start against the sweep at the explorer's
// second stop, both thinned to cells. Every guess is off by the robot's base error (2 cm,
// -1.5 cm, 1.5° about the sensor). All three start from the guess and align the scan thinned as
// the explorer does against the same reference points (our voxel map's, with its normals); PCL's
// methods pair within 10 cm on a table top (5 cm left too few pairs), 25 cm in the office, at
// most 50 iterations.
#include <benchmark/benchmark.h>
#include <pcl/registration/gicp.h>
#include <pcl/registration/icp.h>

#include <array>
#include <map>
#include <memory>
#include <string>

#include "vantage/experiment/exploration.hpp"
#include "vantage/perception/registration.hpp"
#include "vantage/perception/table_segmentation.hpp"
#include "vantage/perception/voxel_filter.hpp"
#include "vantage/perception/voxel_map.hpp"
#include "vantage/sim/world.hpp"

namespace vantage::bench {
namespace {

using perception::pose_error;

struct Pair {
  std::string label;
  perception::VoxelMap map;
  PointCloud scan;  ///< sensor frame
  Eigen::Isometry3d truth, guess;
  perception::RegistrationConfig config;
  double pcl_distance = 0.1;  ///< [m]
};

constexpr int kOfficeCase = 12;

/// The objects (above the table) of a scan from `pose`, in the sensor frame.
PointCloud objects(const sim::World& world, const Eigen::Isometry3d& pose, std::uint64_t seed) {
  const sim::SimulatedScan scan = world.scan(pose, seed);
  const PointCloud world_points = transform(pose, scan.points_sensor);
  const perception::TableSegmentation table = perception::segment_table(world_points, {});
  PointCloud out;
  for (const std::size_t i : table.object_indices) out.push_back(scan.points_sensor[i]);
  return out;
}

/// The truth off by the robot's base error: a shift and a turn about the vertical at the sensor.
Eigen::Isometry3d with_base_error(const Eigen::Isometry3d& truth) {
  Eigen::Isometry3d guess = truth;
  guess.translation() += Eigen::Vector3d(0.02, -0.015, 0.0);
  guess.linear() = Eigen::AngleAxisd(deg2rad(1.5), Eigen::Vector3d::UnitZ()) * truth.linear();
  return guess;
}

/// Table top `scene` (1-4) after `scans` scans of the view sequence.
Pair table_top(int scene, int scans) {
  const sim::Scene description = sim::load_scene("tabletop-" + std::to_string(scene));
  const sim::World world(description);
  const std::vector<Eigen::Isometry3d> poses = description.candidate_poses();
  constexpr std::array<int, 7> kViews = {1, 16, 24, 7, 10, 22, 4};
  Pair p;
  p.label = "tabletop-" + std::to_string(scene) + " after " + std::to_string(scans);
  p.config = default_mapper_config(description).registration;
  for (int k = 0; k < scans; ++k) {
    const Eigen::Isometry3d& pose = poses[kViews[k]];
    p.map.add(transform(pose, objects(world, pose, 1 + k)), pose.translation());
  }
  p.truth = poses[kViews[scans]];
  p.scan = objects(world, p.truth, 100);
  return p;
}

/// The large office: the sweep at the first start against the sweep at the explorer's second stop
/// (`vantage explore --scene office-large-cluttered --method random`, seed 1), each thinned to
/// one point per cell. NOTE: the explorer registers only the points in cells the map knows; here
/// the pairing distance alone keeps the rest out.
Pair office() {
  const sim::Scene scene = sim::load_scene("office-large-cluttered");
  const sim::World world(scene);
  const MapperConfig mapper = default_mapper_config(scene);
  Pair p;
  p.label = "office-large-cluttered";
  p.map = perception::VoxelMap(mapper.map);
  p.config = mapper.registration;
  p.pcl_distance = 0.25;
  const double cell = scene.grid.resolution;
  const Eigen::Isometry3d& start = scene.start_poses.front();
  p.map.add(perception::voxel_downsample(world.sweep(start, 1).points_world(), cell),
            start.translation());
  p.truth = scene.mount.sensor_pose(11.66, 4.05625, deg2rad(43.6));
  p.scan = perception::voxel_downsample(world.sweep(p.truth, 2).points_sensor, cell);
  return p;
}

const Pair& pair_of(int index) {
  static std::map<int, Pair> pairs;
  if (const auto it = pairs.find(index); it != pairs.end()) return it->second;
  Pair p =
      index == kOfficeCase ? office() : table_top(1 + index / 3, std::array{1, 3, 6}[index % 3]);
  p.guess = with_base_error(p.truth);
  p.config.num_threads = 2;
  return pairs.emplace(index, std::move(p)).first->second;
}

void report(benchmark::State& state, const Pair& p, const Eigen::Isometry3d& result) {
  state.SetLabel(p.label);
  state.counters["before_mm"] = 1e3 * pose_error(p.guess, p.truth).translation;
  state.counters["after_mm"] = 1e3 * pose_error(result, p.truth).translation;
  state.counters["after_deg"] = pose_error(result, p.truth).rotation * 180.0 / M_PI;
}

/// Argument: the case (0-12, see the top). Two threads, as the bar; the explorer's
/// settings for the scene.
void BM_Register_Ours(benchmark::State& state) {
  const Pair& p = pair_of(static_cast<int>(state.range(0)));
  perception::RegistrationResult r;
  for (auto _ : state) r = perception::register_scan(p.scan, p.guess, p.map, p.config);
  report(state, p, r.T_world_sensor);
  state.counters["accepted"] = r.accepted() ? 1.0 : 0.0;
  state.counters["solved_mm"] = 1e3 * pose_error(r.T_world_sensor_solved, p.truth).translation;
}
BENCHMARK(BM_Register_Ours)->DenseRange(0, kOfficeCase)->Unit(benchmark::kMillisecond);

template <typename Point>
typename pcl::PointCloud<Point>::Ptr to_pcl(const PointCloud& points,
                                            const std::vector<Eigen::Vector3d>* normals) {
  auto cloud = std::make_shared<pcl::PointCloud<Point>>();
  for (std::size_t i = 0; i < points.size(); ++i) {
    if (normals != nullptr && (*normals)[i].isZero()) continue;
    Point q;
    q.getVector3fMap() = points[i].cast<float>();
    if constexpr (std::is_same_v<Point, pcl::PointNormal>) {
      q.getNormalVector3fMap() =
          normals ? (*normals)[i].cast<float>() : Eigen::Vector3f::Zero().eval();
    }
    cloud->push_back(q);
  }
  return cloud;
}

/// Runs a PCL registration from the guess; `Method` is set up by `configure`.
template <typename Point, typename Method>
void run_pcl(benchmark::State& state, Method& method) {
  const Pair& p = pair_of(static_cast<int>(state.range(0)));
  const auto target = to_pcl<Point>(p.map.points(), &p.map.normals());
  const auto source =
      to_pcl<Point>(perception::voxel_downsample(p.scan, p.config.voxel_size), nullptr);
  method.setMaxCorrespondenceDistance(p.pcl_distance);
  method.setMaximumIterations(50);
  method.setTransformationEpsilon(1e-10);
  perception::silence_pcl_console();  // "Not enough correspondences": after_mm says it
  pcl::PointCloud<Point> aligned;
  Eigen::Matrix4d T = Eigen::Matrix4d::Identity();
  for (auto _ : state) {
    method.setInputTarget(target);
    method.setInputSource(source);
    method.align(aligned, p.guess.matrix());
    T = method.getFinalTransformation();
  }
  Eigen::Isometry3d result = Eigen::Isometry3d::Identity();
  result.linear() = Eigen::Quaterniond(T.topLeftCorner<3, 3>()).normalized().toRotationMatrix();
  result.translation() = T.topRightCorner<3, 1>();
  report(state, p, result);
}

void BM_Register_PclPointToPlane(benchmark::State& state) {
  pcl::IterativeClosestPointWithNormals<pcl::PointNormal, pcl::PointNormal, double> icp;
  run_pcl<pcl::PointNormal>(state, icp);
}
BENCHMARK(BM_Register_PclPointToPlane)->DenseRange(0, kOfficeCase)->Unit(benchmark::kMillisecond);

void BM_Register_PclGicp(benchmark::State& state) {
  pcl::GeneralizedIterativeClosestPoint<pcl::PointXYZ, pcl::PointXYZ, double> gicp;
  run_pcl<pcl::PointXYZ>(state, gicp);
}
BENCHMARK(BM_Register_PclGicp)->DenseRange(0, kOfficeCase)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace vantage::bench
