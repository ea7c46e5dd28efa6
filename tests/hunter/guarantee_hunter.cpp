// The contradiction hunter (docs/hardening.md, "The guarantee hunter"): random small scenes of
// every damping kind and mix, integrator, fixed nodes, anchors, non-uniform masses and
// stiffnesses, tiny and huge magnitudes; every guarantee dampbound prints about them is set
// against an independent dense computation (dense_reference.hpp) and against runs of step().
//
//   guarantee_hunter [--seed S] [--scenes N] [--sweeps N] [--regressions FILE] [--verbose]
//   guarantee_hunter --dump SEED     the scene of one case as a scene file, on stdout
//
// Exit 0 when no contradiction is found, 1 otherwise (each one listed with its seed: add the
// seed to the regressions file so that every later run checks it), 2 on bad arguments.
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "guarantee_checks.hpp"

using namespace dampbound;
using namespace dampbound::hunt;

namespace {

int usage(const std::string& why) {
  std::fprintf(stderr, "guarantee_hunter: %s\n", why.c_str());
  return 2;
}

}  // namespace

int main(int argc, char** argv) {
  std::uint64_t seed = 1;
  long scenes = 300, sweeps = 6;
  std::string regressions;
  bool verbose = false;
  for (int a = 1; a < argc; ++a) {
    const std::string arg = argv[a];
    const auto value = [&]() -> std::string {
      if (a + 1 >= argc) throw std::invalid_argument(arg + " needs a value");
      return argv[++a];
    };
    try {
      if (arg == "--seed") seed = std::stoull(value());
      else if (arg == "--scenes") scenes = std::stol(value());
      else if (arg == "--sweeps") sweeps = std::stol(value());
      else if (arg == "--regressions") regressions = value();
      else if (arg == "--verbose") verbose = true;
      else if (arg == "--dump") {
        std::fputs(scene_toml(make_case(std::stoull(value()))).c_str(), stdout);
        return 0;
      }
      else return usage("unknown argument '" + arg + "' (see the comment at the top of the file)");
    } catch (const std::exception& e) {
      return usage(arg + ": " + e.what());
    }
  }
  Tally tally;
  tally.verbose = verbose;
  std::vector<std::uint64_t> seeds;
  if (!regressions.empty()) {
    std::ifstream in(regressions);
    if (!in) return usage("--regressions: cannot read " + regressions);
    std::string line;
    int number = 0;
    while (std::getline(in, line)) {
      ++number;
      if (line.empty() || line[0] == '#') continue;
      try {
        seeds.push_back(std::stoull(line.substr(0, line.find(' '))));
      } catch (const std::exception&) {
        return usage(regressions + ":" + std::to_string(number) + ": not a seed: " + line);
      }
    }
  }
  const size_t kept = seeds.size();
  for (long k = 0; k < scenes; ++k) seeds.push_back(seed * 1000003ULL + static_cast<std::uint64_t>(k));
  for (size_t k = 0; k < seeds.size(); ++k) hunt_scene(make_case(seeds[k]), tally);
  for (long k = 0; k < sweeps; ++k) hunt_sweep(seed * 7919ULL + static_cast<std::uint64_t>(k), tally);
  for (const std::string& f : tally.found) std::printf("CONTRADICTION %s\n", f.c_str());
  std::printf("hunter: %ld scenes (%zu kept from earlier finds), %ld sweeps, %ld guarantees "
              "checked, %ld contradictions\n",
              tally.scenes, kept, tally.sweeps, tally.checks, tally.contradictions);
  return tally.contradictions == 0 ? 0 : 1;
}
