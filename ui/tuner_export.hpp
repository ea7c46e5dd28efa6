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

/// Whether an export holds the current run: only once it has a verdict (the iteration limit,
/// settled, diverged), unless `unfinished` asks for it while it still runs.
bool export_includes_current(const Tuner& tuner, bool unfinished);

/// Long CSV of the visible pins and, when `current`, the current run: a first column "run"
/// (the pin's name, or "current: <params>"), then write_trace_csv's columns; one header.
void write_runs_trace_csv(std::ostream& out, const Tuner& tuner, bool current = true);

/// One row per run (the visible pins, then the current run when `current`): run, scene,
/// watched, m, kappa, gamma, dt, policy, factor, rule, outcome, first_entry, left_at,
/// settled_at, diverged_at (SPEC 8's band history, as `run --json` has it; empty where none),
/// verdict (the verdict in words), iterations, max_displacement, violations, unstabilisable.
void write_runs_summary_csv(std::ostream& out, const Tuner& tuner, bool current = true);

/// Creates the folder and writes both CSV files and the current step's VTU atomically. Throws
/// InputError naming the path when a file cannot be written. `current` as above.
void export_csv(const Tuner& tuner, const ExportPaths& paths, bool current = true);

}  // namespace dampbound::ui
