// dampbound: the command line. Subcommands live in cmd_*.cpp and register themselves.
#include <algorithm>
#include <cstdio>
#include <exception>
#include <map>

#include "app/cli_words.hpp"
#include "app/commands.hpp"
#include "core/io/format.hpp"
#include "core/io/scene_text.hpp"
#include "core/sweep/kernel.hpp"
#include "dampbound/physics/error.hpp"
#include "dampbound/physics/step_isa.hpp"
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

namespace {
/// One line on stderr: control characters in the message (from a file name or a file's
/// content) are escaped, so that it stays one line and sends nothing to the terminal.
void print_error(const char* what) {
  std::fprintf(stderr, "dampbound: error: %s\n", dampbound::printable(what).c_str());
}
}  // namespace

int main(int argc, char** argv) {
  using namespace dampbound::app;
  CLI::App root{
      "dampbound: damping bounds that guarantee stability in mass-spring systems\n"
      "(Bhasin & Liu). Units: cm, s, and any consistent mass unit."};
  root.require_subcommand(1);
  // The version, and which compiled copies of the sweep kernel and of step()'s spring loop
  // this CPU runs.
  root.set_version_flag("--version", std::string("dampbound ") + DAMPBOUND_VERSION +
                                         " (sweep kernel: " +
                                         dampbound::to_string(dampbound::best_kernel_isa()) +
                                         ", step: " +
                                         dampbound::to_string(dampbound::best_step_isa()) + ")");
  root.set_help_all_flag("--help-all", "Print help for every subcommand");
  bool any_path = false;
  root.add_flag("--allow-any-path", any_path,
                "let a scene name files outside its own folder ([mesh] file: absolute paths, "
                "'..')");
  int digits = 6;
  root.add_option("--digits", digits,
                  "significant digits of the numbers printed for people (files keep full "
                  "precision)")
      ->check(whole_range(1, 17));
  root.fallthrough();  // the flag may also follow the subcommand
  // Registration order depends on how the files were linked: list the subcommands by name.
  auto& table = command_table();
  std::sort(table.begin(), table.end(),
            [](const CommandEntry& a, const CommandEntry& b) { return a.name < b.name; });
  std::map<std::string, std::function<int()>> runners;
  for (auto& entry : table) runners[entry.name] = entry.setup(root);
  // CLI11 answers an unknown first word with "A subcommand is required": name it instead.
  for (int k = 1; k < argc; ++k) {
    const std::string word = argv[k];
    if (word == "--digits") {  // the root's one option with a value: skip the value
      ++k;
      continue;
    }
    if (word.empty() || word[0] == '-') continue;
    if (runners.count(word)) break;
    std::string names;  // the ones --help lists: a hidden command (group "") is left out
    for (const auto& [name, runner] : runners)
      if (!root.get_subcommand(name)->get_group().empty())
        names += (names.empty() ? "" : ", ") + name;
    print_error(("unknown subcommand '" + word + "' (one of: " + names + ")").c_str());
    return 2;
  }
  try {
    root.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return root.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return root.exit(e);
  } catch (const CLI::CallForVersion& e) {
    return root.exit(e);
  } catch (const CLI::ExtrasError& e) {
    // CLI11 says "arguments were not expected": name the flag and the nearest known one.
    const auto said = unknown_flag_message(root, std::vector<std::string>(argv + 1, argv + argc));
    print_error(said ? said->c_str() : e.what());
    return 2;
  } catch (const CLI::ParseError& e) {
    // One line naming the flag; CLI11's own text already does.
    print_error(e.what());
    return 2;
  }
  dampbound::set_scene_paths_unrestricted(any_path);
  dampbound::set_human_digits(digits);
  try {
    for (auto* sub : root.get_subcommands()) {
      refuse_empty_values(*sub);  // `--trace ""` is no trace: say so instead of dropping it
      auto it = runners.find(sub->get_name());
      if (it != runners.end()) return it->second();
    }
  } catch (const dampbound::InputError& e) {
    print_error(e.what());
    return 2;
  } catch (const std::exception& e) {
    // Environment failures (no EGL, no display, a file system error): one line, exit 3.
    print_error(e.what());
    return 3;
  }
  return 2;
}
