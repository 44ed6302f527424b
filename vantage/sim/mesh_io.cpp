#include "vantage/sim/mesh_io.hpp"

#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include <algorithm>
#include <assimp/Importer.hpp>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <new>
#include <optional>
#include <span>
#include <stdexcept>
#include <string>
#include <string_view>
#include <type_traits>

#include "vantage/io/format_parsing.hpp"
#include "vantage/io/input_file.hpp"
#include "vantage/io/ply.hpp"
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

std::string read_text(const std::filesystem::path& path,
                      std::size_t max_bytes = std::string::npos) {
  try {
    return read_input_file(path, InputKind::kMesh, max_bytes);
  } catch (const FormatError& e) {
    throw std::runtime_error(cat("mesh file ", path.string(), ": ", e.what()));
  }
}

bool has_extension(const std::filesystem::path& path, std::string_view ext) {
  return lower_extension(path) == ext;
}

/// The mesh formats load_mesh reads, by extension, and what sniff_format calls their content.
struct MeshFormat {
  std::string_view extension;
  std::string_view content;
};
constexpr MeshFormat kMeshFormats[] = {
    {".ply", "a PLY file"}, {".obj", "OBJ text"}, {".off", "an OFF mesh"}, {".stl", "ASCII STL"}};

/// Throws unless the extension is a mesh format's and the first bytes, where they name a format,
/// name that one: assimp would read OBJ text in `m.xyz` (it sniffs what it does not know), and an
/// extension that lies is a mistake to say, not to guess past.
void require_mesh_format(const std::filesystem::path& path) {
  const std::string extension = lower_extension(path);
  const MeshFormat* format = nullptr;
  for (const MeshFormat& f : kMeshFormats) {
    if (f.extension == extension) format = &f;
  }
  if (format == nullptr) {
    throw std::runtime_error(cat("mesh file ", path.string(), ": '", printable(extension, 20),
                                 "' is not a mesh format vantage reads (.ply, .obj, .off, .stl)"));
  }
  const std::string head = read_text(path, 4096);
  const std::string_view content = sniff_format(head);
  if (!content.empty() && content != format->content) {
    throw std::runtime_error(cat("mesh file ", path.string(), " holds ", content, ", not what its ",
                                 format->extension, " extension says"));
  }
  // NOTE: an ASCII STL cut short was said as assimp's "Cannot parse string \"\" as a real
  // number" (issue 53); a binary STL may begin with "solid" too, and is told by its size.
  if (format->extension == ".stl" && head.find_first_not_of(" \t\r\n") != std::string::npos &&
      std::string_view(head).substr(head.find_first_not_of(" \t\r\n")).starts_with("solid")) {
    std::error_code error;
    const std::uintmax_t size = std::filesystem::file_size(path, error);
    std::uint32_t triangles = 0;
    if (head.size() >= 84) std::memcpy(&triangles, head.data() + 80, sizeof(triangles));
    const bool binary = head.size() >= 84 && 84 + 50 * std::uintmax_t{triangles} == size;
    if (!binary && !error) {
      std::ifstream in(path, std::ios::binary);
      const std::uintmax_t tail = std::min<std::uintmax_t>(size, 1024);
      in.seekg(static_cast<std::streamoff>(size - tail));
      std::string end(static_cast<std::size_t>(tail), '\0');
      in.read(end.data(), static_cast<std::streamsize>(tail));
      if (in && end.find("endsolid") == std::string::npos) {
        throw std::runtime_error(cat("mesh file ", path.string(), ": the ASCII STL ends at byte ",
                                     size, " without its 'endsolid' line: cut short"));
      }
    }
  }
  // NOTE: an OFF header states its counts; assimp reserves for them before it reads a vertex, so
  // counts that the file's bytes cannot hold (each vertex takes 6 bytes or more, each face 8) are
  // refused here, not met as an allocation of gigabytes.
  if (format->extension == ".off") {
    Lines lines(head);
    std::vector<std::string_view> tokens;
    while (tokens.size() < 3) {
      const auto line = lines.next_nonblank();
      if (!line) break;
      for (const std::string_view t : split(*line)) {
        if (t.starts_with('#')) break;
        if (!t.ends_with("OFF")) tokens.push_back(t);
      }
    }
    if (tokens.size() >= 2) {
      const auto vertices = parse_count(tokens[0]), faces = parse_count(tokens[1]);
      std::error_code error;
      const double size = static_cast<double>(std::filesystem::file_size(path, error));
      if (vertices && faces &&
          6.0 * static_cast<double>(*vertices) + 8.0 * static_cast<double>(*faces) > size) {
        throw std::runtime_error(cat("mesh file ", path.string(), ": the OFF header declares ",
                                     *vertices, " vertices and ", *faces, " faces, more than its ",
                                     size, " bytes can hold"));
      }
    }
  }
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

/// The triangles of a PLY file: the vertex element's x, y, z and the face element's
/// vertex_indices (or vertex_index) lists as fans; read by io's one PLY reader.
TriangleMesh read_ply(const std::filesystem::path& path) {
  const std::string bytes = read_text(path);
  TriangleMesh mesh;
  try {
    const PlyReader ply(bytes);
    const auto v = ply.find("vertex");
    if (!v) throw FormatError("no vertex element");
    const PlyElement& vertex = ply.elements()[*v];
    const auto x = vertex.find("x"), y = vertex.find("y"), z = vertex.find("z");
    if (!x || !y || !z) throw FormatError("the vertex element lacks x, y or z");
    const auto f = ply.find("face");
    std::optional<std::size_t> indices;
    if (f) {
      const PlyElement& face = ply.elements()[*f];
      indices = face.find("vertex_indices", true);
      if (!indices) indices = face.find("vertex_index", true);
      if (!indices) throw FormatError("the face element has no vertex_indices list");
    }
    mesh.vertices.reserve(vertex.count);  // the reader checked that the data can hold them
    ply.read(std::max(*v, f.value_or(0)), [&](std::size_t e, std::uint64_t i, const PlyRecord& r) {
      if (e == *v) {
        mesh.vertices.emplace_back(r.scalar(*x), r.scalar(*y), r.scalar(*z));
      } else if (e == f) {
        const std::span<const double> polygon = r.list(*indices);
        for (const double index : polygon) {
          if (index < 0 || index > 2e9)
            throw FormatError(cat("face ", i, " has a bad index ", index));
        }
        // Polygons become fans.
        for (std::size_t k = 2; k < polygon.size(); ++k) {
          mesh.triangles.emplace_back(static_cast<int>(polygon[0]),
                                      static_cast<int>(polygon[k - 1]),
                                      static_cast<int>(polygon[k]));
        }
      }
    });
  } catch (const FormatError& e) {
    throw std::runtime_error(cat("mesh file ", path.string(), " is corrupt: ", e.what()));
  }
  return mesh;
}

/// Throws std::runtime_error saying why `path` is no mesh file to read: missing, a folder, a
/// FIFO... (not "not found" for all of them).
void require_readable(const std::filesystem::path& path) {
  if (const std::string why = input_file_problem(path, InputKind::kMesh); !why.empty()) {
    throw std::runtime_error(cat("mesh file ", path.string(), ": ", why));
  }
}

/// Assimp's error said without its internals: its validation names its own structures
/// ("aiScene::mNumMeshes is 0").
std::string assimp_reason(std::string_view message) {
  if (message.find("mNumMeshes is 0") != std::string_view::npos) return "it holds no mesh";
  if (message.find("bad_alloc") != std::string_view::npos) {
    return "it claims more data than memory holds (a malformed or truncated file)";
  }
  if (message.find("aiScene::") != std::string_view::npos ||
      message.find("aiMesh::") != std::string_view::npos ||
      message.find("Validation") != std::string_view::npos) {
    return "its data is malformed (not a mesh of triangles or polygons)";
  }
  return printable(message, 200);
}

}  // namespace

TriangleMesh load_mesh(const std::filesystem::path& path) {
  require_readable(path);
  require_mesh_format(path);
  if (has_extension(path, ".ply")) return checked(read_ply(path), path);
  Assimp::Importer importer;
  // NOTE: no post-processing but validation: Debian's assimp 5.2 aborts in its triangulation
  // step on some truncated files, so polygons are split into fans here instead.
  const aiScene* scene = nullptr;
  try {
    scene = importer.ReadFile(path.string(), aiProcess_ValidateDataStructure);
  } catch (const std::bad_alloc&) {
    throw std::runtime_error(cat("mesh file ", path.string(),
                                 " cannot be read: it claims more data than memory holds "
                                 "(a malformed or truncated file)"));
  }
  if (scene == nullptr || scene->mRootNode == nullptr ||
      (scene->mFlags & AI_SCENE_FLAGS_INCOMPLETE) != 0) {
    throw std::runtime_error(cat("mesh file ", path.string(),
                                 " cannot be read: ", assimp_reason(importer.GetErrorString())));
  }
  TriangleMesh mesh;
  collect(*scene, *scene->mRootNode, aiMatrix4x4(), mesh);
  return checked(std::move(mesh), path);
}

TriangleMesh load_js_mesh(const std::filesystem::path& path) {
  require_readable(path);
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

}  // namespace vantage::sim
