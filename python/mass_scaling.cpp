// dampbound.mass_scaling: SPEC 11's added mass for a target step, on a scene (as `suggest
// --mass-scale`) or on a user's own K, masses and C (linear_limits' route), the masses as
// NumPy arrays.
#include <pybind11/stl.h>

#include <string>
#include <vector>

#include "core/analysis/linear_limits.hpp"
#include "core/analysis/mass_scaling_scene.hpp"
#include "core/io/report.hpp"
#include "dampbound/physics/error.hpp"
#include "python/arrays.hpp"
#include "python/matrices.hpp"

namespace dampbound::python {
namespace {

py::array_t<double> array_of(const std::vector<double>& v) {
  return py::array_t<double>(py::ssize_t(v.size()), v.data());
}

/// The answer's numbers (both routes).
py::dict result_dict(const MassScalingResult& r) {
  py::dict d;
  d["answer"] = to_string(r.kind);
  d["dt_target"] = r.dt_target;
  d["safety"] = r.safety;
  d["dt_design"] = r.dt_design;
  d["free_mass"] = r.free_mass;
  d["dt_limit_before"] = r.dt_limit_before;
  d["dt_no_mass"] = r.dt_no_mass;
  d["scaled_nodes"] = r.scaled_count;
  d["added_local"] = r.added_local;
  d["added"] = r.added;
  d["added_local_percent"] = 100 * r.added_local_fraction();
  d["added_percent"] = 100 * r.added_fraction();
  d["s_star"] = r.s_star;
  d["dt_limit"] = r.dt_limit;
  d["over_cap"] = r.over_cap;
  d["dt_cap"] = r.dt_cap;
  d["dt_cap_added"] = r.dt_cap_added;
  return d;
}

MassScalingOptions options_of(double safety, double max_added_percent) {
  MassScalingOptions o;
  o.safety = safety;
  o.max_added = max_added_percent / 100;
  return o;
}

}  // namespace

void bind_mass_scaling(py::module_& m) {
  m.def(
      "mass_scaling",
      [](const SceneSpec& scene_in, double dt, const Params* params, double safety,
         double max_added_mass, bool verify) {
        const ResolvedScene resolved(scene_in, params);
        const SceneSpec& scene = resolved.scene();
        if (const auto why = validate(scene)) throw py::value_error("scene: " + *why);
        SceneMassScalingOptions o;
        static_cast<MassScalingOptions&>(o) = options_of(safety, max_added_mass);
        o.verify = verify;
        SceneMassScaling s;
        {
          py::gil_scoped_release release;
          s = scene_mass_scaling(scene, resolved.params(), scene_in.rules, dt, o);
        }
        py::dict d = result_dict(s.result);
        d["mass"] = array_of(s.mass_after);
        d["mass_before"] = array_of(s.mass_before);
        d["mass_scale"] = array_of(s.mass_scale);
        d["frequency_before"] = s.frequency_before;
        d["frequency_after"] = s.frequency_after;
        d["frequency_change_percent"] = s.frequency_change;
        d["lower_bound_change_percent"] = s.lower_bound_change;
        py::list top;
        for (const ScaledNode& n : s.top) {
          py::dict e;
          e["node"] = n.node;
          e["before"] = n.before;
          e["after"] = n.after;
          e["factor"] = n.factor;
          e["cause"] = n.cause;
          top.append(e);
        }
        d["top"] = top;
        d["run"] = s.ran ? py::object(py::str(verdict_short(s.run.result))) : py::object(py::none());
        d["verified"] = s.ran ? py::object(py::bool_(s.run.verified())) : py::object(py::none());
        d["scene"] = s.scene;
        return d;
      },
      py::arg("scene"), py::arg("dt"), py::arg("params") = nullptr, py::arg("safety") = 0.9,
      py::arg("max_added_mass") = 5.0, py::arg("verify") = true,
      "SPEC 11 (docs/criteria.md, 'Mass scaling'): the least mass to add to the nodes that "
      "limit the step so that the target step dt (s) is stable, as `suggest --mass-scale`: a "
      "dict with answer ('nothing_to_add', 'no_mass_helps' or 'scaled'), added and "
      "added_percent (tightened), added_local and added_local_percent (the local rule's), "
      "scaled_nodes, s_star, dt_limit (the scaled model's exact dt limit), over_cap and dt_cap, "
      "mass (N,: every node's mass after; fixed nodes unchanged), mass_before, mass_scale, top "
      "(the 20 nodes with the most added mass and why), run and verified (the run at dt with "
      "the scaled masses, settled rule), and scene (the scaled scene, at dt). safety f in "
      "(0, 1]: design for dt / f; max_added_mass: the cap, % of the free mass.");
  m.def(
      "mass_scaling",
      [](const py::object& K, const py::object& mass, double dt, const py::object& gamma,
         const py::object& C, double rayleigh_mass, double safety, double max_added_mass) {
        const SparseMatrix k = sparse_of(K, "K");
        MatrixModel mm;
        mm.K = &k;
        mm.mass = vector_of(mass, "mass");
        mm.gamma = vector_of(gamma, "gamma");
        mm.dt = dt;
        SparseMatrix c;
        if (!C.is_none()) {
          c = sparse_of(C, "C");
          mm.C = &c;
        }
        MassScalingResult r;
        {
          py::gil_scoped_release unlocked;
          const MassScalingProblem p = mass_scaling_problem(mm, rayleigh_mass);
          r = mass_scaling(p, dt, options_of(safety, max_added_mass));
        }
        py::dict d = result_dict(r);
        d["mass"] = array_of(r.kind == MassScalingCase::scaled ? r.mass : mm.mass);
        d["mass_local"] = array_of(r.kind == MassScalingCase::scaled ? r.mass_local : mm.mass);
        return d;
      },
      py::arg("K"), py::arg("mass"), py::kw_only(), py::arg("dt"), py::arg("gamma") = 0.0,
      py::arg("C") = py::none(), py::arg("rayleigh_mass") = 0.0, py::arg("safety") = 0.9,
      py::arg("max_added_mass") = 5.0,
      "SPEC 11 on your own matrices (linear_limits' route): K (3N x 3N, symmetric, rows "
      "3i..3i+2 node i; leave fixed nodes out), mass (N,), gamma one value or (N,), C the "
      "damping that does not scale with the masses (dashpots, beta K; optional), rayleigh_mass "
      "alpha (1/s) the part that does. The same dict as on a scene (no run, no scene): mass "
      "(N,) the answer's masses, mass_local the local rule's.");
}

}  // namespace dampbound::python
