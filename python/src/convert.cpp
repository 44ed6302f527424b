#include "convert.hpp"

#include <sstream>
#include <thread>

#include "vantage/io/format_parsing.hpp"
#include "vantage/io/trajectory.hpp"
#include "vantage/util/text.hpp"

namespace vantage::python {

namespace {

std::string shape_of(const py::array& a) {
  std::ostringstream out;
  out << "(";
  for (py::ssize_t d = 0; d < a.ndim(); ++d) out << (d ? ", " : "") << a.shape(d);
  out << (a.ndim() == 1 ? ",)" : ")");
  return out.str();
}

}  // namespace

PointCloud to_cloud(const DoubleArray& points, const char* what) {
  if (points.ndim() != 2 || points.shape(1) != 3) {
    throw std::invalid_argument(
        cat(what, " must be an N x 3 array of x, y, z, got shape ", shape_of(points)));
  }
  const auto r = points.unchecked<2>();
  PointCloud cloud(static_cast<std::size_t>(r.shape(0)));
  for (py::ssize_t i = 0; i < r.shape(0); ++i) {
    cloud[static_cast<std::size_t>(i)] = {r(i, 0), r(i, 1), r(i, 2)};
  }
  return cloud;
}

py::array_t<double> from_cloud(const PointCloud& cloud) {
  py::array_t<double> out({static_cast<py::ssize_t>(cloud.size()), py::ssize_t{3}});
  auto w = out.mutable_unchecked<2>();
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    for (int c = 0; c < 3; ++c) w(static_cast<py::ssize_t>(i), c) = cloud[i][c];
  }
  return out;
}

Eigen::Isometry3d to_pose(const Eigen::Matrix4d& matrix, const std::string& what) {
  const std::string problem = rigid_transform_problem(matrix);
  if (!problem.empty())
    throw std::invalid_argument(cat(what, " is not a rigid transform: ", problem));
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.linear() = matrix.topLeftCorner<3, 3>();
  pose.translation() = matrix.topRightCorner<3, 1>();
  return pose;
}

std::vector<Eigen::Isometry3d> to_poses(const DoubleArray& poses, const char* what) {
  if (poses.ndim() != 3 || poses.shape(1) != 4 || poses.shape(2) != 4) {
    throw std::invalid_argument(
        cat(what, " must be a K x 4 x 4 array of poses, got shape ", shape_of(poses)));
  }
  const auto r = poses.unchecked<3>();
  std::vector<Eigen::Isometry3d> out;
  for (py::ssize_t k = 0; k < r.shape(0); ++k) {
    Eigen::Matrix4d m;
    for (int i = 0; i < 4; ++i) {
      for (int j = 0; j < 4; ++j) m(i, j) = r(k, i, j);
    }
    out.push_back(to_pose(m, cat(what, "[", k, "]")));
  }
  return out;
}

std::vector<Frustum> to_views(const DoubleArray& poses, const SensorFov& fov, const char* what) {
  std::vector<Frustum> views;
  for (const Eigen::Isometry3d& pose : to_poses(poses, what)) views.emplace_back(pose, fov);
  return views;
}

py::array_t<double> from_poses(const std::vector<Eigen::Isometry3d>& poses) {
  py::array_t<double> out({static_cast<py::ssize_t>(poses.size()), py::ssize_t{4}, py::ssize_t{4}});
  auto w = out.mutable_unchecked<3>();
  for (std::size_t k = 0; k < poses.size(); ++k) {
    const Eigen::Matrix4d m = poses[k].matrix();
    for (int i = 0; i < 4; ++i) {
      for (int j = 0; j < 4; ++j) w(static_cast<py::ssize_t>(k), i, j) = m(i, j);
    }
  }
  return out;
}

Eigen::Vector3d to_vector3(const DoubleArray& values, const char* what) {
  if (values.ndim() != 1 || values.shape(0) != 3) {
    throw std::invalid_argument(cat(what, " must hold 3 numbers, got shape ", shape_of(values)));
  }
  return {values.at(0), values.at(1), values.at(2)};
}

void raise_file_error(const std::filesystem::path& path, const char* message, bool writing) {
  // NOTE: OSError's errno and filename are left unset: with them set, str() would print
  // "[Errno 2] ..." in place of the library's one-line message.
  std::error_code ec;
  if (!writing && !std::filesystem::exists(path, ec)) {
    PyErr_SetString(PyExc_FileNotFoundError, message);
  } else if (writing || !not_a_readable_file(path).empty()) {
    PyErr_SetString(PyExc_OSError, message);
  } else {
    PyErr_SetString(PyExc_ValueError, message);
  }
  throw py::error_already_set();
}

double mapping_cost(int num_threads) {
  return mapping_bytes_per_cell(
      num_threads > 0 ? num_threads : static_cast<int>(std::thread::hardware_concurrency()));
}

WorkBudget& python_budget() {
  // NOTE: Python's one process-wide setting, as numpy's seterr: the calls that allocate a grid
  // or decide take no budget argument each.
  static WorkBudget budget{kDefaultMaxWorkSeconds, 0, "max_work", "max_memory"};
  return budget;
}

void check_grid_memory(const GridSpec& spec, double bytes_per_cell, const std::string& what) {
  check_memory(
      {static_cast<std::uint64_t>(spec.num_cells()), bytes_per_cell, 0.0},
      python_budget().max_bytes,
      cat(what, " of ", spec.dims.x(), " x ", spec.dims.y(), " x ", spec.dims.z(), " cells"),
      python_budget().memory_option);
}

}  // namespace vantage::python
