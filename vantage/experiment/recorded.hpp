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

namespace vantage {

/// The mapping settings a manifest asks for (ICP, table segmentation, integration mode).
MapperConfig mapper_config_for(const Manifest& manifest);

/// Called after each cloud is mapped, with its index.
using CloudCallback = std::function<void(std::size_t index, const MapperUpdate&)>;

/// Maps the manifest's clouds in order into `mapper` (which may already hold a map). Each cloud is
/// read from disk (PCD or PLY), turned from the manifest's cloud frame into the sensor frame and
/// added at its pose. Throws what reading or mapping throws, naming the file.
void map_recorded(const Manifest& manifest, Mapper& mapper, const CloudCallback& on_cloud = {});

/// Candidate poses from a TUM-format file (timestamp x y z qx qy qz qw; the stamp is ignored),
/// whose poses are of frames with the axes `frame` names; returned with the sensor's axes.
std::vector<Eigen::Isometry3d> read_candidate_poses(const std::filesystem::path& path,
                                                    CloudFrame frame);

}  // namespace vantage
