#include "vantage/io/atomic_file.hpp"

#include <unistd.h>

#include <fstream>
#include <new>
#include <stdexcept>
#include <system_error>

#include "vantage/util/text.hpp"

namespace vantage {
namespace fs = std::filesystem;
namespace {

/// The message of `e` as the user should read it: the temporary path `internal` said as the
/// path it stands for, and a filesystem error as "<path>: <reason>", not as the library's text.
std::string message_naming(const std::exception& e, const fs::path& internal,
                           const fs::path& shown) {
  std::string message = e.what();
  if (const auto* fs_error = dynamic_cast<const fs::filesystem_error*>(&e)) {
    message = cat(fs_error->path1().string(), ": ", fs_error->code().message());
  }
  const std::string from = internal.string(), to = shown.string();
  for (std::size_t at = message.find(from); at != std::string::npos;
       at = message.find(from, at + to.size())) {
    message.replace(at, from.size(), to);
  }
  return message;
}

}  // namespace

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
    const std::string message = message_naming(e, temporary, path);
    throw std::runtime_error(
        message.starts_with(path.string()) ? message : cat(path.string(), ": ", message));
  }
}

void write_atomically(const fs::path& path, std::string_view content) {
  write_atomically(path, [&](std::ostream& out) { out << content; });
}

void write_folder_atomically(const fs::path& dir,
                             const std::function<void(const fs::path&)>& fill) {
  const fs::path partial = dir.string() + ".partial-" + std::to_string(::getpid());
  try {
    fs::remove_all(partial);
    fs::create_directories(partial);
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
    // NOTE: messages name the folder being written, never its temporary sibling.
    try {
      throw;
    } catch (const std::bad_alloc&) {
      throw;
    } catch (const std::invalid_argument& e) {
      throw std::invalid_argument(message_naming(e, partial, dir));
    } catch (const std::exception& e) {
      throw std::runtime_error(message_naming(e, partial, dir));
    }
  }
}

}  // namespace vantage
