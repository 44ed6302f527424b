// Scan-to-map registration on the built-in table tops, ours against PCL's point-to-plane ICP
// (pcl::IterativeClosestPointWithNormals) and GICP (pcl::GeneralizedIterativeClosestPoint) on the
// same pairs (BENCHMARK.md, "Registration"). The reference is the objects of a scan from ring view
// 0, the scan the objects seen from ring view 3 (36° further), its guess off by the robot's base
// error (2 cm, -1.5 cm, 1.5°). All three start from the guess and align the scan thinned to 1 cm
// voxels against the same reference points (our voxel map's, with its normals); PCL's methods
// pair within 10 cm (5 cm left too few pairs from this guess), at most 50 iterations.
#include <benchmark/benchmark.h>
#include <pcl/registration/gicp.h>
#include <pcl/registration/icp.h>

#include <map>
#include <memory>
#include <string>

#include "vantage/perception/registration.hpp"
#include "vantage/perception/table_segmentation.hpp"
#include "vantage/perception/voxel_filter.hpp"
#include "vantage/perception/voxel_map.hpp"
#include "vantage/sim/world.hpp"

namespace vantage::bench {
namespace {

using perception::pose_error;

struct Pair {
  perception::VoxelMap map;
  PointCloud scan;  ///< sensor frame
  Eigen::Isometry3d truth, guess;
};

/// The objects (above the table) of a scan from `pose`, in the sensor frame.
PointCloud objects(const sim::World& world, const Eigen::Isometry3d& pose, std::uint64_t seed) {
  const sim::SimulatedScan scan = world.scan(pose, seed);
  const PointCloud world_points = transform(pose, scan.points_sensor);
  const perception::TableSegmentation table = perception::segment_table(world_points, {});
  PointCloud out;
  for (const std::size_t i : table.object_indices) out.push_back(scan.points_sensor[i]);
  return out;
}

const Pair& pair_of(int scene) {
  static std::map<int, Pair> pairs;
  if (const auto it = pairs.find(scene); it != pairs.end()) return it->second;
  const sim::World world(sim::load_scene("tabletop-" + std::to_string(scene)));
  const std::vector<Eigen::Isometry3d> poses = world.scene().candidate_poses();
  Pair p;
  p.map.add(transform(poses[0], objects(world, poses[0], 1)), poses[0].translation());
  p.truth = poses[3];
  p.scan = objects(world, p.truth, 2);
  p.guess = p.truth;
  p.guess.translation() += Eigen::Vector3d(0.02, -0.015, 0.0);
  p.guess.linear() = Eigen::AngleAxisd(deg2rad(1.5), Eigen::Vector3d::UnitZ()) * p.truth.linear();
  return pairs.emplace(scene, std::move(p)).first->second;
}

void report(benchmark::State& state, const Pair& p, const Eigen::Isometry3d& result) {
  state.counters["before_mm"] = 1e3 * pose_error(p.guess, p.truth).translation;
  state.counters["after_mm"] = 1e3 * pose_error(result, p.truth).translation;
  state.counters["after_deg"] = pose_error(result, p.truth).rotation * 180.0 / M_PI;
}

/// Argument: table top 1..4. Two threads, as the bar.
void BM_Register_Ours(benchmark::State& state) {
  const Pair& p = pair_of(static_cast<int>(state.range(0)));
  perception::RegistrationConfig config;
  config.num_threads = 2;
  perception::RegistrationResult r;
  for (auto _ : state) r = perception::register_scan(p.scan, p.guess, p.map, config);
  report(state, p, r.T_world_sensor);
}
BENCHMARK(BM_Register_Ours)->DenseRange(1, 4)->Unit(benchmark::kMillisecond);

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
  const auto source = to_pcl<Point>(perception::voxel_downsample(p.scan, 0.01), nullptr);
  method.setMaxCorrespondenceDistance(0.1);
  method.setMaximumIterations(50);
  method.setTransformationEpsilon(1e-10);
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
BENCHMARK(BM_Register_PclPointToPlane)->DenseRange(1, 4)->Unit(benchmark::kMillisecond);

void BM_Register_PclGicp(benchmark::State& state) {
  pcl::GeneralizedIterativeClosestPoint<pcl::PointXYZ, pcl::PointXYZ, double> gicp;
  run_pcl<pcl::PointXYZ>(state, gicp);
}
BENCHMARK(BM_Register_PclGicp)->DenseRange(1, 4)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace vantage::bench
