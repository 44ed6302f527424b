#include "vantage/io/atomic_file.hpp"

#include <unistd.h>

#include <fstream>
#include <stdexcept>
#include <system_error>

#include "vantage/util/text.hpp"

namespace vantage {
namespace fs = std::filesystem;

void write_atomically(const fs::path& path, const std::function<void(std::ostream&)>& write) {
  const fs::path temporary = path.string() + ".tmp" + std::to_string(::getpid());
  try {
    if (path.has_parent_path()) fs::create_directories(path.parent_path());
    {
      std::ofstream out(temporary, std::ios::binary | std::ios::trunc);
      if (!out) throw std::runtime_error("cannot open for writing");
      write(out);
      out.flush();
      if (!out) throw std::runtime_error("write failed");
    }
    fs::rename(temporary, path);
  } catch (const std::exception& e) {
    std::error_code ignored;
    fs::remove(temporary, ignored);
    throw std::runtime_error(cat(path.string(), ": ", e.what()));
  }
}

void write_atomically(const fs::path& path, std::string_view content) {
  write_atomically(path, [&](std::ostream& out) { out << content; });
}

void commit_atomically(const fs::path& temporary, const fs::path& path) {
  std::error_code error;
  fs::rename(temporary, path, error);
  if (error) {
    throw std::runtime_error(
        cat(path.string(), ": cannot move ", temporary.string(), " into place: ", error.message()));
  }
}

}  // namespace vantage
