#pragma once
// The command table: each cmd_*.cpp registers one subcommand at static-initialisation time,
// so a new subcommand is a new file and nothing else.
#include <CLI/CLI.hpp>

#include <functional>
#include <string>
#include <vector>

namespace dampbound::app {

/// Adds the subcommand to `root` and returns the function that runs it once parsing succeeded.
/// The runner returns the process exit code (0 ok, 1 a check failed, 2 bad input).
using CommandSetup = std::function<std::function<int()>(CLI::App& root)>;

struct CommandEntry {
  std::string name;
  CommandSetup setup;
};

std::vector<CommandEntry>& command_table();

/// Use at namespace scope in a cmd_*.cpp:
///   static const bool registered = register_command("run", setup_run);
bool register_command(const std::string& name, CommandSetup setup);

}  // namespace dampbound::app
