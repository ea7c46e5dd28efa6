#pragma once
// Exporting the tuner's runs: the plotted data as CSV (no GL here; the PNG of the plots is
// rendered by gui_export.hpp). Every file is written whole or not at all.
#include <iosfwd>
#include <string>
#include <vector>

#include "ui/tuner.hpp"

namespace dampbound::ui {

/// The files of one export: DIR/PREFIX_plots.png, DIR/PREFIX_traces.csv, DIR/PREFIX_runs.csv,
/// DIR/PREFIX_step.vtu.
struct ExportPaths {
  std::string plots_png;
  std::string traces_csv;
  std::string runs_csv;
  std::string step_vtu;  ///< DIR/PREFIX_step.vtu: the current step for ParaView (core/io/vtu.hpp)
};

/// The paths for `dir` ("" = the current directory) and `prefix`. Throws InputError when the
/// prefix is empty or contains a path separator.
ExportPaths export_paths(const std::string& dir, const std::string& prefix);

/// Long CSV of the visible pins and the current run: a first column "run" (the pin's name, or
/// "current: <params>"), then write_trace_csv's columns; one header.
void write_runs_trace_csv(std::ostream& out, const Tuner& tuner);

/// One row per run: run, scene, watched, m, kappa, gamma, dt, policy, factor, outcome,
/// iterations, max_displacement, violations, unstabilisable.
void write_runs_summary_csv(std::ostream& out, const Tuner& tuner);

/// Creates the folder and writes both CSV files and the current step's VTU atomically. Throws InputError naming the
/// path when a file cannot be written.
void export_csv(const Tuner& tuner, const ExportPaths& paths);

}  // namespace dampbound::ui
