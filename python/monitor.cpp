// The monitor over the user's own NumPy arrays (include/dampbound/monitor.hpp), read in place.
#include <pybind11/stl.h>

#include <cmath>
#include <limits>
#include <optional>
#include <stdexcept>

#include "core/io/format.hpp"
#include "python/arrays.hpp"

namespace dampbound::python {

namespace {

DampingPolicy policy_arg(const std::string& s) {
  const auto p = parse_policy(s);
  if (!p) throw py::value_error("policy must be fixed, clamp, upper, lower or safe, got '" + s + "'");
  return *p;
}

Monitor make_monitor(const py::handle& mass, const py::handle& springs, const py::handle& stiffness,
                     const py::handle& rest_length, const py::object& anchor_stiffness,
                     const py::object& rest, const py::object& fixed) {
  py::array_t<double> km, ks, kl, ka, kr;
  const NodeScalars m = node_scalars_of(mass, "mass", km);
  const auto pairs = index_array(springs, "springs", m.size(), 2);
  Monitor mon(m, spring_pairs(pairs.data(), pairs.shape(0)),
              node_scalars_of(stiffness, "stiffness", ks),
              node_scalars_of(rest_length, "rest_length", kl));
  if (!anchor_stiffness.is_none()) {
    if (rest.is_none()) throw py::value_error("anchor_stiffness needs rest (N, 3)");
    mon.set_anchors(node_scalars_of(anchor_stiffness, "anchor_stiffness", ka),
                    node_vectors_of(rest, "rest", kr));
  } else if (!rest.is_none()) {
    throw py::value_error("rest needs anchor_stiffness (N,)");
  }
  if (!fixed.is_none()) {
    const std::vector<std::uint8_t> f = flags_of(fixed, "fixed");
    mon.set_fixed(f.data(), static_cast<Eigen::Index>(f.size()));
  }
  return mon;
}

}  // namespace

void bind_monitor(py::module_& m) {
  py::class_<MonitorReport>(m, "MonitorReport", "The runtime check of one step (paper sec. 5).")
      .def_readonly("violating", &MonitorReport::violating,
                    "nodes whose effective gamma is outside [gamma_lo, gamma_hi]")
      .def_readonly("unstabilisable", &MonitorReport::unstabilisable,
                    "nodes with gamma_lo > gamma_hi (no damping satisfies both)")
      .def_readonly("clamped", &MonitorReport::clamped, "nodes the policy changed")
      .def_readonly("first_violating", &MonitorReport::first_violating, "-1 when none")
      .def_readonly("first_unstabilisable", &MonitorReport::first_unstabilisable, "-1 when none")
      .def_readonly("unguaranteed", &MonitorReport::unguaranteed,
                    "nodes with gamma_lo > gamma_safe (SPEC 9; counted when x is given)")
      .def_readonly("compressed_springs", &MonitorReport::compressed_springs,
                    "springs shorter than their rest length at x: SPEC 9 guarantees nothing")
      .def_property_readonly("ok", &MonitorReport::ok, "no node violating or unstabilisable")
      .def("__repr__", [](const MonitorReport& r) {  // the verdict first, as the CLI says it
        auto nodes = [](int n) { return std::to_string(n) + (n == 1 ? " node" : " nodes"); };
        std::string text = r.ok() ? "ok: every node's damping within [gamma_lo, gamma_hi]"
                                  : "NOT ok: ";
        if (r.violating > 0)
          text += nodes(r.violating) + " outside [gamma_lo, gamma_hi] (first " +
                  std::to_string(r.first_violating) + ")";
        if (r.unstabilisable > 0)
          text += std::string(r.violating > 0 ? "; " : "") + nodes(r.unstabilisable) +
                  " with gamma_lo > gamma_hi (first " + std::to_string(r.first_unstabilisable) + ")";
        if (r.clamped > 0) text += "; the policy changed " + nodes(r.clamped);
        if (r.unguaranteed > 0) text += "; " + nodes(r.unguaranteed) + " with gamma_lo > gamma_safe";
        return "MonitorReport(" + text + ")";
      });

  py::class_<MonitorLimits>(m, "MonitorLimits", "SPEC 7's exact limits at a state.")
      .def_readonly("lambda_max", &MonitorLimits::lambda_max,
                    "largest eigenvalue of M^-1 K (1/s^2)")
      .def_readonly("stable", &MonitorLimits::stable,
                    "the step with these gamma_i, dt does not grow")
      .def_readonly("scale_lo", &MonitorLimits::scale_lo,
                    "s * gamma_i stable for scale_lo <= s < scale_hi")
      .def_readonly("scale_hi", &MonitorLimits::scale_hi)
      .def_readonly("dt_max", &MonitorLimits::dt_max, "largest stable dt with these gamma_i (s)")
      .def_readonly("rate_max", &MonitorLimits::rate_max,
                    "uniform gamma_i/m_i must stay below 2/dt - lambda_max dt/2 (1/s)")
      .def_readonly("dt_max_undamped", &MonitorLimits::dt_max_undamped, "2/sqrt(lambda_max) (s)")
      .def_readonly("indefinite", &MonitorLimits::indefinite,
                    "K is indefinite at x: a mode grows whatever gamma and dt (stable False, "
                    "scale_hi, dt_max, rate_max, dt_max_undamped 0)")
      .def_property_readonly(
          "computed", [](const MonitorLimits& l) { return !l.not_computed; },
          "False when one factorisation would exceed factor_budget_gflop (numbers NaN)")
      .def_readonly("reason", &MonitorLimits::not_computed,
                    "why nothing was computed (None when computed)")
      .def_readonly("lambda_max_at_least", &MonitorLimits::lambda_max_at_least,
                    "not computed: lambda_max is at least this (a Lanczos Rayleigh quotient; "
                    "NaN when computed)")
      .def_readonly("scale_unstable_from", &MonitorLimits::scale_unstable_from,
                    "not computed: s * gamma_i is proved unstable at dt for every s >= this")
      .def_readonly("dt_unstable_from", &MonitorLimits::dt_unstable_from,
                    "not computed: every dt >= this is proved unstable with these gamma_i")
      .def_readonly("scale_stable_up_to", &MonitorLimits::scale_stable_up_to,
                    "not computed, no spring compressed: s * gamma_i is proved stable at dt for "
                    "every s in [0, this] (Gershgorin, SPEC 9; NaN otherwise)")
      .def_readonly("dt_stable_up_to", &MonitorLimits::dt_stable_up_to,
                    "not computed, no spring compressed: every dt <= this is proved stable "
                    "with these gamma_i (NaN otherwise)")
      .def("__repr__", [](const MonitorLimits& l) {  // the answer first, as the CLI says it
        if (l.not_computed) return "MonitorLimits(not computed: " + *l.not_computed + ")";
        if (l.indefinite)
          return std::string("MonitorLimits(NOT stable: K is indefinite at x, a mode grows "
                             "whatever the damping and dt)");
        return "MonitorLimits(" + std::string(l.stable ? "stable" : "NOT stable") +
               " at these gamma_i and dt; dt < " + format_human(l.dt_max) +
               " s; s * gamma_i stable for s in [" + format_human(l.scale_lo) + ", " +
               format_human(l.scale_hi) + "); lambda_max " + format_human(l.lambda_max) +
               " 1/s^2)";
      });

  py::class_<Monitor>(m, "Monitor",
                      "The paper's bounds over your own mass-spring arrays. Topology is copied "
                      "once; per-step arrays (x, v, force, gamma) are read in place when they "
                      "are float64 with adjacent columns.")
      .def(py::init(&make_monitor), py::arg("mass"), py::arg("springs"), py::arg("stiffness"),
           py::arg("rest_length"), py::arg("anchor_stiffness") = py::none(),
           py::arg("rest") = py::none(), py::arg("fixed") = py::none(),
           "mass (N,) m_i > 0 (mass unit); springs (S, 2) node indices; stiffness (S,) "
           "kappa_ij (mass unit/s^2); rest_length (S,) l0_ij (cm); optional anchors: "
           "anchor_stiffness (N,) (0 = none) with rest (N, 3) positions X_i (cm); fixed (N,).")
      .def_property_readonly("node_count", &Monitor::node_count)
      .def_property(
          "threads", &Monitor::threads,
          [](Monitor& mon, int threads) {
            if (threads < 0) throw py::value_error("threads must be >= 0 (0: one per CPU)");
            py::gil_scoped_release release;  // waits for a call on another thread to finish
            mon.set_threads(threads);
          },
          "threads for each call's loops over nodes and springs (1 by default, 0 = one per "
          "CPU); the results are the same bits on any count")
      .def(
          "lower_bounds",
          [](const Monitor& mon) {
            py::array_t<double> out(mon.node_count());
            mon.lower_bounds(node_scalars_out(out.mutable_data(), out.shape(0)));
            return out;
          },
          "(N,) paper eq. 5: gamma_lo_i = 2 sqrt(m_i kappa_i), kappa_i the largest incident "
          "stiffness (mass unit/s)")
      .def(
          "upper_bounds",
          [](const Monitor& mon, const py::handle& v, const py::handle& force, double dt) {
            py::array_t<double> kv, kf, out(mon.node_count());
            const NodeVectors vv = node_vectors_of(v, "v", kv), ff = node_vectors_of(force, "force", kf);
            auto o = node_scalars_out(out.mutable_data(), out.shape(0));
            {
              py::gil_scoped_release release;
              mon.upper_bounds(vv, ff, dt, o);
            }
            return out;
          },
          py::arg("v"), py::arg("force"), py::arg("dt"),
          "(N,) paper eq. 6 at t: |v_i m_i/dt + F_i| / |v_i| (mass unit/s; inf where v_i = 0). "
          "v (N, 3) cm/s, force (N, 3) the internal force F_i, dt (s).")
      .def(
          "check",
          [](const Monitor& mon, const py::handle& v, const py::handle& force,
             const py::handle& gamma, double dt, const std::string& policy, double factor,
             const py::object& gamma_eff, const py::object& x) {
            py::array_t<double> kv, kf, kg, kx;
            py::array_t<double> out = out_array(gamma_eff, "gamma_eff", mon.node_count());
            auto ge = node_scalars_out(out.mutable_data(), out.shape(0),
                                       out.strides(0) / static_cast<py::ssize_t>(sizeof(double)));
            const DampingPolicy p = policy_arg(policy);
            const NodeVectors vv = node_vectors_of(v, "v", kv), ff = node_vectors_of(force, "force", kf);
            const NodeScalars gg = node_scalars_of(gamma, "gamma", kg);
            MonitorReport r;
            if (x.is_none()) {
              py::gil_scoped_release release;
              r = mon.check(vv, ff, gg, dt, p, factor, &ge);
            } else {
              const NodeVectors xx = node_vectors_of(x, "x", kx);
              py::gil_scoped_release release;
              r = mon.check(xx, vv, ff, gg, dt, p, factor, &ge);
            }
            return py::make_tuple(r, out);
          },
          py::arg("v"), py::arg("force"), py::arg("gamma"), py::arg("dt"),
          py::arg("policy") = "fixed", py::arg("factor") = 1.0, py::arg("gamma_eff") = py::none(),
          py::arg("x") = py::none(),
          "The runtime check of one step: bounds from (v, force) at t and the effective damping "
          "of every free node under policy (SPEC 4). gamma (N,) the user's gamma_i (mass "
          "unit/s). Returns (MonitorReport, gamma_eff (N,)); gamma_eff is written in place when "
          "given. The 'safe' policy (SPEC 9) needs the positions x (N, 3) at t (cm); with x the "
          "report also counts unguaranteed nodes and compressed springs.")
      .def(
          "safe_bounds",
          [](const Monitor& mon, const py::handle& x, double dt) {
            py::array_t<double> kx, out(mon.node_count());
            const NodeVectors xx = node_vectors_of(x, "x", kx);
            auto o = node_scalars_out(out.mutable_data(), out.shape(0));
            {
              py::gil_scoped_release release;
              mon.safe_bounds(xx, dt, o);
            }
            return out;
          },
          py::arg("x"), py::arg("dt"),
          "(N,) SPEC 9 at positions x (N, 3) cm: gamma_safe_i = 2 m_i/dt - m_i dt R_i/2 (mass "
          "unit/s; inf for fixed nodes). Damping below it at every node keeps the paper's step, "
          "linearised at x, from growing.")
      .def(
          "internal_forces",
          [](const Monitor& mon, const py::handle& x) {
            py::array_t<double> kx;
            py::array_t<double> out({static_cast<py::ssize_t>(mon.node_count()), py::ssize_t{3}});
            Eigen::Map<Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>> f(
                out.mutable_data(), mon.node_count(), 3);
            const NodeVectors xx = node_vectors_of(x, "x", kx);
            {
              py::gil_scoped_release release;
              mon.internal_forces(xx, f);
            }
            return out;
          },
          py::arg("x"),
          "(N, 3) F_i of SPEC 1 at positions x (cm): springs and anchors, no damping "
          "(mass unit cm/s^2).")
      .def(
          "exact_limits",
          [](const Monitor& mon, const py::handle& x, const py::handle& gamma, double dt,
             std::optional<double> budget_gflop) {
            py::array_t<double> kx, kg;
            if (budget_gflop && !(std::isfinite(*budget_gflop) && *budget_gflop > 0))
              throw py::value_error("factor_budget_gflop must be a finite number > 0 (None: no limit)");
            const NodeVectors xx = node_vectors_of(x, "x", kx);
            const NodeScalars gg = node_scalars_of(gamma, "gamma", kg);
            py::gil_scoped_release release;
            return mon.exact_limits(
                xx, gg, dt,
                budget_gflop ? *budget_gflop * 1e9 : std::numeric_limits<double>::infinity());
          },
          py::arg("x"), py::arg("gamma"), py::arg("dt"), py::arg("factor_budget_gflop") = py::none(),
          "SPEC 7: the exact linear stability of the paper's step at positions x (cm) with "
          "damping gamma (N,) and step dt (s). factor_budget_gflop: over it (CHOLMOD's "
          "prediction for one factorisation) nothing is computed: computed is False, reason says why.");
}

}  // namespace dampbound::python
