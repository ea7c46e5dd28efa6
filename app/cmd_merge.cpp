// dampbound merge PART... -o FILE: joins the parts of a sweep split with --shard K/N.
#include <cstdio>
#include <memory>

#include "app/commands.hpp"
#include "core/io/format.hpp"
#include "core/sweep/csv.hpp"
#include "dampbound/physics/error.hpp"

namespace dampbound::app::cmd_merge {
namespace {

struct MergeArgs {
  std::vector<std::string> parts;
  std::string output;
};

int run(const MergeArgs& a) {
  merge_sweep_parts(a.parts, a.output);
  const SweepTable t = read_sweep_csv(a.output);
  std::printf("merged       %s of sweep %s: %s -> %s\n",
              plural(static_cast<long long>(a.parts.size()), "part").c_str(),
              t.header.sweep_id.c_str(), plural(static_cast<long long>(t.rows.size()), "trial").c_str(),
              a.output.c_str());
  return 0;
}

std::function<int()> setup(CLI::App& root) {
  auto a = std::make_shared<MergeArgs>();
  CLI::App* cmd = root.add_subcommand(
      "merge",
      "Join the CSV parts of a sweep run with --shard K/N into one file, identical to what an "
      "unsplit run writes. Fails unless the parts are of the same sweep and cover every trial "
      "exactly once.");
  cmd->add_option("parts", a->parts, "the part CSVs, in any order")->required();
  cmd->add_option("-o,--output", a->output, "the merged CSV (written atomically)")->required();
  return [a] { return run(*a); };
}

const bool registered = register_command("merge", setup);

}  // namespace
}  // namespace dampbound::app::cmd_merge
