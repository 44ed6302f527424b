#pragma once
/// @file
/// What this binary was built from, as sweep.json records it (vantage/experiment/build_info.cmake
/// writes the definitions at every build).

#include <string_view>

namespace vantage {

/// The version of the sources (CMakeLists.txt's project VERSION), e.g. "0.1.0".
std::string_view build_version();

/// The git commit the binary was built from, 40 hex digits, with "-dirty" when tracked files
/// differed from it; what -DVANTAGE_GIT_COMMIT gave (a source tarball without .git); else
/// "unknown".
std::string_view build_commit();

}  // namespace vantage
