#pragma once
/// @file
/// PRIVATE to vantage_perception's .cpp files: conversions between Vantage's point clouds and
/// PCL's. It includes PCL headers, so no public header may include it.

#include <pcl/point_cloud.h>
#include <pcl/point_types.h>

#include <string_view>

#include "vantage/map/point_cloud.hpp"
#include "vantage/util/text.hpp"

namespace vantage::perception {

/// The points as a PCL cloud of floats. Throws std::invalid_argument naming `what` and the index
/// of the first point that is not finite as a float.
inline pcl::PointCloud<pcl::PointXYZ>::Ptr to_pcl(const PointCloud& points, std::string_view what) {
  auto cloud = std::make_shared<pcl::PointCloud<pcl::PointXYZ>>();
  cloud->reserve(points.size());
  for (std::size_t i = 0; i < points.size(); ++i) {
    const Eigen::Vector3f p = points[i].cast<float>();
    if (!p.allFinite()) {
      throw std::invalid_argument(cat(what, ": point ", i, " is not finite (", points[i].x(), ", ",
                                      points[i].y(), ", ", points[i].z(), ")"));
    }
    cloud->push_back(pcl::PointXYZ(p.x(), p.y(), p.z()));
  }
  return cloud;
}

}  // namespace vantage::perception
