// dampbound: the command line. Subcommands live in cmd_*.cpp and register themselves.
#include <cstdio>
#include <exception>
#include <map>

#include "app/commands.hpp"
#include "core/error.hpp"
#include "core/sweep_kernel.hpp"
#include "dampbound/version.hpp"

namespace dampbound::app {

std::vector<CommandEntry>& command_table() {
  static std::vector<CommandEntry> table;
  return table;
}

bool register_command(const std::string& name, CommandSetup setup) {
  command_table().push_back({name, std::move(setup)});
  return true;
}

}  // namespace dampbound::app

int main(int argc, char** argv) {
  using namespace dampbound::app;
  CLI::App root{
      "dampbound: damping bounds that guarantee stability in mass-spring systems\n"
      "(Bhasin & Liu). Units: cm, s, and any consistent mass unit."};
  root.require_subcommand(1);
  // The version, and which compiled variant of the sweep kernel this CPU runs.
  root.set_version_flag("--version", std::string("dampbound ") + DAMPBOUND_VERSION +
                                         " (sweep kernel: " +
                                         dampbound::to_string(dampbound::best_kernel_isa()) +
                                         ")");
  root.set_help_all_flag("--help-all", "Print help for every subcommand");
  std::map<std::string, std::function<int()>> runners;
  for (auto& entry : command_table()) runners[entry.name] = entry.setup(root);
  try {
    root.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return root.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return root.exit(e);
  } catch (const CLI::CallForVersion& e) {
    return root.exit(e);
  } catch (const CLI::ParseError& e) {
    // One line naming the flag; CLI11's own text already does.
    std::fprintf(stderr, "dampbound: error: %s\n", e.what());
    return 2;
  }
  try {
    for (auto* sub : root.get_subcommands()) {
      auto it = runners.find(sub->get_name());
      if (it != runners.end()) return it->second();
    }
  } catch (const dampbound::InputError& e) {
    std::fprintf(stderr, "dampbound: error: %s\n", e.what());
    return 2;
  } catch (const std::exception& e) {
    // Environment failures (no EGL, no display, a file system error): one line, exit 3.
    std::fprintf(stderr, "dampbound: error: %s\n", e.what());
    return 3;
  }
  return 2;
}
