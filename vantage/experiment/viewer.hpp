#pragma once
/// @file
/// `vantage view`: one self-contained HTML page that shows a results folder in 3D in the browser
/// — the map's occupied cells, the candidate views coloured by predicted gain, the chosen view,
/// the views taken and their order, and a slider over the scans. three.js is inlined, so the page
/// opens offline from disk.

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <string>

#include "vantage/util/limits.hpp"

namespace vantage {

/// Settings of the page.
struct ViewerConfig {
  /// Cells drawn per layer (occupied; unobserved). Beyond it a layer is thinned evenly, and the
  /// page says how many of how many it shows.
  std::size_t max_cells = 200000;
  /// Candidates drawn per decision: the chosen view and the best by score. The rest are cut
  /// (the page says how many), so a million candidates cost the page what a thousand do.
  std::size_t max_candidates = 1000;
  /// The memory budget [bytes]; 0: what the machine has available (vantage/util/memory.hpp).
  std::uint64_t max_memory = 0;
  /// Where scripts/fetch-web.sh put three.js; empty: web_dir().
  std::filesystem::path web_dir;

  /// Throws std::invalid_argument naming the field.
  void validate() const;
};

/// The largest run.json or plan.json `vantage view` reads [bytes]: a million candidates take
/// about 400 MB. The results file's limit of the one table (vantage/util/limits.hpp).
inline constexpr std::uintmax_t kMaxViewerFileBytes = kMaxResultsFileBytes;
/// Bytes a grid cell costs `vantage view` at its peak: the grid's log-odds (4 B) and the
/// OctoMap tree read into it, rounded up (docs/robustness.md, "Memory").
inline constexpr double kViewerBytesPerCell = 8.0;
/// What `vantage view` holds besides the grid and the file: code, three.js, the page.
inline constexpr double kViewerFixedBytes = 64.0 * 1024 * 1024;

/// The three.js release the page inlines; scripts/fetch-web.sh fetches the same.
inline constexpr const char* kThreeVersion = "0.170.0";

/// The folder scripts/fetch-web.sh fills: $VANTAGE_WEB_DIR, else the source tree's .cache/web.
std::filesystem::path web_dir();

/// The page for a results folder: an `explore` folder (run.json and map.bt) or a `plan` folder
/// (plan.json and map.bt). Throws std::runtime_error with one line that names the file for a
/// missing or unreadable folder, a folder that is neither, a run.json / plan.json that is not a
/// regular file, is larger than kMaxViewerFileBytes or malformed, a malformed map.bt, a grid the
/// memory budget cannot hold (before allocating it), or a missing three.js (then it names
/// scripts/fetch-web.sh).
std::string build_view_page(const std::filesystem::path& results_dir,
                            const ViewerConfig& config = {});

}  // namespace vantage
