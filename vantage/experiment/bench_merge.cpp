// `vantage bench merge` (bench.hpp, merge_bench): sweep folders run with the same settings and
// binary, their trials, generated scenes and yardstick files joined into one.

#include <fmt/core.h>

#include <algorithm>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>
#include <stdexcept>
#include <string>
#include <system_error>

#include "vantage/experiment/bench.hpp"
#include "vantage/experiment/detail/sweep_files.hpp"
#include "vantage/experiment/results.hpp"
#include "vantage/io/atomic_file.hpp"

namespace vantage {
namespace fs = std::filesystem;
using namespace detail;  // the sweep folder's files (detail/sweep_files.hpp)
namespace {

/// Throws std::runtime_error naming `path` unless `rows` are rows of scans.csv: at least one,
/// each with the header's number of fields.
void require_trial_rows(const std::string& rows, const fs::path& path) {
  const auto fields = std::count(kScansCsvHeader.begin(), kScansCsvHeader.end(), ',') + 1;
  std::istringstream lines(rows);
  std::string line;
  std::size_t n = 0;
  while (std::getline(lines, line)) {
    ++n;
    const auto found = std::count(line.begin(), line.end(), ',') + 1;
    // NOTE: a trial file from before the surface columns were appended holds fewer fields.
    if (found != fields && found != static_cast<long>(kScansCsvFieldsBeforeSurface)) {
      throw std::runtime_error(fmt::format(
          "{}: line {} holds {} fields, not the {} of a scans.csv row: not a trial file",
          path.string(), n, found, fields));
    }
  }
  if (n == 0) throw std::runtime_error(fmt::format("{}: empty, not a trial file", path.string()));
}

}  // namespace

void merge_bench(const std::vector<fs::path>& dirs, const fs::path& out) {
  if (dirs.empty()) throw std::invalid_argument("bench merge needs at least one folder");
  // NOTE: the target takes part like a source: its settings and its trials must agree with what
  // is merged into it, so nothing of it is replaced unseen.
  std::vector<fs::path> all = dirs;
  std::error_code error;
  const bool target_is_source = std::any_of(dirs.begin(), dirs.end(), [&](const fs::path& dir) {
    return fs::equivalent(dir, out, error);
  });
  if (!target_is_source && fs::exists(out)) all.push_back(out);
  std::map<std::string, std::string> trials;
  std::map<std::string, std::string> scenes;  // generated scene files, by file name
  std::map<std::string, std::string> truths;  // yardstick files, by file name
  nlohmann::json settings = nullptr;          // of the first folder; all must agree
  fs::path settings_dir;                      // that folder
  for (std::size_t k = 0; k < all.size(); ++k) {
    const fs::path& dir = all[k];
    const bool target = k == dirs.size();
    const nlohmann::json found = read_settings(dir);
    if (found.is_null() && !(target && trial_files(dir).empty())) {
      throw std::runtime_error(fmt::format(
          "{}: no {}, so the settings its trials were run with are unknown; only sweeps run with "
          "the same settings can be merged",
          dir.string(), kSettingsFile));
    }
    if (settings.is_null()) {
      settings = found;
      settings_dir = dir;
    } else if (!found.is_null()) {
      require_same_sweep(settings, settings_dir, found, dir);
      settings = with_scenes(settings, found);
    }
    for (const auto& [name, path] : scene_files(dir)) {
      const auto [it, inserted] = scenes.emplace(name, read_file(path));
      if (!inserted && it->second != read_file(path)) {
        throw std::runtime_error(fmt::format(
            "{}: differs from the scene file of the same name in another folder", path.string()));
      }
    }
    for (const auto& [name, path] : scene_files(dir, kYardstickFolder, ".json")) {
      const auto [it, inserted] = truths.emplace(name, read_file(path));
      if (!inserted && it->second != read_file(path)) {
        throw std::runtime_error(
            fmt::format("{}: differs from the yardstick file of the same name in another folder",
                        path.string()));
      }
    }
    const auto files = trial_files(dir);
    if (files.empty() && !target) {
      throw std::runtime_error(fmt::format("{}: no trials/ with trial files", dir.string()));
    }
    for (const auto& [key, path] : files) {
      const std::string rows = read_file(path);
      require_trial_rows(rows, path);
      const auto [it, inserted] = trials.emplace(key, rows);
      if (!inserted && it->second != rows) {
        throw std::runtime_error(fmt::format(
            "{}: trial {} differs from the same trial in another folder{}", path.string(), key,
            target ? " (the --out folder's would be replaced)" : ""));
      }
    }
  }
  fs::create_directories(out / "trials");
  // NOTE: the target's settings took part above, so this only adds the scenes it lacked.
  if (!settings.is_null() && read_settings(out) != settings) {
    write_atomically(out / kSettingsFile, settings.dump(2) + "\n");
  }
  for (const auto& [key, rows] : trials) write_atomically(out / "trials" / (key + ".csv"), rows);
  if (!scenes.empty()) fs::create_directories(out / kScenesFolder);
  for (const auto& [name, text] : scenes) write_atomically(out / kScenesFolder / name, text);
  if (!truths.empty()) fs::create_directories(out / kYardstickFolder);
  for (const auto& [name, text] : truths) write_atomically(out / kYardstickFolder / name, text);
  write_bench_csv(out);
}

}  // namespace vantage
