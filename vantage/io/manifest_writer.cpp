// Writing a manifest (manifest.hpp, docs/manifest.md): the reader's counterpart, which
// `vantage scan` and the examples use to hand recorded clouds and their poses to `vantage plan`.

#include <yaml-cpp/yaml.h>

#include <cmath>
#include <filesystem>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <string>

#include "vantage/io/atomic_file.hpp"
#include "vantage/io/manifest.hpp"
#include "vantage/util/text.hpp"

namespace vantage {
namespace fs = std::filesystem;

namespace {

/// `clouds`: each file relative to `folder`, its pose unless it is to be estimated, its stamp.
void emit_clouds(YAML::Emitter& out, const Manifest& manifest, const fs::path& folder) {
  out << YAML::Key << "clouds" << YAML::Value << YAML::BeginSeq;
  for (const ManifestCloud& cloud : manifest.clouds) {
    out << YAML::BeginMap;
    fs::path file = fs::absolute(cloud.file).lexically_relative(folder);
    if (file.empty()) file = fs::absolute(cloud.file);
    out << YAML::Key << "file" << YAML::Value << file.generic_string();
    // NOTE: no pose: read back, it is estimated again (from the table, or by registration).
    if (!cloud.pose_from_table && !cloud.pose_from_registration) {
      out << YAML::Key << "pose" << YAML::Value << YAML::BeginSeq;
      const Eigen::Matrix4d m = cloud.T_world_cloud.matrix();
      for (int r = 0; r < 4; ++r) {
        out << YAML::Flow << YAML::BeginSeq;
        for (int c = 0; c < 4; ++c) out << m(r, c);
        out << YAML::EndSeq;
      }
      out << YAML::EndSeq;
    }
    if (cloud.stamp) out << YAML::Key << "stamp" << YAML::Value << *cloud.stamp;
    out << YAML::EndMap;
  }
  out << YAML::EndSeq;
}

/// `sensor`: the frame, the intrinsics or the field of view, the ranges, the depth encoding.
void emit_sensor(YAML::Emitter& out, const Manifest& manifest) {
  out << YAML::Key << "sensor" << YAML::Value << YAML::BeginMap;
  out << YAML::Key << "frame" << YAML::Value << std::string(to_string(manifest.frame));
  if (manifest.intrinsics) {
    const PinholeIntrinsics& k = *manifest.intrinsics;
    out << YAML::Key << "intrinsics" << YAML::Value << YAML::BeginMap;
    out << YAML::Key << "fx" << YAML::Value << k.fx << YAML::Key << "fy" << YAML::Value << k.fy;
    out << YAML::Key << "cx" << YAML::Value << k.cx << YAML::Key << "cy" << YAML::Value << k.cy;
    out << YAML::Key << "width" << YAML::Value << k.width;
    out << YAML::Key << "height" << YAML::Value << k.height;
    out << YAML::EndMap;
  } else {
    out << YAML::Key << "fov_deg" << YAML::Value << YAML::BeginMap;
    out << YAML::Key << "horizontal" << YAML::Value
        << manifest.fov.h_fov * 180.0 / std::numbers::pi;
    out << YAML::Key << "vertical" << YAML::Value << manifest.fov.v_fov * 180.0 / std::numbers::pi;
    out << YAML::EndMap;
  }
  out << YAML::Key << "min_range" << YAML::Value << manifest.fov.min_range;
  out << YAML::Key << "max_range" << YAML::Value << manifest.fov.max_range;
  if (manifest.depth) {  // NOTE: a TUM folder's clouds are written as the depth images they are
    out << YAML::Key << "depth" << YAML::Value << YAML::Flow << YAML::BeginMap;
    out << YAML::Key << "scale" << YAML::Value << manifest.depth->units_per_metre;
    out << YAML::Key << "invalid" << YAML::Value << static_cast<int>(manifest.depth->invalid);
    out << YAML::EndMap;
  }
  out << YAML::EndMap;
}

/// `roi`, `resolution` and `options`.
void emit_region_and_options(YAML::Emitter& out, const Manifest& manifest) {
  const auto vec = [&](const Eigen::Vector3d& v) {
    out << YAML::Flow << YAML::BeginSeq << v.x() << v.y() << v.z() << YAML::EndSeq;
  };
  out << YAML::Key << "roi" << YAML::Value << YAML::BeginMap;
  out << YAML::Key << "min" << YAML::Value;
  vec(manifest.roi.min());
  out << YAML::Key << "max" << YAML::Value;
  vec(manifest.roi.max());
  out << YAML::EndMap;
  out << YAML::Key << "resolution" << YAML::Value << manifest.grid.resolution;

  out << YAML::Key << "options" << YAML::Value << YAML::BeginMap;
  out << YAML::Key << "table_segmentation" << YAML::Value << manifest.options.table_segmentation;
  out << YAML::Key << "icp" << YAML::Value << manifest.options.icp;
  out << YAML::Key << "integration" << YAML::Value
      << std::string(to_string(manifest.options.integration));
  out << YAML::Key << "skip_non_finite" << YAML::Value << manifest.options.skip_non_finite;
  out << YAML::Key << "table_height" << YAML::Value << manifest.options.table_height;
  out << YAML::EndMap;
}

}  // namespace

void write_manifest(const fs::path& path, const Manifest& manifest) {
  for (const ManifestCloud& cloud : manifest.clouds) {
    if (cloud.points) {
      throw std::invalid_argument(cat(path.string(), ": ", cloud.file.string(),
                                      " is a recording's frame, which has no file to list"));
    }
  }
  YAML::Emitter out;
  out.SetDoublePrecision(std::numeric_limits<double>::max_digits10);
  out << YAML::BeginMap;
  out << YAML::Key << "version" << YAML::Value << 1;
  emit_clouds(out, manifest, fs::absolute(path).parent_path());
  emit_sensor(out, manifest);
  emit_region_and_options(out, manifest);
  out << YAML::EndMap;
  if (!out.good()) throw std::runtime_error(cat(path.string(), ": ", out.GetLastError()));
  write_atomically(path, cat(out.c_str(), "\n"));
}

}  // namespace vantage
