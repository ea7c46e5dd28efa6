#include "ui/tuner_export.hpp"

#include <filesystem>
#include <ostream>

#include "core/io/files.hpp"
#include "core/io/format.hpp"
#include "core/io/report.hpp"
#include "core/io/vtu.hpp"
#include "dampbound/physics/error.hpp"

namespace dampbound::ui {

namespace {
std::string current_label(const Tuner& t) {
  return "current: " + params_label(t.params());
}

/// CSV field: quoted when it holds a comma, quote or newline.
std::string csv_field(const std::string& s) {
  if (s.find_first_of(",\"\n") == std::string::npos) return s;
  std::string q = "\"";
  for (const char c : s) {
    if (c == '"') q += '"';
    q += c;
  }
  return q + "\"";
}

/// An iteration of the band history; empty where there is none (0).
std::string iteration_field(int it) { return it > 0 ? std::to_string(it) : ""; }

void summary_row(std::ostream& out, const std::string& label, const std::string& scene, int watched,
                 const Params& p, const StopRules& rules, const RunResult& r) {
  out << csv_field(label) << ',' << csv_field(scene) << ',' << watched << ',' << format_number(p.m)
      << ',' << format_number(p.kappa) << ',' << format_number(p.gamma) << ','
      << format_number(p.dt) << ',' << to_string(p.policy) << ',' << format_number(p.factor) << ','
      << to_string(rules.rule) << ',' << to_string(r.outcome) << ','
      << iteration_field(r.first_entry) << ',' << iteration_field(r.left_at) << ','
      << iteration_field(r.settled_at) << ','
      << iteration_field(r.outcome == Outcome::diverged ? r.iterations : 0) << ','
      << csv_field(verdict_short(r)) << ',' << r.iterations << ','
      << format_number(r.max_displacement) << ',' << r.violations << ',' << r.unstabilisable
      << '\n';
}
}  // namespace

ExportPaths export_paths(const std::string& dir, const std::string& prefix) {
  if (prefix.empty()) throw InputError("export: the file prefix is empty");
  if (prefix.find('/') != std::string::npos)
    throw InputError("export: the file prefix '" + prefix + "' contains '/'; use the folder field");
  const std::filesystem::path base =
      dir.empty() ? std::filesystem::path(".") : std::filesystem::path(dir);
  ExportPaths p;
  p.plots_png = (base / (prefix + "_plots.png")).string();
  p.traces_csv = (base / (prefix + "_traces.csv")).string();
  p.runs_csv = (base / (prefix + "_runs.csv")).string();
  p.step_vtu = (base / (prefix + "_step.vtu")).string();
  return p;
}

bool export_includes_current(const Tuner& tuner, bool unfinished) {
  return unfinished || tuner.session().result().outcome != Outcome::running;
}

void write_runs_trace_csv(std::ostream& out, const Tuner& tuner, bool current) {
  bool header = true;
  for (const Pin& pin : tuner.pins()) {
    if (!pin.visible) continue;
    write_trace_csv(out, pin.trace, pin.name, header);
    header = false;
  }
  if (current) write_trace_csv(out, tuner.session().trace(), current_label(tuner), header);
  else if (header) write_trace_csv(out, {}, "run", true);  // the header alone
}

void write_runs_summary_csv(std::ostream& out, const Tuner& tuner, bool current) {
  out << "run,scene,watched,m,kappa,gamma,dt,policy,factor,rule,outcome,first_entry,left_at,"
         "settled_at,diverged_at,verdict,iterations,max_displacement,violations,unstabilisable\n";
  for (const Pin& pin : tuner.pins())
    if (pin.visible)
      summary_row(out, pin.name, pin.scene, pin.watched, pin.params, pin.rules, pin.result);
  const Session& s = tuner.session();
  if (current)
    summary_row(out, current_label(tuner), s.scene().name, s.watched(), s.params(), s.rules(),
                s.result());
}

void export_csv(const Tuner& tuner, const ExportPaths& paths, bool current) {
  const std::filesystem::path dir = std::filesystem::path(paths.traces_csv).parent_path();
  std::error_code ec;
  if (!dir.empty()) std::filesystem::create_directories(dir, ec);
  write_file_atomic(paths.traces_csv, [&](std::ostream& out) { write_runs_trace_csv(out, tuner, current); });
  write_file_atomic(paths.runs_csv, [&](std::ostream& out) { write_runs_summary_csv(out, tuner, current); });
  const Session& s = tuner.session();
  write_file_atomic(paths.step_vtu, [&](std::ostream& out) {
    write_vtu(out, s.model(), s.state(), s.workspace(), s.params().dt, {}, &s.params());
  });
}

}  // namespace dampbound::ui
