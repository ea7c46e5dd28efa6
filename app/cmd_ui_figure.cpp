// dampbound figure NAME|SCENE -o FILE.png: the paper's figures (or a scene's runs) rendered
// headless through EGL with the GUI's plot widget.
#include <cstdio>
#include <memory>

#include "app/commands.hpp"
#include "app/options.hpp"
#include "core/analysis/figures.hpp"
#include "core/io/files.hpp"
#include "core/io/report.hpp"
#include "core/physics/damping_ratio.hpp"
#include "dampbound/physics/error.hpp"
#include "ui/render_png.hpp"
#include "ui/trace_plots.hpp"

namespace dampbound::app::cmd_ui_figure {
namespace {

struct FigureArgs {
  std::string what, output, csv, size = "1200x700";
  std::string scene;
  double zeta = 0, kd = 0, rayleigh_mass = 0, rayleigh_stiffness = 0;
  CLI::Option* zeta_opt = nullptr;
  CLI::Option* damping_opts[3] = {};
};

int run(const FigureArgs& a) {
  int width = 0, height = 0;
  parse_size(a.size, "--size", width, height);
  check_writable(a.output);
  if (!a.csv.empty()) check_writable(a.csv);
  FigureData fig;
  if (a.what == "fig1" || a.what == "fig2") {
    if (a.zeta_opt->count())
      throw InputError("--zeta: fig1 and fig2 draw the paper's own gammas; give a scene file");
    for (const CLI::Option* o : a.damping_opts)
      if (o->count())
        throw InputError(o->get_name() + ": fig1 and fig2 are the paper's nodal damping; give a "
                         "scene file");
    const SceneSpec plane = load_scene_arg(a.scene);
    fig = a.what == "fig1" ? figure_fig1(plane) : figure_fig2(plane);
  } else {
    SceneSpec scene = load_scene_arg(a.what);
    if (a.zeta_opt->count()) {  // every run of the figure at this damping ratio
      scene.params.zeta = a.zeta;
      for (RunSpec& r : scene.runs) r.params.zeta = a.zeta;
    }
    // SPEC 10's damping, given, in the scene and every run of the figure.
    apply_damping_flags(a.damping_opts, a.kd, a.rayleigh_mass, a.rayleigh_stiffness, scene.params);
    for (RunSpec& r : scene.runs)
      apply_damping_flags(a.damping_opts, a.kd, a.rayleigh_mass, a.rayleigh_stiffness, r.params);
    resolve_zeta(scene);
    fig = figure_scene(scene);
  }
  // The CSV is finished first and put in place only once the PNG is: a failure of either
  // (a full disk) leaves neither file.
  std::unique_ptr<PendingOutput> csv;
  if (!a.csv.empty())
    csv = std::make_unique<PendingOutput>(a.csv, [&](int fd) {
      write_stream(fd, a.csv, [&](std::ostream& out) { write_figure_csv(out, fig); });
    });
  const std::string renderer =
      ui::render_plots_png({ui::figure_plot(fig)}, 1, width, height, a.output);
  if (csv) {
    try {
      csv->commit();
    } catch (...) {
      std::remove(a.output.c_str());
      throw;
    }
  }
  std::printf("figure %s -> %s (%dx%d, %s)\n", fig.name.c_str(), a.output.c_str(), width, height,
              renderer.c_str());
  // Figures keep the paper's first-entry rule (SPEC 8); the verdict says so in words.
  for (const FigureRun& r : fig.runs)
    std::printf("  %-28s %s\n", r.label.c_str(), verdict_text(r.result, r.rules).c_str());
  return 0;
}

std::function<int()> setup(CLI::App& root) {
  auto a = std::make_shared<FigureArgs>();
  CLI::App* cmd = root.add_subcommand(
      "figure",
      "Render a figure headless (EGL, no display): fig1 (paper Fig. 1: displacement of the "
      "perturbed node, cm, against iteration), fig2 (Fig. 2: log10 displacement, policy upper "
      "at factor 1.0 and 1.05), or a scene file's [[run]]s overlaid.");
  cmd->add_option("what", a->what, "fig1, fig2, or a scene file")->required();
  cmd->add_option("-o,--output", a->output, "PNG file to write")->required();
  cmd->add_option("--csv", a->csv, "also write the plotted data as CSV");
  cmd->add_option("--size", a->size, "image size WxH in pixels")->capture_default_str();
  cmd->add_option("--scene", a->scene, "the mesh for fig1/fig2")
      ->default_str("paper-plane")
      ->capture_default_str();
  a->scene = "paper-plane";
  a->zeta_opt = add_zeta_option(cmd, a->zeta);
  add_damping_flags(cmd, a->kd, a->rayleigh_mass, a->rayleigh_stiffness, a->damping_opts);
  return [a] { return run(*a); };
}

const bool registered = register_command("figure", setup);

}  // namespace
}  // namespace dampbound::app::cmd_ui_figure
