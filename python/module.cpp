// The `dampbound` Python module: scenes, a Session with NumPy views of its state, the
// protocol's result, the per-node bounds (eq. 5, eq. 6), and (monitor.cpp, analysis.cpp) the
// monitor over the user's own arrays, the exact limits and suggest. Units: cm, s and any
// consistent mass unit, as everywhere in dampbound.
#include <pybind11/eval.h>
#include <pybind11/stl.h>

#include <stdexcept>
#include <unordered_set>

#include "core/io/format.hpp"
#include "core/io/report.hpp"
#include "core/io/scene_file.hpp"
#include "dampbound/physics/error.hpp"
#include "dampbound/run/session.hpp"
#include "dampbound/version.hpp"
#include "python/arrays.hpp"

namespace dampbound::python {

namespace {
std::unordered_set<const void*>& sessions_in_use() {
  static std::unordered_set<const void*> in_use;
  return in_use;
}
}  // namespace

SessionInUse::SessionInUse(const void* session) : session_(session) {
  require_idle(session);
  sessions_in_use().insert(session);
}

SessionInUse::~SessionInUse() { sessions_in_use().erase(session_); }

void SessionInUse::require_idle(const void* session) {
  if (sessions_in_use().count(session))
    throw std::runtime_error("the session is busy in a call on another thread (run, step or "
                             "exact_limits); wait for it to return");
}

namespace {

/// The session behind `self`, when no call on another thread is using it.
const Session& idle(const py::object& self) {
  const Session& s = self.cast<const Session&>();
  SessionInUse::require_idle(&s);
  return s;
}

DampingPolicy policy_of(const std::string& s) {
  const auto p = parse_policy(s);
  if (!p) throw py::value_error("policy must be fixed, clamp, upper or lower, got '" + s + "'");
  return *p;
}

Integrator integrator_of(const std::string& s) {
  const auto i = parse_integrator(s);
  if (!i)
    throw py::value_error("unknown integrator '" + s + "': use " + one_of(integrator_names()));
  return *i;
}

// The names come from the one table (params.hpp's kIntegratorTable); the first is the paper's.
const std::string& integrator_doc() {
  static const std::string doc =
      "one of " + one_of(integrator_names()) + "; the first, the paper's, is the default";
  return doc;
}

void bind_params(py::module_& m) {
  py::class_<Params>(m, "Params",
                     "The user's parameters (paper eq. 1); scene scales multiply them.")
      .def(py::init<>())
      .def_readwrite("m", &Params::m, "node mass (mass unit)")
      .def_readwrite("kappa", &Params::kappa, "spring and anchor stiffness (mass unit/s^2)")
      .def_readwrite("gamma", &Params::gamma, "user's viscous damping (mass unit/s)")
      .def_readwrite("zeta", &Params::zeta,
                     "the nodal damping ratio in place of gamma (None: use gamma): every call "
                     "that takes these params sets gamma_i = zeta * 2 sqrt(m_i kappa_i) at each "
                     "node, as the CLI's --zeta does")
      .def_readwrite("dt", &Params::dt, "time step (s)")
      .def_property(
          "policy", [](const Params& p) { return std::string(to_string(p.policy)); },
          [](Params& p, const std::string& s) { p.policy = policy_of(s); },
          "damping policy (SPEC 4): 'fixed', 'clamp', 'upper' or 'lower'")
      .def_readwrite("factor", &Params::factor, "multiplier of gamma_hi for policy 'upper'")
      .def_readwrite("kd", &Params::kd,
                     "dashpots along every spring and anchor (SPEC 10, mass unit/s): kd_ij = kd "
                     "* kd_scale; the CLI's --kd, Warp's spring_kd")
      .def_readwrite("rayleigh_mass", &Params::rayleigh_mass,
                     "Rayleigh alpha (SPEC 10, 1/s): force -alpha m_i v_i")
      .def_readwrite("rayleigh_stiffness", &Params::rayleigh_stiffness,
                     "Rayleigh beta (SPEC 10, s): force -beta (K(x) v)_i")
      .def_property(
          "integrator", [](const Params& p) { return std::string(to_string(p.integrator)); },
          [](Params& p, const std::string& s) { p.integrator = integrator_of(s); },
          integrator_doc().c_str())
      .def("__repr__", [](const Params& p) {
        // format_number: the exact value in the "C" locale (%f showed 1e-9 as 0.000000).
        return "Params(m=" + format_number(p.m) + ", kappa=" + format_number(p.kappa) +
               (p.zeta ? ", zeta=" + format_number(*p.zeta) : ", gamma=" + format_number(p.gamma)) +
               ", dt=" + format_number(p.dt) +
               (p.kd != 0 ? ", kd=" + format_number(p.kd) : std::string()) +
               (p.rayleigh_mass != 0 ? ", rayleigh_mass=" + format_number(p.rayleigh_mass)
                                     : std::string()) +
               (p.rayleigh_stiffness != 0
                    ? ", rayleigh_stiffness=" + format_number(p.rayleigh_stiffness)
                    : std::string()) +
               ", policy='" + to_string(p.policy) + "')";
      });

  py::class_<StopRules>(m, "StopRules", "When a protocol run stops (SPEC 5).")
      .def(py::init<>())
      .def_readwrite("reference", &StopRules::reference, "perturbation magnitude (cm)")
      .def_readwrite("restore_fraction", &StopRules::restore_fraction,
                     "restored below fraction * reference")
      .def_readwrite("diverge_factor", &StopRules::diverge_factor,
                     "diverged above factor * reference")
      .def_readwrite("max_iterations", &StopRules::max_iterations, "iteration limit")
      .def_property(
          "rule", [](const StopRules& r) { return std::string(to_string(r.rule)); },
          [](StopRules& r, const std::string& s) {
            const auto rule = parse_stop_rule(s);
            if (!rule) throw py::value_error("rule must be first-entry or settled, got '" + s + "'");
            r.rule = *rule;
          },
          "'settled' (the default, SPEC 8: step to the limit) or 'first-entry' (the paper's, SPEC 5)");
}

/// An iteration, or None where the result has none (0), as the JSON's null.
py::object iteration_or_none(int iteration) {
  return iteration > 0 ? py::object(py::int_(iteration)) : py::object(py::none());
}

void bind_results(py::module_& m) {
  py::class_<RunResult>(m, "RunResult", "The result of a protocol run (SPEC 5).")
      .def_property_readonly(
          "outcome", [](const RunResult& r) { return std::string(to_string(r.outcome)); },
          "'running', 'restored', 'diverged', 'not_restored' (first-entry "
          "rule), 'settled', 'not_settled' (settled rule)")
      .def_readonly("iterations", &RunResult::iterations, "iteration of the outcome")
      .def_property_readonly(
          "first_entry", [](const RunResult& r) { return iteration_or_none(r.first_entry); },
          "first iteration below the restore threshold (None: never)")
      .def_property_readonly(
          "left_at", [](const RunResult& r) { return iteration_or_none(r.left_at); },
          "first iteration back at or above it after an entry (None: never)")
      .def_property_readonly(
          "settled_at", [](const RunResult& r) { return iteration_or_none(r.settled_at); },
          "settled rule: below the threshold from here to the limit (None: not settled)")
      .def_readonly("max_displacement", &RunResult::max_displacement,
                    "max |x_i - X_i| at the last iteration (cm; inf if not finite)")
      .def_readonly("violations", &RunResult::violations,
                    "node-steps whose effective gamma was outside [gamma_lo, gamma_hi]")
      .def_readonly("unstabilisable", &RunResult::unstabilisable,
                    "node-steps with gamma_lo > gamma_hi")
      .def_readonly("clamped", &RunResult::clamped, "node-steps whose gamma the policy changed")
      .def_readonly("zero_length_springs", &RunResult::zero_length_springs,
                    "spring-steps skipped for having no direction")
      .def_readonly("time", &RunResult::time, "simulated time (s)")
      .def("__repr__", [](const RunResult& r) {
        return "RunResult(" + verdict_short(r) + "; max |x-X| = " +
               format_human(r.max_displacement) + " cm at t = " + format_human(r.time) + " s)";
      });

  py::class_<NodeSample>(m, "NodeSample", "What the watched node showed in one step.")
      .def_readonly("displacement", &NodeSample::displacement, "|x_c - X_c| (cm)")
      .def_readonly("lower", &NodeSample::lower, "gamma_lo")
      .def_readonly("upper", &NodeSample::upper, "gamma_hi at t (may be inf)")
      .def_readonly("gamma", &NodeSample::gamma, "the user's gamma")
      .def_readonly("gamma_eff", &NodeSample::gamma_eff, "the effective gamma of the step")
      .def_readonly("safe", &NodeSample::safe, "gamma_safe at t (SPEC 9)");

  py::class_<StepSample>(m, "StepSample", "What one step reports (SPEC 3).")
      .def_readonly("iteration", &StepSample::iteration, "steps completed, from 1")
      .def_readonly("time", &StepSample::time, "s, after the step")
      .def_readonly("watched", &StepSample::watched, "the watched node's NodeSample")
      .def_readonly("max_displacement", &StepSample::max_displacement, "cm, inf if not finite")
      .def_readonly("violating", &StepSample::violating, "nodes outside the bounds")
      .def_readonly("unstabilisable", &StepSample::unstabilisable, "nodes with gamma_lo > gamma_hi")
      .def_readonly("clamped", &StepSample::clamped, "nodes the policy changed")
      .def_readonly("finite", &StepSample::finite, "every coordinate finite");
}

void bind_scene(py::module_& m) {
  py::class_<SceneSpec>(m, "Scene", "A scene file's model, parameters, perturbation and rules.")
      .def_readonly("name", &SceneSpec::name)
      .def_readonly("description", &SceneSpec::description)
      .def_readonly("path", &SceneSpec::path)
      .def_property(
          "params", [](const SceneSpec& s) { return s.params; },
          [](SceneSpec& s, const Params& p) { s.params = p; },
          "the scene's parameters (a copy: assign a Params to change them)")
      .def_property(
          "rules", [](const SceneSpec& s) { return s.rules; },
          [](SceneSpec& s, const StopRules& r) { s.rules = r; },
          "the scene's stop rules (a copy: assign a StopRules to change them)")
      .def_readonly("watched", &SceneSpec::watched, "index of the watched node")
      .def_property_readonly("node_count", [](const SceneSpec& s) { return s.model.node_count(); })
      .def_property_readonly("spring_count",
                             [](const SceneSpec& s) { return s.model.spring_count(); })
      .def_property_readonly(
          "rest",
          [](py::object self) { return view_of(self.cast<const SceneSpec&>().model.rest, self); },
          "(N, 3) rest positions X_i (cm), read-only view")
      .def(
          "arrays",
          [](const SceneSpec& s, const Params* params) {
            // The model with params applied, as the arrays a Monitor takes (copies).
            const ResolvedScene r(s, params);
            const Model mo = compile_model(r.scene().model, r.params());
            py::array_t<int> pairs({static_cast<py::ssize_t>(mo.spec().spring_count()), py::ssize_t{2}});
            py::array_t<double> kappa(mo.spec().spring_count()), l0(mo.spec().spring_count());
            for (int k = 0; k < mo.spec().spring_count(); ++k) {
              const Spring& sp = mo.spec().springs[static_cast<size_t>(k)];
              pairs.mutable_at(k, 0) = sp.i;
              pairs.mutable_at(k, 1) = sp.j;
              kappa.mutable_at(k) = mo.spring_kappa[static_cast<size_t>(k)];
              l0.mutable_at(k) = sp.rest_length;
            }
            py::dict d;
            d["mass"] = py::array_t<double>(mo.mass.size(), mo.mass.data());
            d["gamma"] = py::array_t<double>(mo.gamma.size(), mo.gamma.data());
            const std::vector<double> zeta = damping_ratio(mo);
            d["zeta"] = py::array_t<double>(zeta.size(), zeta.data());
            d["springs"] = pairs;
            d["stiffness"] = kappa;
            d["rest_length"] = l0;
            d["anchor_stiffness"] =
                py::array_t<double>(mo.anchor_kappa.size(), mo.anchor_kappa.data());
            d["rest"] =
                py::array_t<double>({static_cast<py::ssize_t>(mo.spec().rest.size()), py::ssize_t{3}},
                                    mo.spec().rest.empty() ? nullptr : mo.spec().rest.front().data());
            d["fixed"] = py::array_t<std::uint8_t>(mo.spec().fixed.size(), mo.spec().fixed.data());
            return d;
          },
          py::arg("params") = nullptr,
          "The model with params (default: the scene's) applied, as NumPy arrays (copies) in "
          "the Monitor's terms: mass (N,), gamma (N,), zeta (N,: gamma_i / 2 sqrt(m_i kappa_i), NaN "
          "without a spring or anchor), springs (S, 2), stiffness (S,), "
          "rest_length (S,), anchor_stiffness (N,), rest (N, 3), fixed (N,).");
  m.def(
      "load_scene",
      [](const std::string& path) {
        // A C path ends at its first NUL: "a.toml\0b" would load a.toml.
        if (path.find('\0') != std::string::npos)
          throw py::value_error("path contains a NUL character");
        return load_scene(path);
      },
      py::arg("path"), "Loads a scene file (TOML); ValueError naming the file and line if bad.");
  m.def("paper_plane_scene", &paper_plane_scene, py::arg("n") = 36,
        "SPEC 5's scene built in code: an n x n grid, node (n/2, n/2) moved 5 cm along y.");
}

void bind_session(py::module_& m) {
  py::class_<Session>(m, "Session",
                      "A running experiment: the scene's model and state, stepped by the one "
                      "step() of dampbound. Array properties are read-only NumPy views of the "
                      "session's own memory (no copies), valid while the session lives.")
      .def(py::init([](const SceneSpec& scene, const Params* params, const StopRules* rules) {
             const ResolvedScene r(scene, params);
             // The CLI's default: the settled rule, unless the rules given say otherwise.
             StopRules settled = scene.rules;
             settled.rule = StopRule::settled;
             return Session(r.scene(), r.params(), rules ? *rules : settled);
           }),
           py::arg("scene"), py::arg("params") = nullptr, py::arg("rules") = nullptr,
           "Starts from the scene's perturbed state; params default to the scene's, rules to "
           "the scene's under the settled rule (as `dampbound run`; pass rules with rule = "
           "'first-entry' for the paper's).")
      .def(
          "step",
          [](Session& s, int n) {
            if (n < 1) throw py::value_error("n must be >= 1");
            SessionInUse use(&s);
            py::gil_scoped_release release;
            for (int k = 1; k < n; ++k) s.step_once();
            return StepSample(s.step_once());
          },
          py::arg("n") = 1, "Takes n steps of params.dt seconds; returns the last StepSample.")
      .def(
          "run",
          [](Session& s) {
            SessionInUse use(&s);
            py::gil_scoped_release release;
            return RunResult(s.run_to_end());
          },
          "Steps until restored, diverged or the iteration limit (SPEC 5); returns RunResult.")
      .def_property(
          "params", [](const py::object& self) { return idle(self).params(); },
          [](Session& s, const Params& p) {
            SessionInUse::require_idle(&s);
            s.set_params(p);
          },
          "parameters (a copy); assign a new Params to change them at the next step")
      .def_property_readonly(
          "result", [](const py::object& self) { return idle(self).result(); },
          "the protocol's result so far")
      .def_property_readonly("running", [](const py::object& self) { return idle(self).running(); })
      .def_property_readonly("iteration",
                             [](const py::object& self) { return idle(self).state().iteration; })
      .def_property_readonly(
          "time", [](const py::object& self) { return idle(self).state().time; }, "s")
      .def_property_readonly(
          "positions",
          [](py::object self) { return view_of(idle(self).state().x, self); },
          "(N, 3) positions x_i (cm), read-only view")
      .def_property_readonly(
          "velocities",
          [](py::object self) { return view_of(idle(self).state().v, self); },
          "(N, 3) velocities v_i (cm/s), read-only view")
      .def_property_readonly(
          "lower_bounds",
          [](py::object self) {
            const Session& s = idle(self);
            return view_of_shared(s.model().lower_bound, s.shared_model());
          },
          "(N,) paper eq. 5: gamma_lo_i = 2 sqrt(m_i kappa_i) (mass unit/s) of the model as it "
          "is when read: a cut or new params later give the session a new model, and this view "
          "keeps showing the one it was taken from")
      .def_property_readonly(
          "upper_bounds",
          [](py::object self) {
            return view_of(idle(self).workspace().upper_bound, self);
          },
          "(N,) paper eq. 6 of the last step: gamma_hi_i (mass unit/s; inf where v_i = 0)")
      .def_property_readonly(
          "gamma_eff",
          [](py::object self) {
            return view_of(idle(self).workspace().gamma_eff, self);
          },
          "(N,) the effective damping of the last step (mass unit/s)")
      .def_property_readonly(
          "displacements",
          [](const py::object& self) {
            const Session& s = idle(self);
            py::array_t<double> d(s.model().spec().node_count());
            for (int i = 0; i < s.model().spec().node_count(); ++i)
              d.mutable_at(i) = displacement(s.model(), s.state(), i);
            return d;
          },
          "(N,) |x_i - X_i| (cm), a new array");
}

}  // namespace

// Results that are dicts of numbers (suggest, ...) read first as the CLI's answer: a dict
// subclass whose repr is d["answer"].
void bind_answers(py::module_& m) {
  py::exec(R"py(
class Answer(dict):
    """A result as a dict of its numbers; its repr is the answer (key 'answer') the CLI opens with."""
    __slots__ = ()
    def __repr__(self):
        if "answer" not in self:
            return dict.__repr__(self)
        return "%s(%s)" % (type(self).__name__, self["answer"])

class Suggestion(Answer):
    """suggest()'s result: the numbers, the verifying runs and the answer line(s)."""
    __slots__ = ()
)py",
           m.attr("__dict__"));
  m.attr("Answer").attr("__module__") = "dampbound";
  m.attr("Suggestion").attr("__module__") = "dampbound";
}

void bind_linear_limits(py::module_& m);  // python/linear_limits.cpp
void bind_meshes(py::module_& m);         // python/meshes.cpp
void bind_mass_scaling(py::module_& m);   // python/mass_scaling.cpp
void bind_knobs(py::module_& m);          // python/knobs.cpp

}  // namespace dampbound::python

PYBIND11_MODULE(dampbound, m) {
  using namespace dampbound::python;
  m.doc() =
      "dampbound: damping bounds that guarantee stability in mass-spring systems (Bhasin & "
      "Liu). Units: cm, s, and any consistent mass unit.";
  m.attr("__version__") = DAMPBOUND_VERSION;
  // Bad input (a scene file, a parameter) is core's InputError: Python's ValueError.
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const dampbound::InputError& e) {
      PyErr_SetString(PyExc_ValueError, e.what());
    }
  });
  bind_answers(m);
  bind_params(m);
  bind_results(m);
  bind_scene(m);
  bind_session(m);
  bind_monitor(m);
  bind_analysis(m);
  bind_linear_limits(m);
  bind_meshes(m);
  bind_mass_scaling(m);
  bind_knobs(m);
}
