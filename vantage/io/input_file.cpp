#include "vantage/io/input_file.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <cerrno>
#include <cstring>
#include <system_error>

#include "vantage/io/format_parsing.hpp"
#include "vantage/util/limits.hpp"
#include "vantage/util/memory.hpp"
#include "vantage/util/text.hpp"

namespace vantage {
namespace fs = std::filesystem;

std::string_view to_string(InputKind kind) {
  switch (kind) {
    case InputKind::kPointCloud:
      return "point cloud file";
    case InputKind::kOctomap:
      return "OctoMap file";
    case InputKind::kMesh:
      return "mesh file";
    case InputKind::kSettings:
      return "manifest or scene file";
    case InputKind::kPoses:
      return "pose file";
    case InputKind::kResults:
      return "results file";
    case InputKind::kDepthImage:
      return "depth image file";
    case InputKind::kRecording:
      return "recording file";
  }
  return "file";
}

std::uintmax_t max_input_bytes(InputKind kind) {
  switch (kind) {
    case InputKind::kPointCloud:
      return kMaxCloudFileBytes;
    case InputKind::kOctomap:
      return kMaxMapFileBytes;
    case InputKind::kMesh:
      return kMaxMeshFileBytes;
    case InputKind::kSettings:
      return kMaxSettingsFileBytes;
    case InputKind::kPoses:
      return kMaxPoseFileBytes;
    case InputKind::kResults:
      return kMaxResultsFileBytes;
    case InputKind::kDepthImage:
      return kMaxDepthImageFileBytes;
    case InputKind::kRecording:
      return kMaxRecordingFileBytes;
  }
  return 0;
}

namespace {

std::string too_large(std::uintmax_t size, InputKind kind) {
  return cat("is ", size, " bytes, more than the ",
             describe_bytes(static_cast<double>(max_input_bytes(kind))), " a ", to_string(kind),
             " may have");
}

}  // namespace

std::string input_file_problem(const fs::path& path, InputKind kind) {
  if (std::string why = not_a_readable_file(path); !why.empty()) return why;
  std::error_code error;
  const std::uintmax_t size = fs::file_size(path, error);
  if (error) return error.message();
  if (size > max_input_bytes(kind)) return too_large(size, kind);
  return {};
}

std::uintmax_t require_input_file(const fs::path& path, InputKind kind) {
  if (const std::string why = input_file_problem(path, kind); !why.empty()) throw FormatError(why);
  std::error_code error;
  return fs::file_size(path, error);
}

std::string read_input_file(const fs::path& path, InputKind kind, std::size_t max_bytes) {
  (void)require_input_file(path, kind);
  // NOTE: opened without blocking and checked again on the descriptor: a path swapped for a FIFO
  // between the check and the open neither blocks nor is read.
  const int fd = ::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC);
  if (fd < 0) throw FormatError("cannot open for reading");
  struct Closer {
    int fd;
    ~Closer() { ::close(fd); }
  } closer{fd};
  struct stat info {};
  if (::fstat(fd, &info) != 0 || !S_ISREG(info.st_mode)) {
    throw FormatError("is not a regular file (it changed while it was opened)");
  }
  // NOTE: one byte past the limit tells a file that grew since it was measured.
  const std::uintmax_t limit = max_input_bytes(kind);
  const std::size_t cap = static_cast<std::size_t>(std::min<std::uintmax_t>(max_bytes, limit + 1));
  std::string bytes;
  bytes.reserve(static_cast<std::size_t>(
      std::min<std::uintmax_t>(static_cast<std::uintmax_t>(info.st_size), cap)));
  char buffer[1 << 16];
  while (bytes.size() < cap) {
    const ssize_t n = ::read(fd, buffer, std::min(sizeof(buffer), cap - bytes.size()));
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) throw FormatError(cat("read failed: ", std::strerror(errno)));
    if (n == 0) break;
    bytes.append(buffer, static_cast<std::size_t>(n));
  }
  if (bytes.size() > limit) {
    throw FormatError(cat("grew while it was read: ", too_large(bytes.size(), kind)));
  }
  return bytes;
}

namespace {

/// The first token of the first line that is neither blank nor a '#' comment.
std::string_view first_token(std::string_view head) {
  Lines lines(head);
  while (const auto line = lines.next_nonblank()) {
    const auto tokens = split(*line);
    if (tokens.empty() || tokens.front().starts_with('#')) continue;
    return tokens.front();
  }
  return {};
}

}  // namespace

std::string_view sniff_format(std::string_view head) {
  if (head.starts_with("# Octomap OcTree")) return "an OctoMap file";
  if (head.starts_with("ply\n") || head.starts_with("ply\r\n")) return "a PLY file";
  const std::string_view first = first_token(head.substr(0, 4096));
  if (first == "VERSION" || first == "FIELDS" || head.starts_with("# .PCD")) {
    return "a PCD point cloud";
  }
  static constexpr std::array<std::string_view, 5> kOff = {"OFF", "COFF", "NOFF", "CNOFF", "STOFF"};
  if (std::find(kOff.begin(), kOff.end(), first) != kOff.end()) return "an OFF mesh";
  static constexpr std::array<std::string_view, 9> kObj = {"v", "vt",     "vn",     "f", "o",
                                                           "g", "mtllib", "usemtl", "s"};
  if (std::find(kObj.begin(), kObj.end(), first) != kObj.end()) return "OBJ text";
  if (first == "solid") return "ASCII STL";
  const std::size_t start = head.find_first_not_of(" \t\r\n");
  if (start != std::string_view::npos && head[start] == '{') {
    const std::size_t next = head.find_first_not_of(" \t\r\n", start + 1);
    if (next != std::string_view::npos && head[next] == '"') return "JSON";
  }
  return {};
}

std::string lower_extension(const fs::path& path) {
  std::string extension = path.extension().string();
  std::transform(extension.begin(), extension.end(), extension.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return extension;
}

}  // namespace vantage
