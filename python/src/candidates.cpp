// Bindings of candidate poses: a sensor looking at a point, the ring, the sphere, the registry's
// candidate sets around a region of interest, and the grid `vantage plan` maps that region into.

#include <pybind11/stl.h>

#include <optional>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "bindings.hpp"
#include "convert.hpp"
#include "vantage/io/manifest.hpp"
#include "vantage/util/text.hpp"
#include "vantage/views/candidate_sets.hpp"
#include "vantage/views/ring.hpp"
#include "vantage/views/sphere.hpp"

namespace vantage::python {

namespace {

Eigen::Matrix4d sensor_looking_at(const DoubleArray& eye, const DoubleArray& target) {
  return Eigen::Matrix4d(look_at(to_vector3(eye, "eye"), to_vector3(target, "target")).matrix());
}

py::array_t<double> ring_of(const DoubleArray& center, double radius, double height, int positions,
                            double start_angle, const std::vector<double>& yaw_offsets) {
  RingConfig ring;
  ring.center = to_vector3(center, "center");
  ring.radius = radius;
  ring.height = height;
  ring.positions = positions;
  ring.start_angle = start_angle;
  ring.yaw_offsets = yaw_offsets;
  ring.validate();
  return from_poses(ring_poses(ring));
}

/// A region of interest: a GridSpec's box, or a (min corner, max corner) pair.
Eigen::AlignedBox3d region_of(const py::object& region) {
  if (py::isinstance<GridSpec>(region)) {
    const auto& spec = region.cast<const GridSpec&>();
    return Eigen::AlignedBox3d(spec.origin, spec.max_corner());
  }
  const auto corners = region.cast<std::pair<DoubleArray, DoubleArray>>();
  const Eigen::AlignedBox3d roi(to_vector3(corners.first, "roi[0]"),
                                to_vector3(corners.second, "roi[1]"));
  if (!roi.min().allFinite() || !roi.max().allFinite() ||
      (roi.min().array() > roi.max().array()).any()) {
    throw std::invalid_argument("roi must be (min corner, max corner), min <= max");
  }
  return roi;
}

py::array_t<double> default_ring_of(const py::object& region, std::optional<double> radius,
                                    std::optional<double> height, std::optional<int> positions) {
  RingConfig ring = default_ring(region_of(region));
  if (radius) ring.radius = *radius;
  if (height) ring.height = *height;
  if (positions) ring.positions = *positions;
  ring.validate();
  return from_poses(ring_poses(ring));
}

std::vector<std::pair<std::string, std::string>> candidate_set_names() {
  std::vector<std::pair<std::string, std::string>> sets;
  for (const CandidateSetRow& row : candidate_sets()) {
    sets.emplace_back(std::string(row.name), std::string(row.help));
  }
  return sets;
}

py::array_t<double> candidate_set_views(const std::string& name, const DoubleArray& roi_min,
                                        const DoubleArray& roi_max, double radius, int views,
                                        std::optional<DoubleArray> poses) {
  CandidateSite site;
  site.region = Eigen::AlignedBox3d(to_vector3(roi_min, "roi_min"), to_vector3(roi_max, "roi_max"));
  if (!site.region.min().allFinite() || !site.region.max().allFinite() ||
      (site.region.min().array() > site.region.max().array()).any()) {
    throw std::invalid_argument("roi must be (min corner, max corner), min <= max");
  }
  site.target = site.region.center();
  CandidateParams params;
  params.radius = radius;
  params.views = views;
  if (poses) params.listed = to_poses(*poses, "poses");
  const CandidateSetRow& row = find_candidate_set(name);
  if (row.needs_robot) {
    throw std::invalid_argument(
        cat("candidate set '", name, "' is an office robot's: explore an office with it"));
  }
  if (row.needs_map) {
    throw std::invalid_argument(
        cat("candidate set '", name, "' is found in a map: plan with it (vt.plan)"));
  }
  return from_poses(row.build(site, params).poses);
}

py::array_t<double> sphere_of(const DoubleArray& center, double radius, int views) {
  SphereConfig sphere;
  sphere.center = to_vector3(center, "center");
  sphere.radius = radius;
  sphere.views = views;
  sphere.validate();
  return from_poses(sphere_poses(sphere));
}

GridSpec grid_of_roi(const DoubleArray& roi_min, const DoubleArray& roi_max, double resolution) {
  return grid_for_roi(
      Eigen::AlignedBox3d(to_vector3(roi_min, "roi_min"), to_vector3(roi_max, "roi_max")),
      resolution);
}

}  // namespace

void bind_candidates(py::module_& m) {
  m.def("look_at", &sensor_looking_at, py::arg("eye"), py::arg("target"),
        "4 x 4 pose of a sensor at `eye` looking at `target`, its z axis as close to world +z as "
        "the direction allows [m].");
  m.def("ring_poses", &ring_of, py::arg("center"), py::arg("radius"), py::arg("height"),
        py::arg("positions") = 10, py::arg("start_angle") = 0.0,
        py::arg("yaw_offsets") = RingConfig{}.yaw_offsets,
        "Candidate views on a horizontal circle around `center` (§5.1): `positions` sensor "
        "positions at `height`, each looking at the centre turned by every yaw offset [m, rad]. "
        "Returns a K x 4 x 4 array, view (k, j) at index k * len(yaw_offsets) + j.");
  m.def("ring_candidates", &default_ring_of, py::arg("region"), py::arg("radius") = std::nullopt,
        py::arg("height") = std::nullopt, py::arg("positions") = std::nullopt,
        "The candidates `vantage plan` scores by default (--candidates ring): a ring around "
        "`region`, a GridSpec (its box, as for `plan --map`) or a (min, max) region of interest "
        "(a manifest's roi) [m]; radius 1.5 half-diagonals of its footprint (at least 1 m), 0.3 m "
        "above its top, 10 positions, yaw offsets -15, 0, 15 degrees; radius, height and "
        "positions as `plan --radius --height --views` override them. K x 4 x 4.");
  m.def("candidate_sets", &candidate_set_names,
        "The candidate sets by name, with a line each: the registry `vantage plan --candidates`, "
        "`explore` and `bench` read (views/candidate_sets.hpp).");
  m.def("candidate_views", &candidate_set_views, py::arg("name"), py::arg("roi_min"),
        py::arg("roi_max"), py::arg("radius") = 0.0, py::arg("views") = 0,
        py::arg("poses") = std::nullopt,
        "The views of the candidate set `name` (candidate_sets()) around a region of interest, "
        "as `vantage plan --candidates NAME` places them: radius and views 0 for the set's own "
        "[m]; 'file' takes `poses` (K x 4 x 4). K x 4 x 4.");
  m.def("sphere_poses", &sphere_of, py::arg("center"), py::arg("radius"), py::arg("views") = 50,
        "Candidate views spread over a sphere around `center`, each looking at it [m]; K x 4 x 4.");
  m.def("grid_for_roi", &grid_of_roi, py::arg("roi_min"), py::arg("roi_max"), py::arg("resolution"),
        "The grid `vantage plan` maps a region of interest into: whole cells on the lattice "
        "through the world origin (OctoMap's) that hold the box [m].");
}

}  // namespace vantage::python
