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

void write_folder_atomically(const fs::path& dir,
                             const std::function<void(const fs::path&)>& fill) {
  const fs::path partial = dir.string() + ".partial-" + std::to_string(::getpid());
  fs::remove_all(partial);
  fs::create_directories(partial);
  try {
    fill(partial);
    if (fs::exists(dir)) fs::remove(dir);  // an empty folder the user made; throws otherwise
    std::error_code error;
    fs::rename(partial, dir, error);
    if (error) {
      throw std::runtime_error(
          cat(dir.string(), ": cannot move ", partial.string(), " into place: ", error.message()));
    }
  } catch (...) {
    std::error_code ignored;
    fs::remove_all(partial, ignored);
    throw;
  }
}

}  // namespace vantage
