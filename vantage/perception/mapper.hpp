#pragma once
/// @file
/// From scans to the map, as the paper's §4.1 chains it: keep the objects above the table
/// (§5.1), register them to the objects mapped so far (§4.2; the paper's ICP, here point to
/// plane weighed against the odometry), and integrate them into the occupancy grid (§4.3, §4.4).
/// `vantage explore` and `vantage plan` both map through this; a scan is one view (a table top) or
/// several taken from one place (an office stop's 360° sweep).

#include <Eigen/Geometry>
#include <cstddef>
#include <optional>
#include <span>
#include <stdexcept>
#include <vector>

#include "vantage/map/integrate.hpp"
#include "vantage/map/occupancy_grid.hpp"
#include "vantage/map/point_cloud.hpp"
#include "vantage/perception/registration.hpp"
#include "vantage/perception/table_segmentation.hpp"
#include "vantage/views/frustum.hpp"

namespace vantage {

/// Settings of the mapping pipeline.
struct MapperConfig {
  OccupancyParams occupancy;
  IntegrationConfig integration;
  /// Register each scan after the first to the map of the registered objects so far, weighed
  /// against its believed pose (perception/registration.hpp).
  bool register_scans = true;
  perception::RegistrationConfig registration;
  /// The registration's reference: the objects of the first scan and of every scan whose
  /// registration passed the check (a scan left at its guess would shift its part of the map,
  /// and every later scan with it).
  perception::VoxelMapConfig map;
  /// Thin every scan to one point per map cell (the centroid of the cell's points) before it is
  /// registered and integrated. Paper-mode integration gives a cell one hit however many points
  /// it holds, so the map is the same; registration and the clouds kept get far smaller (an
  /// office sweep: 1.5M points).
  bool thin_to_cells = false;
  /// Register only the scan's points that land, under the guess, in cells the map has already
  /// observed: a scan's points in unexplored space would pair with the edge of the explored part
  /// and drag the pose towards it (an office sweep).
  bool register_overlap_only = false;
  bool segment_table = false;  ///< integrate (and register) only the points above the table
  perception::TableConfig table;
  /// Keep every integrated point (object_cloud()). Off, memory stays bounded by the grid however
  /// many clouds come (vantage plan over a long recording); the registration's reference is
  /// thinned to one point per voxel either way.
  bool keep_object_cloud = true;
  /// A scan whose registration fell back to its guess is registered again each time a later
  /// scan joins the reference, for this many later scans. When it then passes the check, the
  /// grid is rebuilt from a checkpoint taken before it, with it and every scan since integrated
  /// at their registered poses: the far side of a table, which shares almost nothing with the
  /// near side, is pinned once a view from in between has been mapped. 0: a fallback is final.
  /// The checkpoint is a copy of the grid, held while a scan is pending; a retry that passes
  /// integrates again every scan since it. The default covers a table-top run (8 to 10 scans).
  int reregister_window = 8;
  /// The prior of a scan without a pose of its own (PoseGuess::kPreviousScan), whose guess is
  /// where the scan before it was: how far a hand-held sensor may have moved between two frames
  /// of a sequence, in any direction. Its registration is weighed against this and checked by it
  /// (RegistrationConfig's check, with this prior in place of registration.prior).
  perception::PoseSigma unposed_prior{
      .x = 0.05, .y = 0.05, .z = 0.05, .roll = 0.0873, .pitch = 0.0873, .yaw = 0.0873};

  /// Throws std::invalid_argument naming the field.
  void validate() const;
};

/// Where a scan's pose guess comes from.
enum class PoseGuess {
  kOdometry,  ///< the robot's estimate: registration refines it, or the scan keeps it
  /// No pose: the guess is the previous scan's pose. Registration (MapperConfig::unposed_prior)
  /// must pass its check, or the scan is refused with RegistrationFailed and the map unchanged.
  kPreviousScan,
};

/// A scan without a pose of its own did not register to the map: what the check found.
struct RegistrationFailed : std::runtime_error {
  using std::runtime_error::runtime_error;
};

/// One view of a scan: a table-top scan has one, an office stop's sweep one per step.
struct ScanPart {
  PointCloud points_sensor;  ///< in this view's sensor frame [m]
  /// This view's sensor in the scan's frame (the first view's sensor): the known pan of a sweep.
  Eigen::Isometry3d T_scan_sensor = Eigen::Isometry3d::Identity();
  SensorFov fov;
};

/// What adding one scan did.
struct MapperUpdate {
  Eigen::Isometry3d T_world_sensor_guess = Eigen::Isometry3d::Identity();  ///< as given
  Eigen::Isometry3d T_world_sensor = Eigen::Isometry3d::Identity();        ///< used for integration
  bool registered = false;  ///< registration ran and its correction passed the check
  /// Registration's outcome (kEmptyMap also when it is off or had no points).
  perception::RegistrationOutcome registration = perception::RegistrationOutcome::kEmptyMap;
  /// What registration found: the solved pose whether or not it passed, the posterior's sigma,
  /// the pairs; default (kEmptyMap) when it did not run.
  perception::RegistrationResult registration_result;
  std::size_t points = 0;          ///< points in the scan
  std::size_t object_points = 0;   ///< points integrated (after thinning and table segmentation)
  std::size_t thinned_points = 0;  ///< points left by thinning, before table segmentation
  /// Views whose table segmentation found the table (segmentation on); a view without one
  /// integrates no points.
  std::size_t table_views = 0;
  /// Where the points integrated lie, in the scan's frame (the first view's sensor): with the
  /// true pose, how far a pose error moved what went into the map (perception::pose_error).
  perception::PointSpread object_spread;
  /// Cells that left or re-entered the unobserved set; over the parts of a scan, each cell
  /// counts once, by its net change.
  IntegrationResult integration;
  /// Earlier scans that fell back and now passed the check against the reference this scan
  /// grew; the grid was rebuilt with them at these poses before this scan was integrated.
  struct Reregistered {
    std::size_t scan = 0;  ///< 0-based, in the order add_scan took them
    Eigen::Isometry3d T_world_sensor = Eigen::Isometry3d::Identity();
  };
  std::vector<Reregistered> reregistered;
  double seconds_register = 0.0;  ///< registration, and the retries of earlier scans
  double seconds_segment = 0.0;
  double seconds_integrate = 0.0;  ///< integration, and the grid's rebuild after a retry
};

/// Builds the map scan by scan. The first scan's pose defines the map frame as given; every later
/// one is segmented at its believed pose, registered to the voxel map of the objects registered
/// so far (when enabled), and integrated at the pose registration kept.
class Mapper {
 public:
  /// Validates both; throws std::invalid_argument naming the field.
  Mapper(const GridSpec& grid, const MapperConfig& config);
  /// Continues an existing map (e.g. one read from OctoMap); its own occupancy parameters stay.
  Mapper(OccupancyGrid grid, const MapperConfig& config);

  /// Registers, segments and integrates one scan of points in the sensor frame, taken from the
  /// believed pose `T_world_sensor_guess` with field of view `fov`. Throws std::invalid_argument
  /// for a non-finite point or pose, and RegistrationFailed for a scan of PoseGuess::kPreviousScan
  /// that does not register (or comes first, or with register_scans off); the map is unchanged
  /// then.
  MapperUpdate add_scan(const PointCloud& points_sensor,
                        const Eigen::Isometry3d& T_world_sensor_guess, const SensorFov& fov,
                        PoseGuess guess = PoseGuess::kOdometry);
  /// The same for a scan of several views from one place (e.g. a 360° sweep), registered as a
  /// whole (all views at once, well constrained) and integrated view by view.
  /// `T_world_sensor_guess` is the believed pose of the scan's frame.
  MapperUpdate add_scan(std::span<const ScanPart> parts,
                        const Eigen::Isometry3d& T_world_sensor_guess,
                        PoseGuess guess = PoseGuess::kOdometry);

  const OccupancyGrid& grid() const { return grid_; }
  const MapperConfig& config() const { return config_; }
  /// The reference of the next registration: the registered objects, one point per voxel.
  const perception::VoxelMap& reference() const { return reference_; }
  /// The registered points that went into the grid (world frame): the objects; empty when
  /// MapperConfig::keep_object_cloud is off.
  const PointCloud& object_cloud() const { return objects_; }
  std::size_t scans() const { return scans_; }
  /// Scans still left at their guess that a later scan may yet pin (reregister_window).
  std::size_t pending() const;

 private:
  /// A scan since the checkpoint, as it was integrated.
  struct HeldScan {
    std::size_t index = 0;
    std::vector<ScanPart> parts;  ///< what was integrated of each view, in its sensor frame
    Eigen::Isometry3d T_world_sensor_guess = Eigen::Isometry3d::Identity();
    Eigen::Isometry3d T_world_sensor = Eigen::Isometry3d::Identity();
    bool trusted = false;
  };

  /// Places `scan`: the first scan as given, a later one by registration (refused when it has
  /// no pose and does not register); a trusted scan grows the reference, and may pin the
  /// pending ones.
  void place(HeldScan& scan, bool unposed, MapperUpdate& update);
  /// Integrates `scan`, holding it while a scan is pending (from a checkpoint before the first),
  /// and lets the pending scans go once the window has passed them.
  void keep(HeldScan scan, MapperUpdate& update);
  /// Registers `scan`'s objects to the reference, starting from its guess under `prior`; with
  /// register_overlap_only, only those in cells `known` has observed.
  perception::RegistrationResult register_held(const HeldScan& scan, const OccupancyGrid& known,
                                               const perception::PoseSigma& prior) const;
  /// `scan`'s objects in the world, at its pose.
  PointCloud world_points(const HeldScan& scan) const;
  /// Integrates `scan`'s views at its pose; each cell's change counts once, by its net.
  IntegrationResult integrate(const HeldScan& scan);
  /// Registers the held scans that fell back against the reference again; rebuilds the grid
  /// from the checkpoint when one passes. Returns those that passed; adds the time taken.
  std::vector<MapperUpdate::Reregistered> retry_pending(double& seconds_register,
                                                        double& seconds_integrate);

  MapperConfig config_;
  OccupancyGrid grid_;
  perception::VoxelMap reference_;
  PointCloud objects_;
  std::size_t scans_ = 0;
  /// The grid (and the object cloud's size) before the oldest scan still pending, and every scan
  /// since; empty while no scan is pending.
  std::optional<OccupancyGrid> checkpoint_;
  std::size_t checkpoint_objects_ = 0;
  std::vector<HeldScan> held_;
};

}  // namespace vantage
