#pragma once
/// @file
/// What every libFuzzer harness of fuzz/ shares: the input written to a scratch file (the readers
/// under test take paths, as the CLI does), and the rule that tells a finding from a refusal.
///
/// The rule (docs/fuzzing.md): a reader may refuse an input only with the exceptions its header
/// documents, std::runtime_error or std::invalid_argument (FormatError and YamlError derive from
/// the first), and with one line, as the CLI prints it. Anything else is a finding and aborts:
/// another exception type (std::bad_alloc, std::length_error, a third-party exception), a
/// message with a line break or none at all. Crashes, leaks, undefined behaviour, hangs and huge
/// allocations are caught by the sanitizers and by libFuzzer's -timeout, -rss_limit_mb and
/// -malloc_limit_mb (scripts/run-fuzzers.sh).

#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>
#include <string_view>

namespace vantage::fuzz {

/// A folder of this process's own, made once and removed at exit.
inline const std::filesystem::path& scratch_dir() {
  static const std::filesystem::path dir = [] {
    std::string pattern = (std::filesystem::temp_directory_path() / "vantage-fuzz-XXXXXX").string();
    if (mkdtemp(pattern.data()) == nullptr) {
      std::perror("vantage fuzz: mkdtemp");
      std::abort();
    }
    std::atexit([] {
      std::error_code ignored;
      std::filesystem::remove_all(scratch_dir(), ignored);
    });
    return std::filesystem::path(pattern);
  }();
  return dir;
}

/// Writes the input to `name` in the scratch folder and returns its path.
inline std::filesystem::path write_input(const std::uint8_t* data, std::size_t size,
                                         const std::string& name) {
  const std::filesystem::path path = scratch_dir() / name;
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
  out.close();
  if (!out) {
    std::fprintf(stderr, "vantage fuzz: cannot write %s\n", path.c_str());
    std::abort();
  }
  return path;
}

/// Where a harness stores what it computed from a reader's result, so that nothing is optimised
/// away.
inline volatile double sink = 0.0;

[[noreturn]] inline void finding(std::string_view what, std::string_view message) {
  std::fprintf(stderr, "vantage fuzz: FINDING: %.*s: %.*s\n", static_cast<int>(what.size()),
               what.data(), static_cast<int>(message.size()), message.data());
  std::abort();
}

/// A refusal's message must be one line, as the CLI prints it. With VANTAGE_FUZZ_VERBOSE set,
/// it is printed (to see why a seed is refused: `VANTAGE_FUZZ_VERBOSE=1 fuzz_pcd FILE`).
inline void check_message(std::string_view message) {
  if (message.empty()) finding("empty message", "");
  if (message.find('\n') != std::string_view::npos) finding("message of several lines", message);
  static const bool verbose = std::getenv("VANTAGE_FUZZ_VERBOSE") != nullptr;
  if (verbose) {
    std::fprintf(stderr, "refused: %.*s\n", static_cast<int>(message.size()), message.data());
  }
}

/// Runs `read`; a documented refusal returns quietly, anything else aborts as a finding.
template <typename Read>
void expect_clean(Read&& read) {
  try {
    read();
    static const bool verbose = std::getenv("VANTAGE_FUZZ_VERBOSE") != nullptr;
    if (verbose) std::fprintf(stderr, "accepted\n");
  } catch (const std::runtime_error& e) {
    check_message(e.what());
  } catch (const std::invalid_argument& e) {
    check_message(e.what());
  } catch (const std::exception& e) {
    finding("undocumented exception", e.what());
  } catch (...) {
    finding("undocumented exception", "not derived from std::exception");
  }
}

}  // namespace vantage::fuzz
