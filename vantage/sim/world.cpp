#include "vantage/sim/world.hpp"

#include <embree3/rtcore.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <string>
#include <string_view>

#include "vantage/sim/random.hpp"
#include "vantage/util/parallel.hpp"
#include "vantage/util/text.hpp"

namespace vantage::sim {
namespace {

constexpr std::size_t kRayBlock = 2048;  ///< rays per parallel task, a multiple of 16

void on_embree_error(void* user, RTCError code, const char* message) {
  auto* last = static_cast<std::string*>(user);
  *last = cat("Embree error ", static_cast<int>(code), ": ", message != nullptr ? message : "");
}

/// One ray cast against the scene: distance to the first surface within [0, t_max], or a
/// negative number for no hit.
float intersect(RTCScene scene, const Eigen::Vector3f& origin, const Eigen::Vector3f& dir,
                float t_max) {
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  RTCRayHit rh{};
  rh.ray.org_x = origin.x();
  rh.ray.org_y = origin.y();
  rh.ray.org_z = origin.z();
  rh.ray.dir_x = dir.x();
  rh.ray.dir_y = dir.y();
  rh.ray.dir_z = dir.z();
  rh.ray.tnear = 0.0f;
  rh.ray.tfar = t_max;
  rh.ray.time = 0.0f;
  rh.ray.mask = 0xFFFFFFFFu;  // NOTE: Debian's Embree filters by mask; -1 lets every ray hit
  rh.ray.flags = 0;
  rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
  rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
  rtcIntersect1(scene, &context, &rh);
  return rh.hit.geomID == RTC_INVALID_GEOMETRY_ID ? -1.0f : rh.ray.tfar;
}

/// A scan's rays, cast block by block: each ray's point in the sensor frame, with its range
/// noise, into its own slot.
struct ScanRays {
  const std::vector<Eigen::Vector3d>& directions;  ///< in the sensor frame
  Eigen::Matrix3d R;                               ///< the sensor's rotation in the world
  Eigen::Vector3f origin;
  double min_range, max_range;
  bool depth_noise;  ///< the noise is along the depth (an RGB-D camera), else along the ray
  RangeNoise noise;
  std::uint64_t noise_seed;
  // NOTE: per-ray slots, compacted in ray order afterwards, so that the result does not depend
  // on which thread cast which ray.
  std::vector<Eigen::Vector3d> points;
  std::vector<std::uint8_t> valid;

  /// Casts the rays [begin, end).
  void cast(RTCScene scene, std::size_t begin, std::size_t end) {
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    context.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
    // NOTE: packets of 16 neighbouring rays, which Embree traces together; a scan's rays are
    // coherent (row by row), so this is about twice as fast as one ray at a time.
    RTCRayHit16 packet;
    alignas(64) int lanes[16];
    for (std::size_t first = begin; first < end; first += 16) {
      const std::size_t count = std::min<std::size_t>(16, end - first);
      fill(packet, lanes, first, count);
      rtcIntersect16(lanes, scene, &context, &packet);
      for (std::size_t k = 0; k < count; ++k) {
        if (packet.hit.geomID[k] != RTC_INVALID_GEOMETRY_ID) hit(first + k, packet.ray.tfar[k]);
      }
    }
  }

 private:
  /// The packet of rays [first, first + count), its other lanes off.
  void fill(RTCRayHit16& packet, int* lanes, std::size_t first, std::size_t count) const {
    for (std::size_t k = 0; k < 16; ++k) {
      lanes[k] = k < count ? -1 : 0;
      const Eigen::Vector3f d = k < count
                                    ? Eigen::Vector3f((R * directions[first + k]).cast<float>())
                                    : Eigen::Vector3f::UnitX();
      packet.ray.org_x[k] = origin.x();
      packet.ray.org_y[k] = origin.y();
      packet.ray.org_z[k] = origin.z();
      packet.ray.dir_x[k] = d.x();
      packet.ray.dir_y[k] = d.y();
      packet.ray.dir_z[k] = d.z();
      packet.ray.tnear[k] = 0.0f;
      packet.ray.tfar[k] = static_cast<float>(max_range);
      packet.ray.time[k] = 0.0f;
      packet.ray.mask[k] = 0xFFFFFFFFu;  // NOTE: Debian's Embree filters by mask
      packet.ray.id[k] = static_cast<unsigned>(k);
      packet.ray.flags[k] = 0;
      packet.hit.geomID[k] = RTC_INVALID_GEOMETRY_ID;
      packet.hit.instID[0][k] = RTC_INVALID_GEOMETRY_ID;
    }
  }

  /// Ray `i` hit a surface at `tfar`: its point, unless too close or, with noise, out of range.
  void hit(std::size_t i, float tfar) {
    const Eigen::Vector3d& d = directions[i];
    double range = tfar;
    if (range < min_range) return;  // too close: no return
    if (noise.enabled()) {
      const double z = standard_normal(noise_seed, RandomStream::kRange, i);
      if (depth_noise) {
        const double depth = range * d.x();
        range = (depth + noise.sigma_at(depth) * z) / d.x();
      } else {
        range += noise.sigma_at(range) * z;
      }
      if (range < min_range || range > max_range) return;
    }
    points[i] = d * range;
    valid[i] = 1;
  }
};

}  // namespace

struct World::Embree {
  RTCDevice device = nullptr;
  RTCScene scene = nullptr;
  std::string last_error;

  ~Embree() {
    if (scene != nullptr) rtcReleaseScene(scene);
    if (device != nullptr) rtcReleaseDevice(device);
  }
  void check(std::string_view what) const {
    if (!last_error.empty()) throw std::runtime_error(cat(what, ": ", last_error));
  }
};

void WorldConfig::validate() const {
  if (num_threads < 0) {
    throw std::invalid_argument(cat("num_threads must be >= 0 (0 = all cores), got ", num_threads));
  }
}

World::World(Scene scene, const WorldConfig& config)
    : scene_(std::move(scene)), config_(config), embree_(std::make_unique<Embree>()) {
  config_.validate();
  scene_.sensor.validate();
  scene_.pose_noise.validate();
  directions_ = ray_directions(scene_.sensor);

  Embree& e = *embree_;
  e.device = rtcNewDevice("verbose=0");
  if (e.device == nullptr) throw std::runtime_error("Embree: cannot create a device");
  rtcSetDeviceErrorFunction(e.device, on_embree_error, &e.last_error);
  e.scene = rtcNewScene(e.device);
  // NOTE: robust mode keeps rays from slipping through the shared edges of adjacent triangles.
  rtcSetSceneFlags(e.scene, RTC_SCENE_FLAG_ROBUST);
  rtcSetSceneBuildQuality(e.scene, RTC_BUILD_QUALITY_HIGH);
  for (const Shape& shape : scene_.shapes) {
    RTCGeometry geometry = nullptr;
    if (shape.sphere) {
      geometry = rtcNewGeometry(e.device, RTC_GEOMETRY_TYPE_SPHERE_POINT);
      auto* v = static_cast<float*>(rtcSetNewGeometryBuffer(
          geometry, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT4, 4 * sizeof(float), 1));
      v[0] = static_cast<float>(shape.sphere->center.x());
      v[1] = static_cast<float>(shape.sphere->center.y());
      v[2] = static_cast<float>(shape.sphere->center.z());
      v[3] = static_cast<float>(shape.sphere->radius);
    } else {
      const TriangleMesh& mesh = shape.mesh_world;
      mesh.validate(shape.name);
      geometry = rtcNewGeometry(e.device, RTC_GEOMETRY_TYPE_TRIANGLE);
      auto* v = static_cast<float*>(rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_VERTEX, 0,
                                                            RTC_FORMAT_FLOAT3, 3 * sizeof(float),
                                                            mesh.vertices.size()));
      auto* idx = static_cast<unsigned*>(
          rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                                  3 * sizeof(unsigned), mesh.triangles.size()));
      e.check(shape.name);
      for (std::size_t i = 0; i < mesh.vertices.size(); ++i) {
        for (int c = 0; c < 3; ++c) v[3 * i + c] = static_cast<float>(mesh.vertices[i][c]);
      }
      for (std::size_t i = 0; i < mesh.triangles.size(); ++i) {
        for (int c = 0; c < 3; ++c) idx[3 * i + c] = static_cast<unsigned>(mesh.triangles[i][c]);
      }
    }
    rtcCommitGeometry(geometry);
    rtcAttachGeometry(e.scene, geometry);
    rtcReleaseGeometry(geometry);
    e.check(shape.name);
  }
  run_with_threads(config_.num_threads, [&] { rtcCommitScene(e.scene); });
  e.check("building the scene");
}

namespace {

/// How far from the world's origin a ray may start [m]. Embree works in float and aborts on
/// origins beyond ~1.8e18; long before that a float position is meaningless (at 1e5 m its
/// spacing is 8 mm, a table-top cell).
constexpr double kMaxCoordinate = 1e5;

/// Throws std::invalid_argument unless `origin` is finite and within kMaxCoordinate.
void check_origin(const Eigen::Vector3d& origin, std::string_view what) {
  for (int a = 0; a < 3; ++a) {
    if (!(std::abs(origin[a]) <= kMaxCoordinate)) {
      throw std::invalid_argument(cat(what, " ", "xyz"[a], " = ", origin[a],
                                      " m lies outside the simulated world's range of +-",
                                      kMaxCoordinate, " m"));
    }
  }
}

}  // namespace

World::~World() = default;
World::World(World&&) noexcept = default;
World& World::operator=(World&&) noexcept = default;

std::optional<double> World::cast(const Eigen::Vector3d& origin, const Eigen::Vector3d& direction,
                                  double max_range) const {
  const double n = direction.norm();
  if (!(n > 0.0) || !origin.allFinite() || !direction.allFinite() || !(max_range >= 0.0)) {
    throw std::invalid_argument(
        "World::cast needs a finite origin, a non-zero direction and "
        "max_range >= 0");
  }
  check_origin(origin, "ray origin");
  const float t = intersect(embree_->scene, origin.cast<float>(), (direction / n).cast<float>(),
                            static_cast<float>(std::min(max_range, 1e30)));
  if (t < 0.0f) return std::nullopt;
  return static_cast<double>(t);
}

bool World::occluded(const Eigen::Vector3d& origin, const Eigen::Vector3d& direction,
                     double distance) const {
  const double n = direction.norm();
  if (!(n > 0.0) || !origin.allFinite() || !direction.allFinite() || !(distance >= 0.0)) {
    throw std::invalid_argument(
        "World::occluded needs a finite origin, a non-zero direction and distance >= 0");
  }
  check_origin(origin, "ray origin");
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  RTCRay ray{};
  ray.org_x = static_cast<float>(origin.x());
  ray.org_y = static_cast<float>(origin.y());
  ray.org_z = static_cast<float>(origin.z());
  const Eigen::Vector3d d = direction / n;
  ray.dir_x = static_cast<float>(d.x());
  ray.dir_y = static_cast<float>(d.y());
  ray.dir_z = static_cast<float>(d.z());
  ray.tnear = 0.0f;
  ray.tfar = static_cast<float>(std::min(distance, 1e30));
  ray.mask = 0xFFFFFFFFu;
  ray.flags = 0;
  rtcOccluded1(embree_->scene, &context, &ray);
  // NOTE: Embree marks an occluded ray by setting tfar to -inf.
  return ray.tfar < 0.0f;
}

Eigen::Isometry3d World::noisy_pose(const Eigen::Isometry3d& T_world_sensor,
                                    std::uint64_t seed) const {
  const PoseNoise& noise = scene_.pose_noise;
  if (!noise.enabled()) return T_world_sensor;
  const double dx = noise.x * standard_normal(seed, RandomStream::kPose, 0);
  const double dy = noise.y * standard_normal(seed, RandomStream::kPose, 1);
  const double dyaw = noise.yaw * standard_normal(seed, RandomStream::kPose, 2);
  Eigen::Isometry3d T = T_world_sensor;
  T.translation() += Eigen::Vector3d(dx, dy, 0.0);
  T.linear() = Eigen::AngleAxisd(dyaw, Eigen::Vector3d::UnitZ()) * T_world_sensor.linear();
  return T;
}

SimulatedScan World::scan(const Eigen::Isometry3d& T_world_sensor, std::uint64_t seed) const {
  return scan_with(T_world_sensor, noisy_pose(T_world_sensor, seed), scene_.sensor, directions_,
                   seed);
}

SimulatedScan World::scan(const Eigen::Isometry3d& T_world_sensor, const SensorConfig& sensor,
                          std::uint64_t seed) const {
  return scan_with(T_world_sensor, noisy_pose(T_world_sensor, seed), sensor, ray_directions(sensor),
                   seed);
}

SimulatedScan World::scan_with(const Eigen::Isometry3d& T_true, const Eigen::Isometry3d& T_noisy,
                               const SensorConfig& sensor,
                               const std::vector<Eigen::Vector3d>& directions,
                               std::uint64_t noise_seed) const {
  if (!T_true.matrix().allFinite()) throw std::invalid_argument("scan pose must be finite");
  check_origin(T_true.translation(), "scan pose");
  const std::size_t n = directions.size();
  ScanRays rays{directions,
                T_true.linear(),
                T_true.translation().cast<float>(),
                sensor.fov.min_range,
                sensor.fov.max_range,
                sensor.type == SensorType::kRgbd,
                sensor.noise,
                noise_seed,
                std::vector<Eigen::Vector3d>(n),
                std::vector<std::uint8_t>(n, 0)};
  RTCScene scene = embree_->scene;
  run_with_threads(config_.num_threads, [&] {
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, kRayBlock),
                      [&](const tbb::blocked_range<std::size_t>& block) {
                        rays.cast(scene, block.begin(), block.end());
                      });
  });
  SimulatedScan scan;
  scan.T_world_sensor_true = T_true;
  scan.T_world_sensor_noisy = T_noisy;
  scan.fov = sensor.fov;
  scan.rays = n;
  std::size_t count = 0;
  for (const std::uint8_t v : rays.valid) count += v;
  scan.points_sensor.reserve(count);
  for (std::size_t i = 0; i < n; ++i) {
    if (rays.valid[i] != 0) scan.points_sensor.push_back(rays.points[i]);
  }
  return scan;
}

std::vector<Eigen::Isometry3d> World::sweep_poses(const Eigen::Isometry3d& T_world_sensor) const {
  const int steps = scene_.sensor.sweep_steps;
  std::vector<Eigen::Isometry3d> poses;
  poses.reserve(static_cast<std::size_t>(steps));
  for (int k = 0; k < steps; ++k) {
    Eigen::Isometry3d T = T_world_sensor;
    T.linear() = Eigen::AngleAxisd(2.0 * std::numbers::pi * k / steps, Eigen::Vector3d::UnitZ()) *
                 T_world_sensor.linear();
    poses.push_back(T);
  }
  return poses;
}

SimulatedSweep World::sweep(const Eigen::Isometry3d& T_world_sensor, std::uint64_t seed) const {
  SimulatedSweep sweep;
  sweep.T_world_sensor_true = T_world_sensor;
  sweep.T_world_sensor_noisy = noisy_pose(T_world_sensor, seed);
  const std::vector<Eigen::Isometry3d> truth = sweep_poses(T_world_sensor);
  const std::vector<Eigen::Isometry3d> belief = sweep_poses(sweep.T_world_sensor_noisy);
  const Eigen::Isometry3d T_0_world = T_world_sensor.inverse();
  for (std::size_t k = 0; k < truth.size(); ++k) {
    // NOTE: each step draws its range noise from its own stream of the seed.
    SimulatedScan step =
        scan_with(truth[k], belief[k], scene_.sensor, directions_, mix64(seed + k + 1));
    const Eigen::Isometry3d T_0_k = T_0_world * truth[k];
    for (const Eigen::Vector3d& p : step.points_sensor) sweep.points_sensor.push_back(T_0_k * p);
    sweep.steps.push_back(std::move(step));
  }
  return sweep;
}

}  // namespace vantage::sim
