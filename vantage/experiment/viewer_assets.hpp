#pragma once
/// @file
/// The page `vantage view` fills in: share/viewer/view.html and view.js, embedded at build time
/// by embed_viewer.cmake so the binary needs no files of ours at run time.

#include <string_view>

namespace vantage {

/// share/viewer/view.html: the page, with the markers @TITLE@, @THREE@, @ORBIT@, @DATA@ and
/// @APP@ in that order.
std::string_view viewer_page_template();

/// share/viewer/view.js: the module that draws the data.
std::string_view viewer_app_script();

}  // namespace vantage
