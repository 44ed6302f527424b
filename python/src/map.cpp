// Bindings of the map: GridSpec, OccupancyGrid, SensorFov, scan integration and OctoMap files.

#include <pybind11/operators.h>
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <cmath>
#include <cstdint>
#include <limits>

#include "bindings.hpp"
#include "convert.hpp"
#include "vantage/io/octomap_io.hpp"
#include "vantage/map/integrate.hpp"
#include "vantage/util/text.hpp"

namespace vantage::python {

namespace {

std::string repr(const GridSpec& s) {
  return cat("GridSpec(origin=(", s.origin.x(), ", ", s.origin.y(), ", ", s.origin.z(),
             "), resolution=", s.resolution, ", dims=(", s.dims.x(), ", ", s.dims.y(), ", ",
             s.dims.z(), "))");
}

Index3 to_index(const std::vector<std::int64_t>& dims, const char* what) {
  if (dims.size() != 3) {
    throw std::invalid_argument(cat(what, " must hold 3 integers, got ", dims.size()));
  }
  // NOTE: a count past an int is a range error (ValueError), not a type error (issue 53).
  for (std::size_t a = 0; a < 3; ++a) {
    if (dims[a] < std::numeric_limits<int>::min() || dims[a] > std::numeric_limits<int>::max()) {
      throw std::invalid_argument(cat(what, "[", a, "] = ", dims[a], " lies past the ",
                                      std::numeric_limits<int>::max(), " cells an axis may have"));
    }
  }
  return {static_cast<int>(dims[0]), static_cast<int>(dims[1]), static_cast<int>(dims[2])};
}

GridSpec make_spec(const DoubleArray& origin, double resolution,
                   const std::vector<std::int64_t>& dims) {
  GridSpec spec;
  spec.origin = to_vector3(origin, "origin");
  spec.resolution = resolution;
  spec.dims = to_index(dims, "dims");
  spec.validate();
  return spec;
}

py::tuple shape_of(const GridSpec& spec) {
  return py::make_tuple(spec.dims.x(), spec.dims.y(), spec.dims.z());
}

/// Per-cell values of a grid as a [i, j, k] array.
template <typename T, typename F>
py::array_t<T> per_cell(const OccupancyGrid& grid, F&& value) {
  py::array_t<T> out = grid_shaped<T>(grid.spec());
  T* data = out.mutable_data();
  for (std::size_t i = 0; i < grid.size(); ++i) data[i] = value(i);
  return out;
}

/// Sets every cell from a [i, j, k] array of probabilities; checks all before changing any.
void set_probabilities(OccupancyGrid& grid, const py::array_t<double, py::array::forcecast>& p) {
  const GridSpec& spec = grid.spec();
  if (p.ndim() != 3 || p.shape(0) != spec.dims.x() || p.shape(1) != spec.dims.y() ||
      p.shape(2) != spec.dims.z()) {
    throw std::invalid_argument(cat("probabilities must have the grid's shape (", spec.dims.x(),
                                    ", ", spec.dims.y(), ", ", spec.dims.z(), ")"));
  }
  const auto r = p.unchecked<3>();
  std::vector<double> values(grid.size());
  for (int k = 0; k < spec.dims.z(); ++k) {
    for (int j = 0; j < spec.dims.y(); ++j) {
      for (int i = 0; i < spec.dims.x(); ++i) {
        const double v = r(i, j, k);
        if (!(v >= 0.0 && v <= 1.0)) {
          throw std::invalid_argument(
              cat("probabilities[", i, ", ", j, ", ", k, "] = ", v, " lies outside [0, 1]"));
        }
        values[spec.linear({i, j, k})] = v;
      }
    }
  }
  for (std::size_t i = 0; i < values.size(); ++i) grid.set_probability(i, values[i]);
}

IntegrationResult integrate(OccupancyGrid& grid, const DoubleArray& points_world,
                            const Eigen::Matrix4d& T_world_sensor, const SensorFov& fov,
                            const std::string& mode, bool hole_filling, int num_threads) {
  IntegrationConfig config;
  config.mode = parse_integration_mode(mode);
  config.hole_filling.enabled = hole_filling;
  config.num_threads = num_threads;
  config.validate();
  Scan scan{to_cloud(points_world, "points_world"),
            Frustum(to_pose(T_world_sensor, "T_world_sensor"), fov)};
  py::gil_scoped_release release;
  return integrate_scan(grid, scan, config);
}

OccupancyGrid load(const std::filesystem::path& path, const std::optional<GridSpec>& spec,
                   int padding, bool crop) {
  OctomapImportConfig config;
  config.grid = spec;
  config.padding = padding;
  config.crop = crop;
  config.check_grid = [&](const GridSpec& grid) {
    check_grid_memory(grid, kOccupancyGridBytesPerCell, cat("the grid of ", path.string()));
  };
  config.validate();
  return with_file(path, false, [&] { return read_octomap(path, config).grid; });
}

py::dict save(const OccupancyGrid& grid, const std::filesystem::path& path) {
  const OctomapExport e = with_file(path, true, [&] { return write_octomap(path, grid); });
  py::dict out;
  out["format"] = std::string(to_string(e.format));
  out["free_cells"] = e.free_cells;
  out["occupied_cells"] = e.occupied_cells;
  out["unobserved_cells"] = e.unobserved_cells;
  out["tree_nodes"] = e.tree_nodes;
  out["spec"] = grid.spec();  // what load(spec=) needs for the same grid: files hold no box
  return out;
}

OccupancyGrid make_grid(const GridSpec& spec, double p_hit, double p_miss, double p_min,
                        double p_max) {
  check_grid_memory(spec, kOccupancyGridBytesPerCell, "an OccupancyGrid");
  return OccupancyGrid(spec, OccupancyParams{p_hit, p_miss, p_min, p_max});
}

py::array_t<double> probabilities(const OccupancyGrid& g) {
  return per_cell<double>(g, [&](std::size_t i) { return g.probability(i); });
}

py::dict counts_of(const OccupancyGrid& g) {
  const CellCounts c = g.counts();
  py::dict out;
  out["unobserved"] = c.unobserved;
  out["free"] = c.free;
  out["occupied"] = c.occupied;
  return out;
}

void def_grid_spec(py::module_& m) {
  py::class_<GridSpec>(m, "GridSpec",
                       "Where a dense grid of cubic cells lies: cell (i, j, k) spans origin + "
                       "(i, j, k) * resolution to the next corner [m].")
      .def(py::init(&make_spec), py::arg("origin"), py::arg("resolution"), py::arg("dims"),
           "A grid with min corner `origin` [m], cell edge `resolution` [m] and `dims` = (nx, ny, "
           "nz) cells. Raises ValueError naming the field when unusable.")
      .def_static(
          "centered",
          [](const DoubleArray& center, double resolution, const std::vector<std::int64_t>& dims) {
            GridSpec spec = GridSpec::centered(to_vector3(center, "center"), resolution,
                                               to_index(dims, "dims"));
            spec.validate();
            return spec;
          },
          py::arg("center"), py::arg("resolution"), py::arg("dims"),
          "A grid of `dims` cells whose box is centred on `center` [m].")
      .def_property_readonly(
          "origin", [](const GridSpec& s) { return Eigen::Vector3d(s.origin); },
          "Min corner of cell (0, 0, 0) [m].")
      .def_property_readonly(
          "resolution", [](const GridSpec& s) { return s.resolution; }, "Cell edge length [m].")
      .def_property_readonly("dims", &shape_of, "Cells along x, y, z.")
      .def_property_readonly("shape", &shape_of, "The same as dims: the shape of grid arrays.")
      .def_property_readonly("num_cells", &GridSpec::num_cells, "Cells in the grid.")
      .def_property_readonly(
          "max_corner", [](const GridSpec& s) { return Eigen::Vector3d(s.max_corner()); },
          "Max corner of the grid's box [m].")
      .def(
          "center",
          [](const GridSpec& s, int i, int j, int k) {
            return Eigen::Vector3d(s.center({i, j, k}));
          },
          py::arg("i"), py::arg("j"), py::arg("k"), "Centre of cell (i, j, k) [m].")
      .def(
          "index_of",
          [](const GridSpec& s, const DoubleArray& p) {
            const Index3 c = s.index_of(to_vector3(p, "point"));
            return py::make_tuple(c.x(), c.y(), c.z());
          },
          py::arg("point"), "Cell (i, j, k) holding a point; IndexError outside the grid.")
      .def(py::self == py::self)
      .def("__repr__", &repr);
}

void def_sensor_fov(py::module_& m) {
  py::class_<SensorFov>(m, "SensorFov",
                        "A depth sensor's field of view: full horizontal and vertical angles "
                        "[rad] and range limits [m]. The sensor looks along +x, +y left, +z up.")
      .def(py::init([](double h_fov, double v_fov, double min_range, double max_range) {
             SensorFov fov{h_fov, v_fov, min_range, max_range};
             fov.validate();
             return fov;
           }),
           py::arg("h_fov") = SensorFov{}.h_fov, py::arg("v_fov") = SensorFov{}.v_fov,
           py::arg("min_range") = SensorFov{}.min_range,
           py::arg("max_range") = SensorFov{}.max_range,
           "Angles in radians, ranges in metres; ValueError naming the field when unusable.")
      .def_static(
          "from_degrees",
          [](double h_deg, double v_deg, double min_range, double max_range) {
            SensorFov fov{deg2rad(h_deg), deg2rad(v_deg), min_range, max_range};
            fov.validate();
            return fov;
          },
          py::arg("h_fov_deg"), py::arg("v_fov_deg"), py::arg("min_range"), py::arg("max_range"),
          "The same with the angles in degrees.")
      .def_readonly("h_fov", &SensorFov::h_fov, "Full horizontal field of view [rad].")
      .def_readonly("v_fov", &SensorFov::v_fov, "Full vertical field of view [rad].")
      .def_readonly("min_range", &SensorFov::min_range, "[m]")
      .def_readonly("max_range", &SensorFov::max_range, "[m]")
      .def(py::self == py::self)
      .def("__repr__", [](const SensorFov& f) {
        return cat("SensorFov(h_fov=", f.h_fov, ", v_fov=", f.v_fov, ", min_range=", f.min_range,
                   ", max_range=", f.max_range, ")");
      });
}

void def_occupancy_grid(py::module_& m) {
  py::class_<OccupancyGrid>(m, "OccupancyGrid",
                            "A dense occupancy grid in log-odds, updated as OctoMap does. Arrays "
                            "it returns have the grid's shape and are indexed [i, j, k].")
      .def(py::init(&make_grid), py::arg("spec"), py::arg("p_hit") = OccupancyParams{}.p_hit,
           py::arg("p_miss") = OccupancyParams{}.p_miss, py::arg("p_min") = OccupancyParams{}.p_min,
           py::arg("p_max") = OccupancyParams{}.p_max,
           "An all-unknown grid (p = 0.5) with OctoMap's hit/miss/clamp probabilities. "
           "MemoryError, before allocating, for a grid larger than the memory available.")
      .def_property_readonly("spec", &OccupancyGrid::spec, "The grid's GridSpec.")
      .def_property_readonly(
          "shape", [](const OccupancyGrid& g) { return shape_of(g.spec()); }, "(nx, ny, nz).")
      .def("probabilities", &probabilities,
           "Occupancy probability of every cell, float64 [i, j, k].")
      .def("log_odds", &log_odds_array, "Stored log-odds of every cell, float32 [i, j, k].")
      .def("states", &state_array,
           "Class of every cell, uint8 [i, j, k]: UNOBSERVED (0.4 < p < 0.6), FREE (p <= 0.4) or "
           "OCCUPIED (p >= 0.6).")
      .def("counts", &counts_of, "Cells in each class: {'unobserved', 'free', 'occupied'}.")
      .def("set_probabilities", &set_probabilities, py::arg("probabilities"),
           "Sets every cell from an array of the grid's shape (clamped as the grid clamps). "
           "ValueError naming the first value outside [0, 1]; the grid is unchanged then.")
      .def("integrate", &integrate, py::arg("points_world"), py::arg("T_world_sensor"),
           py::arg("fov"), py::arg("mode") = "paper", py::arg("hole_filling") = true,
           py::arg("num_threads") = 0,
           "Integrates one scan: an N x 3 array of points in the world [m] seen from the 4 x 4 "
           "sensor pose with field of view `fov`. mode 'paper' (hits, hole filling, unknown-space "
           "estimation) or 'endpoint' (OctoMap's ray casting). ValueError for a non-finite point "
           "or a pose that is not rigid; the grid is unchanged then.")
      .def("save", &save, py::arg("path"),
           "Writes the grid as an OctoMap .bt or .ot file, atomically; returns what it wrote, "
           "with the grid's `spec` to load it back with. OSError when writing fails, ValueError "
           "for another extension.")
      .def_static("load", &load, py::arg("path"), py::arg("spec") = std::nullopt,
                  py::arg("padding") = 0, py::arg("crop") = false,
                  "Reads an OctoMap .bt or .ot file into a grid: into `spec` when given (with "
                  "`crop`, voxels outside it are dropped), else into the smallest box holding "
                  "every known voxel grown by `padding` cells, on OctoMap's lattice through the "
                  "world origin. An OctoMap file holds voxels, not the grid's box: a grid with "
                  "unknown cells at its border, or whose origin is off that lattice, comes back "
                  "the same only with spec= (save() returns it). FileNotFoundError for a missing "
                  "file, OSError for one that cannot be read, ValueError for a malformed one, "
                  "MemoryError (before allocating) for a grid larger than the memory available.")
      .def(
          "copy", [](const OccupancyGrid& g) { return OccupancyGrid(g); }, "An independent copy.")
      .def("__repr__", [](const OccupancyGrid& g) {
        const CellCounts c = g.counts();
        return cat("OccupancyGrid(", repr(g.spec()), ", unobserved=", c.unobserved,
                   ", free=", c.free, ", occupied=", c.occupied, ")");
      });
}

}  // namespace

py::array_t<std::uint8_t> state_array(const OccupancyGrid& grid) {
  return per_cell<std::uint8_t>(
      grid, [&](std::size_t i) { return static_cast<std::uint8_t>(grid.state(i)); });
}

py::array_t<float> log_odds_array(const OccupancyGrid& grid) {
  return per_cell<float>(grid, [&](std::size_t i) { return grid.log_odds(i); });
}

void bind_map(py::module_& m) {
  m.attr("UNOBSERVED") = static_cast<int>(CellState::kUnobserved);
  m.attr("FREE") = static_cast<int>(CellState::kFree);
  m.attr("OCCUPIED") = static_cast<int>(CellState::kOccupied);
  def_grid_spec(m);
  def_sensor_fov(m);
  py::class_<IntegrationResult>(m, "IntegrationResult", "What integrating one scan changed.")
      .def_property_readonly(
          "left_unobserved", [](const IntegrationResult& r) { return r.left_unobserved.size(); },
          "Cells that left the unobserved class: the scan's actual gain [cells].")
      .def_property_readonly(
          "entered_unobserved",
          [](const IntegrationResult& r) { return r.entered_unobserved.size(); },
          "Cells a hit or miss moved back into the unobserved class.")
      .def_readonly("points_inside", &IntegrationResult::points_inside, "Points in the grid.")
      .def_readonly("points_outside", &IntegrationResult::points_outside,
                    "Points outside the grid (their rays still count).")
      .def_readonly("hit_cells", &IntegrationResult::hit_cells, "Distinct cells hit.")
      .def_readonly("filled_cells", &IntegrationResult::filled_cells,
                    "Cells hole filling turned occupied.")
      .def_readonly("missed_cells", &IntegrationResult::missed_cells, "Distinct cells missed.");

  def_occupancy_grid(m);
}

}  // namespace vantage::python
