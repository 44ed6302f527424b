#pragma once
/// @file
/// The manifest that describes real data for `vantage plan`: point clouds and their poses, the
/// sensor, the region of interest and the options. The format is documented in docs/manifest.md.
/// This reads and checks the description only; the perception module reads the clouds.

#include <Eigen/Geometry>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "vantage/map/grid_spec.hpp"
#include "vantage/map/integrate.hpp"
#include "vantage/map/point_cloud.hpp"
#include "vantage/views/frustum.hpp"

namespace vantage {

/// The axes of the frame the clouds' points and poses are given in.
enum class CloudFrame {
  kOptical,   ///< camera optical frame: z forward, x right, y down (OpenCV, ROS *_optical_frame,
              ///< TUM)
  kXForward,  ///< x forward, y left, z up (REP 103; Vantage's sensor frame)
};

std::string_view to_string(CloudFrame frame);
/// Parses "optical" or "x_forward"; throws std::invalid_argument naming the value.
CloudFrame parse_cloud_frame(std::string_view name);

/// Rotation that takes Vantage's sensor axes (x forward, y left, z up) into a cloud frame, so
/// that T_world_sensor = T_world_cloud * R_cloud_sensor.
Eigen::Matrix3d R_cloud_sensor(CloudFrame frame);

/// Pinhole intrinsics of a depth camera [pixels].
struct PinholeIntrinsics {
  double fx = 0.0, fy = 0.0;  ///< focal lengths [px]
  double cx = 0.0, cy = 0.0;  ///< principal point [px], pixel centres at integer coordinates
  int width = 0, height = 0;  ///< image size [px]

  /// Throws std::invalid_argument naming the field: positive focal lengths and size, principal
  /// point inside the image.
  void validate() const;
  bool operator==(const PinholeIntrinsics&) const = default;
};

/// The symmetric field of view that lies inside the image: on each axis twice the smaller of the
/// angles from the principal point to the image's two edges (pixel edges at -0.5 and
/// width - 0.5), so that the frustum never claims cells the camera cannot see. For a centred
/// principal point this is 2 atan(width / (2 fx)).
SensorFov fov_from_intrinsics(const PinholeIntrinsics& intrinsics, double min_range,
                              double max_range);

/// How a depth image's raw values map to metres.
struct DepthEncoding {
  double units_per_metre = 1000.0;  ///< [1/m] 1000: millimetres (ROS 16UC1); 5000: TUM RGB-D
  std::uint16_t invalid = 0;        ///< the value of a pixel without depth

  /// Throws std::invalid_argument naming the field: a finite, positive scale.
  void validate() const;
  bool operator==(const DepthEncoding&) const = default;
};

/// How trajectory poses are paired with clouds.
enum class PoseMatch {
  kOrder,      ///< the i-th pose with the i-th cloud; the counts must be equal
  kTimestamp,  ///< each cloud with the pose nearest its stamp, within max_time_difference
};

/// One cloud of the data set.
struct ManifestCloud {
  /// PCD or PLY, or a 16-bit depth PNG (Manifest::depth), resolved against the manifest's folder;
  /// for a recording's frame, the recording and the frame's stamp ("run.bag@1305031102.175304").
  std::filesystem::path file;
  /// A recording's frame: its points, read with the manifest (there is no file of its own).
  std::shared_ptr<const PointCloud> points;
  std::size_t non_finite = 0;  ///< points of a recording's frame dropped as non-finite
  /// Pose of the cloud's frame: points_world = T_world_cloud * points_cloud.
  Eigen::Isometry3d T_world_cloud = Eigen::Isometry3d::Identity();
  /// The same pose with Vantage's sensor axes, for Frustum: T_world_cloud * R_cloud_sensor.
  Eigen::Isometry3d T_world_sensor = Eigen::Isometry3d::Identity();
  std::optional<double> stamp;       ///< [s], when given or used for matching
  bool pose_from_viewpoint = false;  ///< the pose came from the PCD file's VIEWPOINT
  /// No pose was given: with table segmentation on, the pose is estimated from the table when the
  /// cloud is read (perception::estimate_table_pose); the poses above are the identity till then.
  bool pose_from_table = false;
  /// No pose was given for a cloud after the first: its pose is found by registering it to the
  /// map of the clouds before it (frame to model), starting from the previous cloud's pose; the
  /// poses above are the identity till then.
  bool pose_from_registration = false;
};

/// Processing switches the manifest sets.
struct ManifestOptions {
  bool table_segmentation = false;  ///< remove the support plane before integration
  bool icp = false;                 ///< refine each cloud's pose by ICP against the map
  IntegrationMode integration = IntegrationMode::kPaper;
  /// Drop points with a non-finite coordinate instead of failing: organized RGB-D clouds mark
  /// pixels without depth with NaN. Off by default, so a corrupt cloud never passes silently.
  bool skip_non_finite = false;
  /// [m] the world z of the table's top in the table frame a pose from the table is given in.
  double table_height = 0.75;
  bool operator==(const ManifestOptions&) const = default;
};

/// A damaged recording read with `salvage` (issue 53): where the damage lies, and what was kept.
struct RecordingSalvage {
  std::string damage;        ///< what its reader found, in one line, naming the byte
  std::uint64_t offset = 0;  ///< [byte] the first byte of the file that cannot be trusted
  std::size_t frames = 0;    ///< whole frames of the topic before it (before `every`)
  /// The frames of the topic its index counts after them; nothing when the index is lost with the
  /// damage (a file cut short).
  std::optional<std::uint64_t> dropped;
};

/// A checked manifest: plain values, nothing read from the clouds yet.
struct Manifest {
  std::filesystem::path file;  ///< the manifest that was read
  std::vector<ManifestCloud> clouds;
  CloudFrame frame = CloudFrame::kOptical;
  SensorFov fov;                                ///< from `fov_deg` or from `intrinsics`
  std::optional<PinholeIntrinsics> intrinsics;  ///< when the manifest gives them
  /// `sensor.depth`: how the depth images among the clouds encode depth; needed with any (a TUM
  /// RGB-D folder's default: 5000 units a metre, 0 invalid).
  std::optional<DepthEncoding> depth;
  std::optional<std::filesystem::path> tum;        ///< the TUM RGB-D folder the clouds came from
  std::optional<std::filesystem::path> recording;  ///< the bag or MCAP file they came from
  std::optional<RecordingSalvage> salvage;  ///< the recording was damaged and read with salvage
  std::optional<std::filesystem::path> trajectory;  ///< the TUM file the poses came from, if any
  PoseMatch match = PoseMatch::kOrder;
  double max_time_difference = 0.02;  ///< [s], for PoseMatch::kTimestamp
  Eigen::AlignedBox3d roi;            ///< region of interest as given [m]
  /// The smallest box of whole cells on the lattice through the world origin (OctoMap's) that
  /// holds the ROI: origin = floor(min / resolution) * resolution, likewise ceil for the max.
  GridSpec grid;
  ManifestOptions options;
};

/// The grid for a region of interest, by Manifest::grid's rule. Throws std::invalid_argument for
/// an empty or non-finite box, a non-positive resolution or a grid over kMaxGridCells.
GridSpec grid_for_roi(const Eigen::AlignedBox3d& roi, double resolution);

/// What the command line may change in how a manifest is read.
struct ManifestReadOptions {
  /// Of a TUM RGB-D folder (`tum`), take the first frame and every `every`-th after it, in place
  /// of `tum.every`.
  std::optional<int> every = std::nullopt;
  std::optional<std::string> topic =
      std::nullopt;  ///< of a recording (`recording`), in place of its topic
  /// Of a damaged recording, map the whole frames before the damage (Manifest::salvage says what
  /// was dropped) rather than refuse it.
  bool salvage = false;
};

/// Reads and checks a manifest: a YAML file, or a folder holding `manifest.yaml`. When the
/// manifest lists no clouds, every `.pcd` and `.ply` file beside it is taken, sorted by name; with
/// `tum`, the depth frames of a TUM RGB-D folder and their ground-truth poses (io/tum_rgbd.hpp).
/// Every problem throws std::runtime_error with one line "file:line: key: what".
Manifest read_manifest(const std::filesystem::path& path, const ManifestReadOptions& options = {});

/// Writes a manifest that read_manifest reads back to the same clouds, poses (one 4x4 matrix per
/// cloud, never a trajectory), sensor, ROI and options; cloud paths are written relative to the
/// manifest's folder. Atomic. Throws std::invalid_argument for a recording's frame (no file).
void write_manifest(const std::filesystem::path& path, const Manifest& manifest);

}  // namespace vantage
