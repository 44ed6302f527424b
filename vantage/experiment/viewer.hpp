#pragma once
/// @file
/// `vantage view`: one self-contained HTML page that shows a results folder in 3D in the browser
/// — the map's occupied cells, the candidate views coloured by predicted gain, the chosen view,
/// the views taken and their order, and a slider over the scans. three.js is inlined, so the page
/// opens offline from disk.

#include <cstddef>
#include <filesystem>
#include <string>

namespace vantage {

/// Settings of the page.
struct ViewerConfig {
  /// Cells drawn per layer (occupied; unobserved). Beyond it a layer is thinned evenly, and the
  /// page says how many of how many it shows.
  std::size_t max_cells = 200000;
  /// Where scripts/fetch-web.sh put three.js; empty: web_dir().
  std::filesystem::path web_dir;

  /// Throws std::invalid_argument naming the field.
  void validate() const;
};

/// The three.js release the page inlines; scripts/fetch-web.sh fetches the same.
inline constexpr const char* kThreeVersion = "0.170.0";

/// The folder scripts/fetch-web.sh fills: $VANTAGE_WEB_DIR, else the source tree's .cache/web.
std::filesystem::path web_dir();

/// The page for a results folder: an `explore` folder (run.json and map.bt) or a `plan` folder
/// (plan.json and map.bt). Throws std::runtime_error with one line that names the file for a
/// missing or unreadable folder, a folder that is neither, a malformed run.json / plan.json or
/// map.bt, or a missing three.js (then it names scripts/fetch-web.sh).
std::string build_view_page(const std::filesystem::path& results_dir,
                            const ViewerConfig& config = {});

}  // namespace vantage
