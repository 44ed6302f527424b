#include "vantage/perception/table_segmentation.hpp"

#include <pcl/ModelCoefficients.h>
#include <pcl/PointIndices.h>
#include <pcl/sample_consensus/method_types.h>
#include <pcl/sample_consensus/model_types.h>
#include <pcl/segmentation/sac_segmentation.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <memory>
#include <optional>
#include <stdexcept>

#include "vantage/perception/detail/pcl_bridge.hpp"
#include "vantage/perception/normals.hpp"
#include "vantage/perception/voxel_filter.hpp"
#include "vantage/util/text.hpp"

namespace vantage::perception {
namespace {

/// One horizontal plane found by RANSAC, with its inliers (indices into the searched cloud).
struct Plane {
  Eigen::Vector4d coefficients;
  std::vector<int> inliers;
  std::size_t points = 0;  ///< the input points its inliers stand for
};

double cross(const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  return a.x() * b.y() - a.y() * b.x();
}

/// Convex hull, counter-clockwise, without collinear points (Andrew's monotone chain).
std::vector<Eigen::Vector2d> convex_hull(std::vector<Eigen::Vector2d> points) {
  std::sort(points.begin(), points.end(), [](const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
    return a.x() < b.x() || (a.x() == b.x() && a.y() < b.y());
  });
  points.erase(std::unique(points.begin(), points.end()), points.end());
  if (points.size() < 3) return points;
  std::vector<Eigen::Vector2d> hull(2 * points.size());
  std::size_t k = 0;
  for (std::size_t i = 0; i < points.size(); ++i) {  // lower chain
    while (k >= 2 && cross(hull[k - 1] - hull[k - 2], points[i] - hull[k - 2]) <= 0) --k;
    hull[k++] = points[i];
  }
  for (std::size_t i = points.size() - 1, lower = k + 1; i-- > 0;) {  // upper chain
    while (k >= lower && cross(hull[k - 1] - hull[k - 2], points[i] - hull[k - 2]) <= 0) --k;
    hull[k++] = points[i];
  }
  hull.resize(k - 1);  // the last point repeats the first
  return hull;
}

/// Whether `p` lies inside the convex counter-clockwise polygon with every edge moved outward
/// by `margin`.
bool inside(const std::vector<Eigen::Vector2d>& hull,
            const std::vector<Eigen::Vector2d>& unit_edges, const Eigen::Vector2d& p,
            double margin) {
  for (std::size_t e = 0; e < hull.size(); ++e) {
    if (cross(unit_edges[e], p - hull[e]) < -margin) return false;
  }
  return true;
}

/// A plane's convex extent: its points projected onto it, counter-clockwise seen from above.
struct Extent {
  Extent(const Eigen::Vector4d& plane, const PointCloud& points)
      : n(plane.head<3>()), d(plane[3]), u(n.unitOrthogonal()), v(n.cross(u)) {
    std::vector<Eigen::Vector2d> projected;
    projected.reserve(points.size());
    for (const Eigen::Vector3d& p : points) projected.emplace_back(u.dot(p), v.dot(p));
    hull = convex_hull(std::move(projected));
    for (std::size_t e = 0; e < hull.size(); ++e) {
      unit_edges.push_back((hull[(e + 1) % hull.size()] - hull[e]).normalized());
    }
  }
  double height(const Eigen::Vector3d& p) const { return n.dot(p) + d; }
  /// Whether `p`, projected, lies inside the hull with every edge moved outward by `margin`.
  bool contains(const Eigen::Vector3d& p, double margin) const {
    return inside(hull, unit_edges, {u.dot(p), v.dot(p)}, margin);
  }
  /// The hull's corners on the plane, in the world frame [m].
  std::vector<Eigen::Vector3d> corners() const {
    // NOTE: (u, v, n) is right-handed with n up, so counter-clockwise in (u, v) is
    // counter-clockwise seen from above.
    std::vector<Eigen::Vector3d> out;
    for (const Eigen::Vector2d& q : hull) out.push_back(q.x() * u + q.y() * v - d * n);
    return out;
  }

  Eigen::Vector3d n;
  double d;
  Eigen::Vector3d u, v;
  std::vector<Eigen::Vector2d> hull, unit_edges;
};

/// `test` of every point, in parallel (each point alone: the same for any thread count).
template <typename Test>
std::vector<char> flag(const PointCloud& points, Test&& test) {
  std::vector<char> out(points.size(), 0);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, points.size(), 4096),
                    [&](const tbb::blocked_range<std::size_t>& range) {
                      for (std::size_t i = range.begin(); i != range.end(); ++i) {
                        out[i] = static_cast<char>(test(points[i]));
                      }
                    });
  return out;
}

/// The least-squares plane of the flagged points (the normal: the covariance's least
/// eigenvector), oriented as `guess`; `guess` itself when fewer than three are flagged.
Eigen::Vector4d fit_plane(const PointCloud& points, const std::vector<char>& flagged,
                          const Eigen::Vector4d& guess) {
  // NOTE: about the guess's point nearest the origin, so that the sums lose no precision.
  const Eigen::Vector3d centre = -guess[3] * guess.head<3>();
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  Eigen::Matrix3d outer = Eigen::Matrix3d::Zero();
  std::size_t count = 0;
  for (std::size_t i = 0; i < points.size(); ++i) {
    if (!flagged[i]) continue;
    const Eigen::Vector3d q = points[i] - centre;
    sum += q;
    outer += q * q.transpose();
    ++count;
  }
  if (count < 3) return guess;
  const Eigen::Vector3d mean = sum / static_cast<double>(count);
  const Eigen::Matrix3d covariance = outer / static_cast<double>(count) - mean * mean.transpose();
  Eigen::Vector3d n =
      Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(covariance).eigenvectors().col(0);
  if (n.dot(guess.head<3>()) < 0.0) n = -n;
  Eigen::Vector4d plane;
  plane << n, -n.dot(mean + centre);
  return plane;
}

/// The search of a cloud's sample for horizontal planes, largest first.
class PlaneSearch {
 public:
  PlaneSearch(const PointCloud& sample, const std::vector<std::size_t>& weight,
              const TableConfig& config)
      : sample_(sample), weight_(weight), config_(config) {}

  /// Whether a plane lies at a table's height (its inliers' mean z within the configured range).
  bool eligible(const Plane& plane) const {
    double z = 0.0;
    for (const int i : plane.inliers) z += sample_[static_cast<std::size_t>(i)].z();
    z /= static_cast<double>(plane.inliers.size());
    return z >= config_.min_table_z && z <= config_.max_table_z;
  }

  /// The planes found, each with the points left by those before it, until RANSAC finds none or
  /// no plane of what remains could outweigh the largest eligible one.
  std::vector<Plane> planes() const {
    // Normals oriented up, toward a viewpoint high above the cloud (only their angle to +z is
    // used).
    Eigen::Vector3d top = Eigen::Vector3d::Zero();
    for (const Eigen::Vector3d& p : sample_) top += p;
    top = top / static_cast<double>(sample_.size()) + Eigen::Vector3d(0.0, 0.0, 1e3);
    const std::vector<Eigen::Vector3d> normals =
        estimate_normals(sample_,
                         {.k_neighbours = config_.normal_neighbours,
                          .radius = config_.normal_radius,
                          .num_threads = config_.num_threads},
                         top);
    const pcl::PointCloud<pcl::PointXYZ>::Ptr cloud = to_pcl(sample_, "segment_table");
    auto pcl_normals = std::make_shared<pcl::PointCloud<pcl::Normal>>();
    auto remaining = std::make_shared<pcl::Indices>();
    const double min_cos = std::cos(config_.max_angle);
    for (std::size_t i = 0; i < normals.size(); ++i) {
      const Eigen::Vector3f n = normals[i].cast<float>();
      pcl_normals->push_back(pcl::Normal(n.x(), n.y(), n.z()));
      // NOTE: only points whose normal is within max_angle of vertical can lie on a horizontal
      // surface; the rest (sides of objects, points without a normal, whose angle PCL would
      // compare as NaN) are left out of the search, which cuts RANSAC's work several times over.
      if (std::abs(normals[i].z()) >= min_cos) remaining->push_back(static_cast<int>(i));
    }
    std::vector<Plane> planes;
    std::size_t most_points = 0;  // of an eligible plane so far
    std::size_t remaining_points = points_of(*remaining);
    // NOTE: once fewer points remain than the largest eligible plane holds, no later plane can
    // beat it, so the search stops: usually after the table, or the floor and then the table.
    for (int k = 0; k < config_.max_planes && remaining->size() >= config_.min_inliers &&
                    remaining_points > most_points;
         ++k) {
      std::optional<Plane> plane = ransac(cloud, pcl_normals, remaining);
      if (!plane) break;
      remaining = outside_slab(*plane, *remaining);
      remaining_points = points_of(*remaining);
      if (eligible(*plane)) most_points = std::max(most_points, plane->points);
      planes.push_back(std::move(*plane));
    }
    return planes;
  }

 private:
  // NOTE: planes are weighed by the input points their sample points stand for, not by the
  // sample points: a coarse sample counts area, and a sparse floor's would outweigh the table.
  std::size_t points_of(const pcl::Indices& indices) const {
    std::size_t n = 0;
    for (const int i : indices) n += weight_[static_cast<std::size_t>(i)];
    return n;
  }

  /// The largest horizontal plane RANSAC finds among `remaining`, or none.
  std::optional<Plane> ransac(const pcl::PointCloud<pcl::PointXYZ>::Ptr& cloud,
                              const pcl::PointCloud<pcl::Normal>::Ptr& normals,
                              const std::shared_ptr<pcl::Indices>& remaining) const {
    // NOTE: constructed with random = false, PCL seeds its sample consensus with the fixed seed
    // 12345, and the default thread count (-1) keeps RANSAC serial: the search is repeatable.
    pcl::SACSegmentationFromNormals<pcl::PointXYZ, pcl::Normal> sac(false);
    sac.setModelType(pcl::SACMODEL_NORMAL_PARALLEL_PLANE);
    sac.setMethodType(pcl::SAC_RANSAC);
    sac.setAxis(Eigen::Vector3f::UnitZ());
    sac.setEpsAngle(config_.max_angle);
    sac.setNormalDistanceWeight(config_.normal_distance_weight);
    sac.setDistanceThreshold(config_.distance_threshold);
    sac.setMaxIterations(config_.max_iterations);
    sac.setOptimizeCoefficients(true);
    sac.setInputCloud(cloud);
    sac.setInputNormals(normals);
    sac.setIndices(remaining);
    pcl::PointIndices inliers;
    pcl::ModelCoefficients coefficients;
    sac.segment(inliers, coefficients);
    if (inliers.indices.size() < config_.min_inliers || coefficients.values.size() != 4) {
      return std::nullopt;
    }
    Plane plane;
    for (int a = 0; a < 4; ++a)
      plane.coefficients[a] = coefficients.values[static_cast<std::size_t>(a)];
    plane.coefficients /= plane.coefficients.head<3>().norm();
    if (plane.coefficients.z() < 0.0) plane.coefficients = -plane.coefficients;
    plane.inliers.assign(inliers.indices.begin(), inliers.indices.end());
    std::sort(plane.inliers.begin(), plane.inliers.end());
    plane.points = points_of(plane.inliers);
    return plane;
  }

  // NOTE: the plane claims its whole slab, not only the inliers whose normals agreed: noisy
  // normals left ~half of a sparse floor behind, which then came back as many small "planes",
  // each costing RANSAC its full max_iterations (2 s instead of 0.2 s).
  std::shared_ptr<pcl::Indices> outside_slab(const Plane& plane,
                                             const pcl::Indices& remaining) const {
    auto rest = std::make_shared<pcl::Indices>();
    for (const int i : remaining) {
      const Eigen::Vector3d& p = sample_[static_cast<std::size_t>(i)];
      if (std::abs(plane.coefficients.head<3>().dot(p) + plane.coefficients[3]) >
          config_.distance_threshold) {
        rest->push_back(i);
      }
    }
    return rest;
  }

  const PointCloud& sample_;
  const std::vector<std::size_t>& weight_;
  const TableConfig& config_;
};

/// The table as the full cloud shows it.
struct TableFit {
  Eigen::Vector4d plane;
  Extent extent;
};

/// The table's plane and extent in the full cloud: the sample's plane and extent first, then the
/// full cloud's points near that plane and within a voxel of that extent (what sampling may have
/// pulled in) refit the plane and widen the extent to where the table's points reach. None when
/// an extent is degenerate.
std::optional<TableFit> fit_table(const PointCloud& points_world, const PointCloud& sample,
                                  const Plane& table, const TableConfig& config) {
  PointCloud sample_inliers;
  for (const int i : table.inliers) sample_inliers.push_back(sample[static_cast<std::size_t>(i)]);
  const Extent coarse(table.coefficients, sample_inliers);
  if (coarse.hull.size() < 3) return std::nullopt;
  // 1: near the plane, inside the sample's hull; 2: near it, outside, but within a voxel.
  const std::vector<char> near = flag(points_world, [&](const Eigen::Vector3d& p) -> char {
    if (std::abs(coarse.height(p)) > config.distance_threshold) return 0;
    if (coarse.contains(p, 0.0)) return 1;
    return coarse.contains(p, config.voxel_size) ? 2 : 0;
  });
  const Eigen::Vector4d plane = fit_plane(points_world, near, table.coefficients);
  for (std::size_t i = 0; i < points_world.size(); ++i) {
    if (near[i] == 2) sample_inliers.push_back(points_world[i]);
  }
  // NOTE: the sample's hull holds every full-cloud point inside it, so the points outside it and
  // its corners give the hull of all the inliers.
  for (const Eigen::Vector3d& corner : coarse.corners()) sample_inliers.push_back(corner);
  const Extent extent(plane, sample_inliers);
  if (extent.hull.size() < 3) return std::nullopt;
  return TableFit{plane, extent};
}

}  // namespace

void TableConfig::validate() const {
  const auto fail = [](const char* field, const char* rule, double value) {
    throw std::invalid_argument(cat("table.", field, " must be ", rule, ", got ", value));
  };
  const auto finite_at_least = [](double v, double low) { return std::isfinite(v) && v >= low; };
  if (!finite_at_least(voxel_size, 0.0)) fail("voxel_size", ">= 0", voxel_size);
  if (normal_neighbours < 0) fail("normal_neighbours", ">= 0", normal_neighbours);
  if (normal_neighbours == 0 && !(normal_radius > 0.0 && std::isfinite(normal_radius))) {
    fail("normal_radius", "> 0 when normal_neighbours is 0", normal_radius);
  }
  if (!(distance_threshold > 0.0 && std::isfinite(distance_threshold))) {
    fail("distance_threshold", "> 0", distance_threshold);
  }
  if (!(max_angle > 0.0 && max_angle < std::numbers::pi / 2)) {
    fail("max_angle", "in (0, pi/2) rad", max_angle);
  }
  if (!(normal_distance_weight >= 0.0 && normal_distance_weight <= 1.0)) {
    fail("normal_distance_weight", "in [0, 1]", normal_distance_weight);
  }
  if (max_iterations < 1) fail("max_iterations", ">= 1", max_iterations);
  if (min_inliers < 3) fail("min_inliers", ">= 3", static_cast<double>(min_inliers));
  if (max_planes < 1) fail("max_planes", ">= 1", max_planes);
  if (std::isnan(min_table_z) || std::isnan(max_table_z) || !(min_table_z <= max_table_z)) {
    fail("max_table_z", ">= table.min_table_z", max_table_z);
  }
  if (!finite_at_least(min_height, 0.0)) fail("min_height", ">= 0", min_height);
  if (!(max_height > min_height && std::isfinite(max_height))) {
    fail("max_height", "> table.min_height", max_height);
  }
  if (!finite_at_least(margin, 0.0)) fail("margin", ">= 0", margin);
  if (num_threads < 0) fail("num_threads", ">= 0", num_threads);
}

TableSegmentation segment_table(const PointCloud& points_world, const TableConfig& config) {
  config.validate();
  for (std::size_t i = 0; i < points_world.size(); ++i) {
    if (!points_world[i].allFinite()) {
      throw std::invalid_argument(cat("segment_table: point ", i, " is not finite"));
    }
  }
  TableSegmentation result;
  std::vector<std::size_t> weight;  // the input points each sample point stands for
  const PointCloud sample = voxel_downsample(points_world, config.voxel_size, &weight);
  if (sample.size() < config.min_inliers) return result;
  const PlaneSearch search(sample, weight, config);
  const std::vector<Plane> planes = search.planes();

  // The table: the eligible plane with the most inliers, the first found on a tie.
  const Plane* table = nullptr;
  for (const Plane& plane : planes) {
    if (search.eligible(plane) && (!table || plane.points > table->points)) {
      table = &plane;
    }
  }
  if (!table) return result;
  const std::optional<TableFit> fit = fit_table(points_world, sample, *table, config);
  if (!fit) return result;
  const Extent& extent = fit->extent;

  result.found = true;
  result.plane = fit->plane;
  result.table_hull = extent.corners();
  const std::vector<char> kind = flag(points_world, [&](const Eigen::Vector3d& p) -> char {
    const double height = extent.height(p);
    const bool near_plane = std::abs(height) <= config.distance_threshold;
    const bool above = height > config.min_height && height <= config.max_height;
    if (!near_plane && !above) return 0;
    if (!extent.contains(p, config.margin)) return 0;
    return near_plane ? 1 : 2;
  });
  for (std::size_t i = 0; i < points_world.size(); ++i) {
    if (kind[i] == 1) ++result.table_inliers;
    if (kind[i] == 2) {
      result.objects.push_back(points_world[i]);
      result.object_indices.push_back(i);
    }
  }
  return result;
}

}  // namespace vantage::perception
