/// `vantage`: next-best-view planning in cluttered 3D scenes. A thin shell over the library: each
/// subcommand parses its options and calls the library; any error becomes one line on stderr,
/// `vantage: error: <what> (<where>)`, and the exit code of docs/robustness.md: 0 done, 1 the
/// input or the run failed, 2 the command line is wrong.

#include <fmt/core.h>

#include <CLI/CLI.hpp>
#include <exception>
#include <filesystem>
#include <new>
#include <string>
#include <string_view>

#include "commands/commands.hpp"
#include "shell.hpp"
#include "vantage/perception/registration.hpp"
#include "vantage/util/text.hpp"
#include "vantage/util/work.hpp"

namespace {

/// The names of `app`'s subcommands, "a, b or c".
std::string command_names(const CLI::App& app) {
  std::string names;
  const auto commands = app.get_subcommands([](const CLI::App*) { return true; });
  for (std::size_t i = 0; i < commands.size(); ++i) {
    names += (i == 0 ? "" : (i + 1 == commands.size() ? " or " : ", ")) + commands[i]->get_name();
  }
  return names;
}

/// Refuses an unknown command (or sub-command, as in `bench frob`) before CLI11 parses, which
/// would call it "a subcommand is required" or an unexpected argument.
void check_commands(const CLI::App& app, int argc, char** argv) {
  const CLI::App* current = &app;
  std::string path = "vantage";
  for (int i = 1; i < argc; ++i) {
    const std::string_view token = argv[i];
    if (token.empty() || token.front() == '-') return;
    const auto commands = current->get_subcommands([](const CLI::App*) { return true; });
    if (commands.empty()) return;
    const CLI::App* next = nullptr;
    for (const CLI::App* command : commands) {
      if (command->check_name(std::string(token))) next = command;
    }
    if (next == nullptr) {
      // NOTE: a command that also takes a positional (`vantage scene NAME`) reads it as that.
      const auto positionals =
          current->get_options([](const CLI::Option* o) { return o->get_positional(); });
      if (!positionals.empty()) return;
      throw vantage::cli::UsageError(fmt::format("unknown command '{}' ({} takes {})",
                                                 vantage::printable(token, 60), path,
                                                 command_names(*current)));
    }
    path += " " + next->get_name();
    current = next;
  }
}

/// Refuses an empty value (`--out ""`, `--alpha=`): CLI11 takes it as given, and the commands
/// would read it as "not given" and fall back to a default.
void check_empty_values(int argc, char** argv) {
  for (int i = 1; i < argc; ++i) {
    const std::string_view token = argv[i];
    const std::string_view before = i > 1 ? std::string_view(argv[i - 1]) : std::string_view();
    if (token.empty()) {
      throw vantage::cli::UsageError(
          before.starts_with('-')
              ? fmt::format("{}: the value is empty (give one, or leave the option out)",
                            vantage::printable(before, 60))
              : std::string("an argument is empty (give a value)"));
    }
    if (token.starts_with("--") && token.ends_with('=')) {
      throw vantage::cli::UsageError(
          fmt::format("{}: the value is empty (give one, or leave the option out)",
                      vantage::printable(token.substr(0, token.size() - 1), 60)));
    }
  }
}

/// CLI11's message for a parse error, said the way the rest of the tool says things.
std::string parse_message(const CLI::ParseError& e, const CLI::App& app) {
  if (dynamic_cast<const CLI::RequiredError*>(&e) != nullptr &&
      std::string_view(e.what()).starts_with("A subcommand")) {
    return fmt::format("give a command: {} (vantage --help)", command_names(app));
  }
  return e.what();
}

}  // namespace

int main(int argc, char** argv) {
  using vantage::cli::report_error;
  CLI::App app("Vantage: next-best-view planning in cluttered 3D scenes", "vantage");
  app.set_version_flag("--version", VANTAGE_VERSION);
  app.require_subcommand(1);
  vantage::cli::add_explore_command(app);
  vantage::cli::add_bench_command(app);
  vantage::cli::add_plan_command(app);
  vantage::cli::add_ray_command(app);
  vantage::cli::add_scan_command(app);
  vantage::cli::add_scene_command(app);
  vantage::cli::add_view_command(app);
  app.footer(
      "Exit codes: 0 done, 1 the input or the run failed, 2 the command line is wrong "
      "(docs/robustness.md).");
  vantage::perception::silence_pcl_console();  // failures are reported per scan, in one line
  try {
    check_commands(app, argc, argv);
    check_empty_values(argc, argv);
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    if (e.get_exit_code() == 0) return app.exit(e);  // --help, --version
    return report_error(parse_message(e, app), vantage::cli::kExitUsage);
  } catch (const vantage::cli::UsageError& e) {
    return report_error(e.what(), vantage::cli::kExitUsage);
  } catch (const vantage::WorkBudgetError& e) {
    // NOTE: work the budget refused is the command line's to change, as an option out of range.
    return report_error(e.what(), vantage::cli::kExitUsage);
  } catch (const std::filesystem::filesystem_error& e) {
    // NOTE: what() is "filesystem error: cannot ...: <reason> [path]"; say the path and reason.
    return report_error(fmt::format("{}: {}", e.path1().string(), e.code().message()),
                        vantage::cli::kExitFailure);
  } catch (const std::bad_alloc&) {
    return report_error(
        "out of memory: the run needs more than this machine has free (a smaller grid, or "
        "--max-memory to see the estimate)",
        vantage::cli::kExitFailure);
  } catch (const std::exception& e) {
    return report_error(e.what(), vantage::cli::kExitFailure);
  }
  return vantage::cli::kExitOk;
}
