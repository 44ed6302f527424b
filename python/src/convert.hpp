#pragma once
/// @file
/// What the binding files share: numpy <-> Vantage value conversions, checks of poses, and the
/// mapping of file errors to Python's OSError.

#include <pybind11/eigen.h>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <Eigen/Geometry>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

#include "vantage/map/grid_spec.hpp"
#include "vantage/map/point_cloud.hpp"
#include "vantage/util/memory.hpp"
#include "vantage/util/work.hpp"
#include "vantage/views/frustum.hpp"

namespace vantage::python {

namespace py = pybind11;

/// A C-ordered array of doubles, converted from whatever numpy can convert.
using DoubleArray = py::array_t<double, py::array::c_style | py::array::forcecast>;

/// An N x 3 array as a point cloud; throws std::invalid_argument naming `what` and the shape
/// when it is not N x 3. Non-finite points pass: the library names them where it checks them.
PointCloud to_cloud(const DoubleArray& points, const char* what);

/// A point cloud as an N x 3 array [m].
py::array_t<double> from_cloud(const PointCloud& cloud);

/// A 4 x 4 rigid transform; throws std::invalid_argument naming `what` when the matrix is not
/// rigid (not finite, bottom row not [0 0 0 1], rotation not orthonormal or a reflection).
Eigen::Isometry3d to_pose(const Eigen::Matrix4d& matrix, const std::string& what);

/// A K x 4 x 4 array (or a list of 4 x 4 matrices) as poses; pose k is named `what[k]`.
std::vector<Eigen::Isometry3d> to_poses(const DoubleArray& poses, const char* what);

/// Frusta of K x 4 x 4 sensor poses with one field of view; pose k is named `what[k]`.
std::vector<Frustum> to_views(const DoubleArray& poses, const SensorFov& fov, const char* what);

/// Poses as a K x 4 x 4 array.
py::array_t<double> from_poses(const std::vector<Eigen::Isometry3d>& poses);

/// A vector of 3 numbers; throws std::invalid_argument naming `what` otherwise.
Eigen::Vector3d to_vector3(const DoubleArray& values, const char* what);

/// An array of shape `spec.dims`, indexed [i, j, k], whose data holds one value per cell in
/// the grid's linear order (x fastest), to be filled.
template <typename T>
py::array_t<T> grid_shaped(const GridSpec& spec) {
  const auto nx = static_cast<py::ssize_t>(spec.dims.x());
  const auto ny = static_cast<py::ssize_t>(spec.dims.y());
  const auto nz = static_cast<py::ssize_t>(spec.dims.z());
  const auto s = static_cast<py::ssize_t>(sizeof(T));
  // NOTE: x runs fastest in memory, so the [i, j, k] array is Fortran-ordered: no reordering.
  return py::array_t<T>({nx, ny, nz}, {s, s * nx, s * nx * ny});
}

/// Raises the Python error a file's std::runtime_error stands for, with `message`:
/// FileNotFoundError when `path` does not exist, OSError when `writing` or when it is no
/// readable file (a folder, a FIFO, no permission), ValueError otherwise (its content is
/// malformed: bad input, as a bad argument is).
[[noreturn]] void raise_file_error(const std::filesystem::path& path, const char* message,
                                   bool writing);

/// Calls `f`, turning a std::runtime_error about `path` into the Python error raise_file_error
/// says; the memory budget's refusal stays a MemoryError. The message stays the library's one
/// line.
template <typename F>
auto with_file(const std::filesystem::path& path, bool writing, F&& f) {
  try {
    return f();
  } catch (const std::invalid_argument&) {
    throw;
  } catch (const MemoryBudgetError&) {
    throw;
  } catch (const std::runtime_error& e) {
    raise_file_error(path, e.what(), writing);
  }
}

/// The budget every call is checked against, as the CLI's --max-memory and --max-work
/// (vt.set_budget; docs/robustness.md, "Work"): one per process, the defaults until set.
WorkBudget& python_budget();

/// What a Mapper's or a plan's grid costs a cell on `num_threads` threads (0: every core).
double mapping_cost(int num_threads);

/// Refuses (MemoryBudgetError, Python's MemoryError) a grid of `spec` at `bytes_per_cell` that
/// the memory available now cannot hold, before it is allocated; `what` names it.
void check_grid_memory(const GridSpec& spec, double bytes_per_cell, const std::string& what);

}  // namespace vantage::python
