// The poses of a manifest's clouds: a trajectory matched by order or by time stamp, or a pose per
// cloud (its own matrix, as read, its PCD's VIEWPOINT, the table, registration).

#include <algorithm>
#include <charconv>
#include <cmath>
#include <iterator>
#include <string>
#include <system_error>
#include <vector>

#include "vantage/io/cloud_io.hpp"
#include "vantage/io/detail/manifest_sources.hpp"
#include "vantage/io/input_file.hpp"
#include "vantage/io/trajectory.hpp"
#include "vantage/util/text.hpp"

namespace vantage::detail {
namespace fs = std::filesystem;
namespace {

// 4 rows of 4 numbers, or 16 numbers row by row; then checked to be rigid.
Eigen::Isometry3d rigid(const YamlField& f) {
  Eigen::Matrix4d m;
  if (f.is_sequence() && f.size() == 4 && f[0].is_sequence()) {
    for (std::size_t r = 0; r < 4; ++r) {
      const YamlField row = f[r];
      if (!row.is_sequence() || row.size() != 4) row.fail("must be a row of 4 numbers");
      for (std::size_t c = 0; c < 4; ++c) {
        m(static_cast<int>(r), static_cast<int>(c)) = row[c].number();
      }
    }
  } else if (f.is_sequence() && f.size() == 16) {
    for (std::size_t k = 0; k < 16; ++k) {
      m(static_cast<int>(k / 4), static_cast<int>(k % 4)) = f[k].number();
    }
  } else {
    f.fail("must be a 4x4 matrix: 4 rows of 4 numbers, or 16 numbers row by row");
  }
  const std::string problem = rigid_transform_problem(m);
  if (!problem.empty()) f.fail(cat("not a rigid transform: ", problem));
  Eigen::Isometry3d T;
  T.matrix() = m;
  return T;
}

// The stamp a cloud is matched by: its `stamp`, else its file name if that is a number.
std::optional<double> stamp_from_name(const fs::path& file) {
  const std::string stem = file.stem().string();
  double value = 0.0;
  const auto [ptr, ec] = std::from_chars(stem.data(), stem.data() + stem.size(), value);
  if (ec != std::errc() || ptr != stem.data() + stem.size() || !std::isfinite(value)) {
    return std::nullopt;
  }
  return value;
}

/// `match: order`: the trajectory's poses, one to one with the clouds.
void match_by_order(const YamlField& trajectory, const std::vector<StampedPose>& poses,
                    Manifest& manifest) {
  const std::string traj = manifest.trajectory->filename().string();
  if (poses.size() != manifest.clouds.size()) {
    trajectory.fail(cat(traj, " holds ", poses.size(), " poses but there are ",
                        manifest.clouds.size(), " clouds (match: order pairs them one to one)"));
  }
  for (std::size_t i = 0; i < poses.size(); ++i) {
    manifest.clouds[i].T_world_cloud = poses[i].T_world_frame;
  }
}

/// `match: timestamp`: each cloud the pose nearest its stamp, within max_time_difference.
void match_by_stamp(const YamlField& root, const YamlField& trajectory,
                    const std::vector<StampedPose>& poses, const ManifestEntries& clouds,
                    Manifest& manifest) {
  const std::string traj = manifest.trajectory->filename().string();
  if (poses.empty()) trajectory.fail(cat(traj, " holds no poses"));
  for (std::size_t i = 1; i < poses.size(); ++i) {
    if (!(poses[i].stamp > poses[i - 1].stamp)) {
      trajectory.fail(cat(traj, ": time stamps must increase for match: timestamp (pose ", i,
                          " at ", poses[i].stamp, " s follows ", poses[i - 1].stamp, " s)"));
    }
  }
  for (std::size_t i = 0; i < manifest.clouds.size(); ++i) {
    ManifestCloud& cloud = manifest.clouds[i];
    const std::string key = cat("clouds[", i, "]");
    if (!cloud.stamp) cloud.stamp = stamp_from_name(cloud.file);
    if (!cloud.stamp) {
      clouds.at(i, root).fail_as(key, cat("no stamp to match the trajectory by: give ", key,
                                          ".stamp, or name the file by its time stamp (",
                                          cloud.file.filename().string(), ")"));
    }
    const double t = *cloud.stamp;
    // Nearest pose in time; ties go to the earlier pose.
    const auto after =
        std::lower_bound(poses.begin(), poses.end(), t,
                         [](const StampedPose& p, double stamp) { return p.stamp < stamp; });
    auto best = after == poses.end() ? std::prev(after) : after;
    if (after != poses.begin() &&
        (after == poses.end() || t - std::prev(after)->stamp <= after->stamp - t)) {
      best = std::prev(after);
    }
    const double dt = std::abs(best->stamp - t);
    if (dt > manifest.max_time_difference) {
      clouds.at(i, trajectory)
          .fail_as(key, cat("no pose in ", traj, " within ", manifest.max_time_difference,
                            " s of stamp ", t, " (the nearest is ", dt, " s away)"));
    }
    cloud.T_world_cloud = best->T_world_frame;
  }
}

/// The `trajectory` key ({file, match, max_time_difference}): every cloud's pose from a TUM
/// trajectory file.
void read_trajectory(const YamlField& root, const YamlField& trajectory,
                     const ManifestEntries& clouds, Manifest& manifest) {
  trajectory.allow_keys({"file", "match", "max_time_difference"});
  for (const std::optional<YamlField>& entry : clouds.entries) {
    if (entry && entry->has("pose")) {
      entry->at("pose").fail("give poses per cloud or a trajectory, not both");
    }
  }
  const YamlField file = trajectory.at("file");
  manifest.trajectory = (manifest.file.parent_path() / file.text()).lexically_normal();
  if (const auto match = trajectory.get("match")) {
    const std::string name = match->text();
    if (name == "order") {
      manifest.match = PoseMatch::kOrder;
    } else if (name == "timestamp") {
      manifest.match = PoseMatch::kTimestamp;
    } else {
      match->fail(cat("unknown '", name, "' (expected order or timestamp)"));
    }
  }
  if (const auto dt = trajectory.get("max_time_difference")) {
    manifest.max_time_difference = dt->positive();
  }
  if (const std::string why = input_file_problem(*manifest.trajectory, InputKind::kPoses);
      !why.empty()) {
    file.fail(cat(manifest.trajectory->string(), ": ", why));
  }
  const std::vector<StampedPose> poses = read_tum_trajectory(*manifest.trajectory);
  if (manifest.match == PoseMatch::kOrder) {
    match_by_order(trajectory, poses, manifest);
  } else {
    match_by_stamp(root, trajectory, poses, clouds, manifest);
  }
}

/// Without a trajectory: each cloud as read, by its `pose`, by its PCD's VIEWPOINT, or else the
/// first from the table and a later one by registration.
void pose_each_cloud(const YamlField& root, const ManifestEntries& clouds, Manifest& manifest) {
  for (std::size_t i = 0; i < manifest.clouds.size(); ++i) {
    ManifestCloud& cloud = manifest.clouds[i];
    const std::string key = cat("clouds[", i, "].pose");
    cloud.pose_from_registration = false;
    if (clouds.posed[i]) continue;
    if (clouds.entries[i] && clouds.entries[i]->has("pose")) {
      cloud.T_world_cloud = rigid(clouds.entries[i]->at("pose"));
      continue;
    }
    // A PCD file may carry its own pose (VIEWPOINT), as PCL and strands' nbv_planning record it.
    const std::optional<Eigen::Isometry3d> viewpoint =
        lower_extension(cloud.file) == ".png" || cloud.points ? std::nullopt
                                                              : read_cloud_viewpoint(cloud.file);
    const std::string name = cloud.file.filename().string();
    // NOTE: only the first cloud defines the world (a pose from the table would define it
    // again, and disagree); each later cloud without a pose is registered to the map so far.
    if (!viewpoint && i > 0) {
      cloud.pose_from_registration = true;
      continue;
    }
    if (!viewpoint && manifest.options.table_segmentation) {
      cloud.pose_from_table = true;
      continue;
    }
    if (!viewpoint) {
      clouds.at(i, root).fail_as(
          key, cat("missing: the first cloud ", name,
                   " has no pose (give it a pose, a trajectory, a "
                   "VIEWPOINT other than the identity in the PCD file, or "
                   "options.table_segmentation: true for a pose from the table)"));
    }
    cloud.T_world_cloud = *viewpoint;
    cloud.pose_from_viewpoint = true;
  }
}

}  // namespace

void read_poses(const YamlField& root, const ManifestEntries& clouds, Manifest& manifest) {
  if (const auto trajectory = root.get("trajectory")) {
    read_trajectory(root, *trajectory, clouds, manifest);
  } else {
    pose_each_cloud(root, clouds, manifest);
  }
}

}  // namespace vantage::detail
