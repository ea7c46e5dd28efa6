// dampbound map RESULTS.csv -o FILE.png: the stability map of a sweep (core/sweep/map.hpp)
// drawn with the plot widget through the headless EGL host (app/map_png.hpp).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>

#include "app/commands.hpp"
#include "app/map_png.hpp"
#include "app/options.hpp"
#include "core/io/files.hpp"
#include "core/io/format.hpp"
#include "core/sweep/map.hpp"
#include "core/sweep/summary.hpp"
#include "dampbound/physics/error.hpp"
#include "ui/egl_host.hpp"
#include "ui/map_plot.hpp"
#include "ui/plot.hpp"

namespace dampbound::app::cmd_ui_map {
namespace {

struct MapArgs {
  std::string csv, output, scene, size;
  std::vector<std::string> axes;
  double dt = 0;
  CLI::Option* dt_opt = nullptr;
};

int run(const MapArgs& a) {
  int width = 0, height = 0;
  if (!a.size.empty()) parse_size(a.size, "--size", width, height);
  try {
    check_writable(a.output);
  } catch (const InputError& e) {
    throw InputError(std::string("-o: ") + e.what());
  }
  const SweepTable table = read_sweep_csv(a.csv);
  const std::string scene_path = a.scene.empty() ? table.header.scene_path : a.scene;
  double lambda_unit = NAN;
  MapOptions opt;
  for (const std::string& pair : a.axes) {
    const size_t colon = pair.find(':');
    if (colon == std::string::npos || pair.find(':', colon + 1) != std::string::npos)
      throw InputError("--axes: '" + pair + "' is not X:Y (for example kd:dt)");
    opt.axes.emplace_back(pair.substr(0, colon), pair.substr(colon + 1));
  }
  try {
    const SceneSpec scene = load_scene_arg(scene_path);
    lambda_unit = unit_stiffness_eigenvalue(scene);
    opt.dashpot_ratio = dashpot_stiffness_ratio(scene);
  } catch (const std::exception& e) {
    std::printf("warning      no exact linear limit (scene %s: %s)\n",
                printable(scene_path).c_str(), printable(e.what()).c_str());
  }
  if (a.dt_opt->count()) opt.dt = a.dt;
  const StabilityMap map = build_stability_map(table, lambda_unit, opt);
  render_map_png(map, a.output, width, height);
  std::printf("map          %s -> %s (%zu panels, lambda_max = %s * kappa/m 1/s^2)\n",
              a.csv.c_str(), a.output.c_str(), map.panels.size(),
              format_human(lambda_unit).c_str());
  for (const std::string& line : map.summary) std::printf("%s\n", line.c_str());
  return 0;
}

std::function<int()> setup(CLI::App& root) {
  auto a = std::make_shared<MapArgs>();
  CLI::App* cmd = root.add_subcommand(
      "map",
      "Draw the stability map of a sweep CSV (headless, EGL): outcome over kappa/m and zeta "
      "(or factor), and over m and kappa per zeta, with the paper's boundary and the exact "
      "linear one; print how often the predictions held.");
  cmd->add_option("results", a->csv, "a sweep CSV (dampbound sweep -o)")->required();
  cmd->add_option("-o,--output", a->output, "PNG file to write")->required();
  cmd->add_option("--scene", a->scene,
                  "scene for lambda_max (default: the one named in the CSV header)");
  a->dt_opt = cmd->add_option("--dt", a->dt, "which dt to draw when the sweep has several")
                  ->check(finite_positive());
  cmd->add_option("--size", a->size, "image size WxH in pixels (default from the panel count)");
  std::string names;
  for (const std::string& n : map_axis_names()) names += (names.empty() ? "" : ", ") + n;
  cmd->add_option("--axes", a->axes,
                  "X:Y, repeatable: one panel per pair of columns in place of the paper's "
                  "layout, the other columns held at the first trial's values, with the exact "
                  "linear limit where it applies (" + names + ")");
  return [a] { return run(*a); };
}

const bool registered = register_command("map", setup);

}  // namespace
}  // namespace dampbound::app::cmd_ui_map
