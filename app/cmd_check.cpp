// dampbound check [PATH ...]: run every scene's [[expect]] tables headlessly, one line per
// expectation, JUnit XML for CI systems, non-zero exit when any fails.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <ostream>

#include "app/commands.hpp"
#include "app/options.hpp"
#include "core/analysis/expect.hpp"
#include "core/io/files.hpp"
#include "core/io/format.hpp"
#include "core/io/scene_file.hpp"
#include "core/physics/damping_ratio.hpp"
#include "dampbound/physics/error.hpp"

namespace dampbound::app::cmd_check {
namespace {

namespace fs = std::filesystem;

struct CheckArgs {
  std::vector<std::string> paths;
  std::string junit;
};

/// Every *.toml under the given files and folders, sorted, each once.
std::vector<std::string> scene_files(const std::vector<std::string>& paths) {
  std::vector<std::string> out;
  for (const std::string& p : paths) {
    std::error_code ec;
    if (fs::is_directory(p, ec)) {
      for (const auto& e : fs::recursive_directory_iterator(p))
        if (e.is_regular_file() && e.path().extension() == ".toml") out.push_back(e.path().string());
    } else if (fs::is_regular_file(p, ec)) {
      out.push_back(p);
    } else if (fs::exists(p, ec)) {
      check_regular_input(p);  // a FIFO or a device: named as such
    } else {
      throw InputError(p + ": no such file or folder");
    }
  }
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}

struct SceneReport {
  std::string file, error;
  std::vector<ExpectationResult> results;
  double seconds = 0;
};

void write_junit(std::ostream& out, const std::vector<SceneReport>& reports) {
  int tests = 0, failures = 0;
  for (const auto& r : reports) {
    tests += static_cast<int>(r.results.size()) + (r.error.empty() ? 0 : 1);
    failures += r.error.empty() ? 0 : 1;
    for (const auto& x : r.results) failures += !x.pass;
  }
  out << "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<testsuites name=\"dampbound check\" tests=\""
      << tests << "\" failures=\"" << failures << "\">\n";
  for (const auto& r : reports) {
    int f = r.error.empty() ? 0 : 1;
    for (const auto& x : r.results) f += !x.pass;
    out << "  <testsuite name=\"" << xml_escape(r.file) << "\" tests=\""
        << r.results.size() + (r.error.empty() ? 0 : 1) << "\" failures=\"" << f
        << "\" time=\"" << r.seconds << "\">\n";
    if (!r.error.empty())
      out << "    <testcase classname=\"" << xml_escape(r.file) << "\" name=\"load\">\n"
          << "      <failure message=\"" << xml_escape(r.error) << "\"/>\n    </testcase>\n";
    for (const auto& x : r.results) {
      const std::string name = (x.run.empty() ? "" : x.run + ": ") + x.what;
      out << "    <testcase classname=\"" << xml_escape(r.file) << "\" name=\""
          << xml_escape(name) << "\">";
      if (!x.pass)
        out << "\n      <failure message=\"measured " << xml_escape(x.measured) << " (line "
            << x.line << ")\"/>\n    ";
      out << "</testcase>\n";
    }
    out << "  </testsuite>\n";
  }
  out << "</testsuites>\n";
}

int run(const CheckArgs& a) {
  const std::vector<std::string> paths =
      a.paths.empty() ? std::vector<std::string>{shipped_scenes_dir()}
                      : a.paths;
  if (!a.junit.empty()) check_writable(a.junit);
  const auto files = scene_files(paths);
  if (files.empty()) throw InputError("check: no .toml scene under the given paths");
  std::vector<SceneReport> reports;
  int pass = 0, fail = 0, broken = 0;
  for (const std::string& file : files) {
    SceneReport rep;
    rep.file = file;
    const auto t0 = std::chrono::steady_clock::now();
    try {
      SceneSpec scene = load_scene(file);
      resolve_zeta(scene);
      require_magnitudes(scene.model, scene.params);
      rep.results = check_expectations(scene);
    } catch (const InputError& e) {
      rep.error = printable(e.what());  // it may quote the file: one inert line
    }
    rep.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    if (!rep.error.empty()) {
      // The reader's message already starts with the file (and line) it names.
      const bool named = rep.error.rfind(file, 0) == 0;
      std::printf("FAIL  %s%s%s\n", named ? "" : file.c_str(), named ? "" : ": ",
                  rep.error.c_str());
      ++broken;
    } else if (rep.results.empty()) {
      std::printf("----  %s: no expectations\n", file.c_str());
    }
    for (const auto& x : rep.results) {
      std::printf("%s  %s:%d %s%s%s (measured %s)\n", x.pass ? "pass" : "FAIL", file.c_str(),
                  x.line, x.run.empty() ? "" : "[", x.run.empty() ? "" : (x.run + "] ").c_str(),
                  x.what.c_str(), x.measured.c_str());
      (x.pass ? pass : fail)++;
    }
    std::fflush(stdout);
    reports.push_back(std::move(rep));
  }
  // Nothing judged is not a pass: a CI job pointed at the wrong folder must not stay green.
  if (pass + fail + broken == 0)
    throw InputError("check: no [[expect]] table in the " + std::to_string(files.size()) +
                     " scene file(s) given: add one (docs/scene-format.md, [[expect]]) or "
                     "point check at scenes that have them");
  if (!a.junit.empty())
    write_file_atomic(a.junit, [&](std::ostream& out) { write_junit(out, reports); });
  std::printf("check: %d passed, %d failed\n", pass, fail);
  std::fflush(stdout);
  if (broken > 0)
    throw InputError("check: " + std::to_string(broken) +
                     " scene file(s) not loaded: fix the FAIL lines above");
  return fail ? 1 : 0;
}

std::function<int()> setup(CLI::App& root) {
  auto a = std::make_shared<CheckArgs>();
  CLI::App* cmd = root.add_subcommand(
      "check",
      "Run the [[expect]] tables of every scene under the given files or folders (default: the "
      "shipped scenes/) headlessly; one line per expectation; exit 1 when any fails, 2 when "
      "a scene file cannot be loaded or there is no expectation to run.");
  cmd->add_option("paths", a->paths, "scene files or folders (searched for *.toml)");
  cmd->add_option("--junit", a->junit, "also write the results as JUnit XML to this file");
  return [a] { return run(*a); };
}

const bool registered = register_command("check", setup);

}  // namespace
}  // namespace dampbound::app::cmd_check
