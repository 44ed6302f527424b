#pragma once
/// @file
/// Planning on recorded data: a robot's clouds and poses, described by a manifest
/// (docs/manifest.md), mapped through the same pipeline as the simulated runs.

#include <Eigen/Geometry>
#include <functional>
#include <optional>
#include <vector>

#include "vantage/io/manifest.hpp"
#include "vantage/perception/mapper.hpp"
#include "vantage/perception/table_pose.hpp"

namespace vantage {

/// The mapping settings a manifest asks for (ICP, table segmentation, integration mode).
MapperConfig mapper_config_for(const Manifest& manifest);

/// What mapping one cloud of a manifest did.
struct RecordedCloud {
  std::size_t index = 0;  ///< in the manifest's order
  MapperUpdate update;
  /// The pose estimated from the table, for a cloud without one (ManifestCloud::pose_from_table).
  std::optional<perception::TablePose> table_pose;
  std::size_t non_finite_skipped = 0;  ///< points dropped by options.skip_non_finite
};

/// Called after each cloud is mapped.
using CloudCallback = std::function<void(const RecordedCloud&)>;

/// Maps the manifest's clouds in order into `mapper` (which may already hold a map). Each cloud is
/// read from disk (PCD or PLY), turned from the manifest's cloud frame into the sensor frame and
/// added at its pose; a cloud without a pose gets one from the table it looks at, in the table
/// frame with the table's top at options.table_height (perception::estimate_table_pose); a later
/// cloud without a pose (ManifestCloud::pose_from_registration) is registered to the map so far,
/// starting from the pose the cloud before it was mapped at (PoseGuess::kPreviousScan). Throws
/// what reading or mapping throws, naming the file and the cloud's number; std::runtime_error so
/// when a cloud without a pose shows no table or does not register, and when a cloud holds a
/// non-finite point (pointing to options.skip_non_finite).
void map_recorded(const Manifest& manifest, Mapper& mapper, const CloudCallback& on_cloud = {});

/// Candidate poses from a TUM-format file (timestamp x y z qx qy qz qw; the stamp is ignored),
/// whose poses are of frames with the axes `frame` names; returned with the sensor's axes.
std::vector<Eigen::Isometry3d> read_candidate_poses(const std::filesystem::path& path,
                                                    CloudFrame frame);

}  // namespace vantage
