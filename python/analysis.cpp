// The exact limits of SPEC 7 for a scene's model and suggest (core/analysis/suggest.hpp) in Python.
#include <pybind11/stl.h>

#include <cmath>
#include <optional>
#include <string>
#include <vector>

#include "core/analysis/answer.hpp"
#include "core/analysis/equilibrium.hpp"
#include "core/analysis/linear_stability_exact.hpp"
#include "core/analysis/suggest.hpp"
#include "dampbound/physics/error.hpp"
#include "dampbound/run/session.hpp"
#include "python/arrays.hpp"

namespace dampbound::python {

namespace {

std::string joined(const std::vector<std::string>& lines) {
  std::string text;
  for (const std::string& line : lines) text += (text.empty() ? "" : "; ") + line;
  return text;
}

py::dict runs_dict(const std::vector<VerifiedRun>& runs) {
  py::dict d;
  for (const VerifiedRun& r : runs) d[py::str(r.label)] = py::make_tuple(r.params, r.result);
  return d;
}

}  // namespace

void bind_analysis(py::module_& m) {
  py::class_<ExactStability::Unfactored>(
      m, "UnfactoredBounds",
      "Over the factorisation budget: what plain Lanczos, Gershgorin and the node-block splitting "
      "prove without a "
      "factorisation (docs/criteria.md).")
      .def_readonly("lambda_max_lo", &ExactStability::Unfactored::lambda_max_lo,
                    "lambda_max of M^-1 K is at least this (a Rayleigh quotient; 1/s^2)")
      .def_readonly("lambda_max_hi", &ExactStability::Unfactored::lambda_max_hi,
                    "and at most this (the lower of Gershgorin's bound and the node-block "
                    "splitting's; 1/s^2)")
      .def_readonly("lambda_patch_nodes", &ExactStability::Unfactored::lambda_patch_nodes,
                    "where A's own top is local: the nodes of the patch around it that narrowed "
                    "the bracket (0: none did)")
      .def_readonly("index_at_least", &ExactStability::Unfactored::index_at_least,
                    "the paper's step: lambda_max(dt^2 A + 2 dt C) is at least this; >= 4 "
                    "proves the step unstable (NaN for other integrators)")
      .def_readonly("index_at_most", &ExactStability::Unfactored::index_at_most,
                    "the paper's step with no spring compressed: the index is at most this "
                    "(the lowest of Gershgorin on its rows, SPEC 9's safe bound, the node-block "
                    "splitting and the patch around the index's top); < 4 proves it stable (NaN "
                    "otherwise)")
      .def_readonly("patch_nodes", &ExactStability::Unfactored::patch_nodes,
                    "the paper's step: the nodes of the patch around the index's top whose "
                    "proofs are taken where they prove more (0: its top is not local)")
      .def_readonly("index_patch", &ExactStability::Unfactored::index_patch,
                    "the patch's upper bound on the index where it is index_at_most (NaN "
                    "otherwise)")
      .def_readonly("gamma_unstable_from", &ExactStability::Unfactored::gamma_unstable_from,
                    "every gamma from this on is proved unstable at dt (inf: none is; NaN: not "
                    "the paper's step)")
      .def_readonly("dt_unstable_from", &ExactStability::Unfactored::dt_unstable_from,
                    "every dt from this on is proved unstable at gamma (inf: none is; the "
                    "paper's step, and forward Euler and Verlet at uniform gamma/m)")
      .def_readonly("mode_unstable_from", &ExactStability::Unfactored::mode_unstable_from,
                    "forward Euler, Verlet and RK4 at uniform gamma/m: every mode with lambda from "
                    "this on is unstable at gamma and dt, so lambda_max_lo >= it proves the "
                    "step unstable (NaN otherwise)")
      .def_readonly("gamma_unstable_below", &ExactStability::Unfactored::gamma_unstable_below,
                    "forward Euler and Verlet at uniform gamma/m: every gamma up to this is "
                    "proved unstable at dt (-inf: none is; NaN otherwise)")
      .def_readonly("stable_lambda_hi", &ExactStability::Unfactored::stable_lambda_hi,
                    "forward Euler, Verlet and RK4 at uniform gamma/m with K >= 0 proved: every "
                    "mode lies in [0, this] (lambda_max_hi; NaN otherwise); `stable` says "
                    "whether the user's gamma and dt are proved stable")
      .def_readonly("dt_stable_up_to", &ExactStability::Unfactored::dt_stable_up_to,
                    "every dt up to this is proved stable at gamma (those integrators, and the "
                    "paper's step by index_at_most; NaN otherwise)")
      .def_readonly("gamma_stable_lo", &ExactStability::Unfactored::gamma_stable_lo,
                    "and every gamma in [gamma_stable_lo, gamma_stable_hi] at dt (none when lo > "
                    "hi; NaN otherwise)")
      .def_readonly("gamma_stable_hi", &ExactStability::Unfactored::gamma_stable_hi)
      .def_readonly("lanczos_steps", &ExactStability::Unfactored::lanczos_steps)
      .def_readonly("unconditional", &ExactStability::Unfactored::unconditional,
                    "implicit Euler with K proved positive semidefinite: stable for every dt "
                    "and gamma (no factorisation needed)");
  py::class_<ExactStability>(m, "ExactStability",
                             "SPEC 7's exact linear stability of a model at a state.")
      .def_property_readonly(
          "method", [](const ExactStability& e) { return std::string(to_string(e.method)); })
      .def_readonly("uniform_rate", &ExactStability::uniform_rate, "gamma_i/m_i equal everywhere")
      .def_property_readonly(
          "lambda_max", [](const ExactStability& e) { return e.spectrum.lambda_max; },
          "largest eigenvalue of M^-1 K (1/s^2)")
      .def_property_readonly(
          "lambda_min", [](const ExactStability& e) { return e.spectrum.lambda_min; },
          "smallest eigenvalue of M^-1 K (1/s^2)")
      .def_readonly("spectral_radius", &ExactStability::spectral_radius,
                    "of one step at the user's gamma and dt (NaN: not computed)")
      .def_readonly("stable", &ExactStability::stable, "the step does not grow")
      .def("__repr__",
           [](const ExactStability& e) {  // the CLI's answer lines (core/analysis/answer.hpp)
             std::string text;
             for (const std::string& line : exact_answer(e, nullptr, nullptr, "at the state"))
               text += (text.empty() ? "" : "; ") + line;
             return "ExactStability(" + text + ")";
           })
      .def_readonly(
          "gamma_lo", &ExactStability::gamma_lo,
          "the user's gamma is stable at dt for gamma_lo <= gamma < gamma_hi (mass unit/s)")
      .def_readonly("gamma_hi", &ExactStability::gamma_hi, "(mass unit/s; may be inf)")
      .def_readonly("dt_max", &ExactStability::dt_max, "largest stable dt at the user's gamma (s)")
      .def_property_readonly("computed", &ExactStability::computed,
                             "False when one factorisation would exceed factor_budget_gflop: "
                             "then every number is NaN")
      .def_property_readonly(
          "reason",
          [](const ExactStability& e) {
            return e.computed() ? std::nullopt : std::optional<std::string>(e.over_budget_reason());
          },
          "why nothing was computed (None when computed)")
      .def_property_readonly(
          "unfactored",
          [](const ExactStability& e) {
            return e.computed() ? std::nullopt
                                : std::optional<ExactStability::Unfactored>(e.unfactored);
          },
          "over the budget: the bounds proved without a factorisation (UnfactoredBounds; None "
          "when computed)");

  auto options = [](int threads, std::optional<double> budget_gflop) {
    if (threads < 0) throw py::value_error("threads must be >= 0 (0: one per CPU)");
    if (budget_gflop && !(std::isfinite(*budget_gflop) && *budget_gflop > 0))
      throw py::value_error("factor_budget_gflop must be a finite number > 0 (None: no limit)");
    ExactOptions o;
    o.threads = threads;
    if (budget_gflop) o.max_factor_flops = *budget_gflop * 1e9;
    return o;
  };
  m.def(
      "exact_limits",
      [options](const Session& s, int threads, std::optional<double> budget) {
        SessionInUse::require_idle(&s);
        const ExactOptions o = options(threads, budget);
        // A snapshot: the model is shared and never changed again, x and params are copies,
        // so the session may step on another thread while this runs without the GIL.
        const std::shared_ptr<const Model> model = s.shared_model();
        const std::vector<Vec3> x = s.state().x;
        const Params p = s.params();
        require_finite(node_vectors(x.front().data(), static_cast<Eigen::Index>(x.size())), "x");
        py::gil_scoped_release release;
        return exact_stability(*model, x, p, o);
      },
      py::arg("session"), py::arg("threads") = 1, py::arg("factor_budget_gflop") = py::none(),
      "SPEC 7: the exact limits of the session's model at its current state and parameters "
      "(lambda_max certified by sparse Cholesky, never a dense decomposition of a large mesh). "
      "threads: for the Lanczos products (0: one per CPU); the same bits on any count. "
      "factor_budget_gflop: when one factorisation would take more (CHOLMOD's prediction), "
      "nothing is factorised and the result has computed=False (None: no limit).");
  m.def(
      "exact_limits",
      [options](const SceneSpec& scene_in, const Params* params, int threads,
                std::optional<double> budget, const py::object& x) {
        const ResolvedScene resolved(scene_in, params);
        const SceneSpec& scene = resolved.scene();
        const Params& p = resolved.params();
        const ExactOptions o = options(threads, budget);
        std::vector<Vec3> at = scene.model.rest;
        if (!x.is_none()) {
          py::array_t<double> keep;
          const NodeVectors v = node_vectors_of(x, "x", keep);
          if (v.rows() != scene.model.node_count())
            throw py::value_error("x must have one row per node (" +
                                  std::to_string(scene.model.node_count()) + ")");
          require_finite(v, "x");
          for (Eigen::Index i = 0; i < v.rows(); ++i) at[static_cast<size_t>(i)] = v.row(i);
        }
        py::gil_scoped_release release;
        return exact_stability(compile_model(scene.model, p), at, p, o);
      },
      py::arg("scene"), py::arg("params") = nullptr, py::arg("threads") = 1,
      py::arg("factor_budget_gflop") = py::none(), py::arg("x") = py::none(),
      "SPEC 7: the exact limits of the scene's model with params (default: the scene's), "
      "linearised at rest or at the (N, 3) positions x (e.g. static_equilibrium's); threads "
      "and factor_budget_gflop as above.");
  m.def(
      "static_equilibrium",
      [options](const SceneSpec& scene_in, const Params* params, std::optional<double> budget) {
        const ResolvedScene resolved(scene_in, params);
        const SceneSpec& scene = resolved.scene();
        const Params& p = resolved.params();
        EquilibriumOptions o;
        o.max_factor_flops = options(1, budget).max_factor_flops;
        Equilibrium e;
        {
          py::gil_scoped_release release;
          e = static_equilibrium(compile_model(scene.model, p), o);
        }
        py::array_t<double> x({static_cast<py::ssize_t>(e.x.size()), py::ssize_t{3}});
        auto w = x.mutable_unchecked<2>();
        for (size_t i = 0; i < e.x.size(); ++i)
          for (int c = 0; c < 3; ++c) w(static_cast<py::ssize_t>(i), c) = e.x[i](c);
        py::dict d;
        d["x"] = x;
        d["converged"] = e.converged;
        d["iterations"] = e.iterations;
        d["net_force"] = e.net.largest;
        d["node"] = e.net.node;
        d["force_scale"] = e.net.scale;
        return d;
      },
      py::arg("scene"), py::arg("params") = nullptr, py::arg("factor_budget_gflop") = py::none(),
      "The static equilibrium under the scene's external forces and rest lengths (the CLI's "
      "bounds --equilibrium; Newton's method on the potential energy, where a damped run "
      "settles): a dict with x (N, 3), converged, iterations, net_force (the largest "
      "|F_i + f_i| at x), node (where) and force_scale (the largest force term). Over "
      "factor_budget_gflop: RuntimeError.");

  m.def(
      "suggest",
      [options](const SceneSpec& scene_in, const Params* params, const StopRules* rules,
                const std::string& what, bool verify, std::optional<double> factor_budget_gflop) {
        const ResolvedScene resolved(scene_in, params);
        const SceneSpec& scene = resolved.scene();
        const Params& p = resolved.params();
        const StopRules r = rules ? *rules : scene_in.rules;
        if (const auto why = validate(r)) throw py::value_error(*why);
        if (const auto why = validate(scene)) throw py::value_error("scene: " + *why);
        SuggestOptions o;
        o.verify = verify;
        o.max_factor_flops = options(1, factor_budget_gflop).max_factor_flops;
        py::dict d;
        if (what == "gamma") {
          DampingSuggestion s;
          {
            py::gil_scoped_release release;
            s = suggest_damping(scene, p, r, o);
          }
          d["dt"] = s.dt;
          d["gamma_min"] = s.gamma_min;
          d["gamma_max"] = s.gamma_max;
          d["min_by"] = s.min_by;
          d["max_by"] = s.max_by;
          d["empty"] = s.empty;
          d["gamma_best"] = s.gamma_best;
          d["best_method"] = s.best_method;
          d["dt_max_at_gamma_min"] = s.dt_max_at_gamma_min;
          d["proved_only"] = s.proved_only;
          d["gamma_unstable_from"] = s.gamma_unstable_from;
          d["runs"] = runs_dict(s.runs);
          d["answer"] = joined(damping_answer(s));
        } else if (what == "dt") {
          StepSuggestion s;
          {
            py::gil_scoped_release release;
            s = suggest_step(scene, p, r, o);
          }
          d["gamma"] = s.gamma;
          d["dt_exact"] = s.dt_exact;
          d["dt_all"] = s.dt_all;
          d["dt_all_by"] = s.dt_all_by;
          d["proved_only"] = s.proved_only;
          d["dt_unstable_from"] = s.dt_unstable_from;
          d["runs"] = runs_dict(s.runs);
          d["answer"] = joined(step_answer(s));
        } else {
          throw py::value_error("what must be 'gamma' or 'dt', got '" + what + "'");
        }
        return answer_dict("Suggestion", d);
      },
      py::arg("scene"), py::arg("params") = nullptr, py::arg("rules") = nullptr,
      py::arg("what") = "gamma", py::arg("verify") = true,
      py::arg("factor_budget_gflop") = py::none(),
      "Stable values for the scene (the CLI's `suggest`). what='gamma': at params.dt, the "
      "range of the user's gamma (mass unit/s) every applicable criterion accepts "
      "[gamma_min, gamma_max) and the fastest-settling gamma_best. what='dt': at params.gamma, "
      "the exact largest stable dt (s) and the largest dt every criterion accepts. verify=True "
      "runs each suggestion through a Session: runs maps a label to (Params, RunResult). "
      "Over factor_budget_gflop (default: none) proved_only is True: the range [gamma_min, "
      "gamma_max] and dt_exact are what is proved stable without a factorisation, the exact "
      "limits below gamma_unstable_from / dt_unstable_from. answer: the CLI's answer lines, "
      "which the result's repr shows.");
}

}  // namespace dampbound::python
