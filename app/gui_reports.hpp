#pragma once
// What a scripted `dampbound gui --frames N` run reports (tests, measurements): the Suggest
// tab's answers on stderr, the map it waits for, the --stats JSON line. Window builds only.
#if defined(DAMPBOUND_HAVE_GLFW)
#include <string>

#include "ui/glfw_host.hpp"
#include "ui/gui_app.hpp"

namespace dampbound::app {

/// The Suggest tab's substeps, in one line on stderr (scripted --tab suggest runs).
void print_substeps_line(const ui::BackgroundJob<ui::SubstepsResult>& job);
/// The Suggest tab's stiffness ceiling and Rayleigh pair, in one line on stderr.
void print_knobs_line(const ui::BackgroundJob<ui::KnobsResult>& job);
/// The scripted last frame of `--tab map`: waits for every pass of the map, saying on stderr
/// which pass is done once the wait passes 2 s.
void wait_for_map(ui::TunerMap& map);
/// The --stats line on stdout: frames, outcome, frame times, the exact analysis on show.
void print_stats(ui::GuiApp& app, const ui::WindowRun& run, const std::string& renderer,
                 int width, int height);

}  // namespace dampbound::app
#endif
