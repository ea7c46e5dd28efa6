// The knobs held fixed and the rest asked (core/analysis/kappa_ceiling.hpp, rayleigh_design.hpp,
// limits_diff.hpp) in Python: kappa_ceiling, rayleigh_from_spectrum, diff_limits, save_limits.
#include <pybind11/stl.h>

#include <cmath>
#include <fstream>
#include <optional>
#include <string>
#include <vector>

#include "core/analysis/kappa_ceiling.hpp"
#include "core/analysis/limits_diff.hpp"
#include "core/analysis/rayleigh_design.hpp"
#include "core/io/files.hpp"
#include "python/arrays.hpp"

namespace dampbound::python {

namespace {

py::array_t<double> numpy(const std::vector<double>& v) {
  py::array_t<double> a(static_cast<py::ssize_t>(v.size()));
  std::copy(v.begin(), v.end(), a.mutable_data());
  return a;
}

py::object run_or_none(const StiffnessCeiling& c, const VerifiedRun& r) {
  if (!c.ran) return py::none();
  return py::cast(r.result);
}

/// A Scene (its own parameters, or `params`) or the path of a baseline .json.
LimitsSnapshot snapshot_of(const py::object& what, const Params* params) {
  if (py::isinstance<py::str>(what)) {
    const std::string path = what.cast<std::string>();
    return read_limits_json(read_file_text(path), path);
  }
  const SceneSpec& scene_in = what.cast<const SceneSpec&>();
  const ResolvedScene resolved(scene_in, params);
  Params p = resolved.params();
  p.policy = DampingPolicy::fixed;
  py::gil_scoped_release release;
  return limits_snapshot(resolved.scene(), p);
}

py::dict limits_dict(const LimitsSnapshot& s) {
  py::dict d;
  d["scene"] = s.scene;
  d["dt"] = s.params.dt;
  d["dt_limit"] = s.dt_limit;
  d["gamma_lo"] = s.gamma_lo;
  d["gamma_hi"] = s.gamma_hi;
  d["dt_safe"] = s.dt_safe;
  d["dt_safe_node"] = s.dt_safe_node;
  py::list worst;
  for (const LimitsSnapshot::Node& n : s.worst) worst.append(py::make_tuple(n.node, n.dt_safe, n.cause));
  d["worst"] = worst;
  d["mode_nodes"] = s.mode_nodes;
  d["mode_share"] = s.mode_share;
  d["node_dt_safe"] = numpy(s.node_dt_safe);
  return d;
}

}  // namespace

void bind_knobs(py::module_& m) {
  m.def(
      "kappa_ceiling",
      [](const SceneSpec& scene_in, const Params* params, const StopRules* rules, bool verify) {
        const ResolvedScene resolved(scene_in, params);
        const SceneSpec& scene = resolved.scene();
        Params p = resolved.params();
        p.policy = DampingPolicy::fixed;
        const StopRules r = rules ? *rules : scene_in.rules;
        if (const auto why = validate(scene)) throw py::value_error("scene: " + *why);
        std::vector<StiffnessCeiling> ceilings;
        ContactCeilings contact;
        {
          py::gil_scoped_release release;
          ceilings.push_back(stiffness_ceiling(scene, p, whole_selection(scene.model), r, verify));
          for (const SceneRegion& g : scene.regions)
            ceilings.push_back(stiffness_ceiling(scene, p, region_selection(scene.model, g), r, verify));
          const Model model = compile_model(scene.model, p);
          contact = contact_ceilings(model, model.spec().rest, p.dt, p.kd, 5);
        }
        py::list out;
        for (const StiffnessCeiling& c : ceilings) {
          py::dict e;
          e["label"] = c.label;
          e["springs"] = c.springs;
          e["anchors"] = c.anchors;
          e["factor"] = c.factor;
          e["index"] = c.index;
          e["below"] = run_or_none(c, c.below);
          e["above"] = run_or_none(c, c.above);
          e["below_settles"] = c.ran ? py::cast(c.below.verified()) : py::none();
          e["above_settles"] = c.ran ? py::cast(c.above.verified()) : py::none();
          out.append(e);
        }
        py::dict d;
        d["ceilings"] = out;
        d["contact_stiffness_max"] = numpy(contact.k_max);
        d["contact_min"] = contact.min;
        d["contact_median"] = contact.median;
        d["contact_worst"] = contact.worst;
        return d;
      },
      py::arg("scene"), py::arg("params") = nullptr, py::arg("rules") = nullptr,
      py::arg("verify") = true,
      "Stiffness ceilings (the CLI's suggest --kappa-max) at params.dt and the scene's damping, "
      "for the paper's step, linearised at rest: 'ceilings' lists, for every spring and anchor "
      "and then each region, the largest factor on their stiffness that keeps the step stable "
      "(exact index; beta K follows), with runs at 0.98x ('below') and 1.02x ('above') when "
      "verify; 'contact_stiffness_max' (N,) is each node's largest extra zero-length spring "
      "(dashpot kd) keeping its SPEC 9/10 rows dominant (NaN at fixed nodes, mass unit/s^2).");

  m.def(
      "rayleigh_from_spectrum",
      [](const SceneSpec& scene_in, double zeta1, std::optional<double> zeta2,
         std::optional<std::pair<double, double>> band, const Params* params) {
        const ResolvedScene resolved(scene_in, params);
        RayleighRequest r;
        r.zeta1 = zeta1;
        r.zeta2 = zeta2 ? *zeta2 : zeta1;
        if (band) r.f1 = band->first, r.f2 = band->second;
        RayleighDesign x;
        {
          py::gil_scoped_release release;
          x = rayleigh_from_spectrum(resolved.scene(), resolved.params(), r);
        }
        py::dict d;
        d["alpha"] = x.alpha;
        d["beta"] = x.beta;
        d["feasible"] = x.feasible;
        d["stable"] = x.stable;
        d["beta_max"] = x.beta_max;
        d["beta_max_closed"] = x.beta_max_closed;
        d["dt_max"] = x.dt_max;
        d["f1"] = x.f1;
        d["f2"] = x.f2;
        d["f_lowest"] = x.f_lowest;
        d["f_highest"] = x.f_highest;
        d["f_nyquist"] = x.f_nyquist;
        d["lambda_min"] = x.lambda_min;
        d["lambda_max"] = x.lambda_max;
        d["zeta2_at_beta_max"] = x.zeta2_at_beta_max;
        d["terminal_velocity"] = x.forced_nodes > 0 ? x.terminal_velocity : NAN;
        d["terminal_node"] = x.terminal_node;
        d["f"] = numpy(x.curve_f);
        d["zeta"] = numpy(x.curve_zeta);
        return d;
      },
      py::arg("scene"), py::arg("zeta1"), py::arg("zeta2") = py::none(),
      py::arg("band") = py::none(), py::arg("params") = nullptr,
      "Rayleigh alpha (1/s) and beta (s) giving damping ratio zeta1 at f1 and zeta2 (default "
      "zeta1) at f2 (band=(f1, f2) in Hz; default the lowest mode and the highest the step "
      "resolves), on the eigenvalues of the scene's M^-1 K (the CLI's suggest --rayleigh). "
      "'stable' judges the pair at params.dt with the scene's gamma and kd (exact index); "
      "'beta_max' is the largest stable beta with alpha held; 'f', 'zeta' sample zeta(f); "
      "'terminal_velocity' is |f_i|/(alpha m_i) at the loaded node where it is largest (NaN "
      "without loads).");

  m.def(
      "diff_limits",
      [](const py::object& old_scene, const py::object& new_scene, std::optional<double> frame_dt,
         double max_drop) {
        const LimitsSnapshot o = snapshot_of(old_scene, nullptr), n = snapshot_of(new_scene, nullptr);
        const LimitsDiff d = diff_limits(o, n);
        py::dict r;
        r["old"] = limits_dict(o);
        r["new"] = limits_dict(n);
        r["drop"] = d.drop;
        r["failed"] = !(d.drop * 100 <= max_drop);
        r["matched_nodes"] = d.matched_nodes;
        r["renumbered"] = d.renumbered;
        r["changed_nodes"] = d.changed_nodes;
        r["changed_springs"] = d.changed_springs;
        r["parameters"] = d.parameters;
        py::list changes;
        for (const LimitChange& c : d.changes) changes.append(py::make_tuple(c.what, c.weight));
        r["changes"] = changes;
        py::list falls;
        for (const LimitsDiff::Fall& f : d.falls) falls.append(py::make_tuple(f.node, f.old_dt, f.new_dt));
        r["falls"] = falls;
        if (frame_dt)
          r["substeps"] = py::make_tuple(limit_substeps(*frame_dt, o.dt_limit),
                                         limit_substeps(*frame_dt, n.dt_limit));
        return r;
      },
      py::arg("old"), py::arg("new"), py::arg("frame_dt") = py::none(), py::arg("max_drop") = 20.0,
      "Two scenes' limits (the CLI's diff): each of old and new a Scene or the path of a "
      "baseline .json (save_limits). 'drop' = 1 - new dt limit / old; 'failed' when it exceeds "
      "max_drop percent (or a limit is not computed); 'changes' lists (text, share of the new "
      "limiting mode) for the nodes and springs that changed where the new scene is limited, "
      "matched by rest position; 'substeps' (old, new) at frame_dt.");

  m.def(
      "save_limits",
      [](const SceneSpec& scene, const std::string& path, const Params* params) {
        const LimitsSnapshot s = snapshot_of(py::cast(scene), params);
        write_file_atomic(path, [&](std::ostream& out) { write_limits_json(out, s); });
        return limits_dict(s);
      },
      py::arg("scene"), py::arg("path"), py::arg("params") = nullptr,
      "Writes the scene's limits as a baseline .json for diff_limits (the CLI's diff SCENE "
      "--save FILE) and returns them.");
}

}  // namespace dampbound::python
