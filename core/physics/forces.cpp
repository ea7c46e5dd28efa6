#include "dampbound/physics/forces.hpp"

#include "core/physics/detail/spring_block.hpp"
#include "core/physics/detail/spring_pass.hpp"

namespace dampbound {

int internal_forces(const Model& model, const std::vector<Vec3>& x, std::vector<Vec3>& force,
                    SpringPass* pass) {
  return detail::spring_pass(model, x, &force, nullptr, pass).zero_length;
}

}  // namespace dampbound

namespace dampbound {

void damping_forces(const Model& model, const std::vector<Vec3>& x, const std::vector<Vec3>& v,
                    std::vector<Vec3>& damping) {
  const size_t n = x.size();
  damping.resize(n);
  const double alpha = model.rayleigh_mass, beta = model.rayleigh_stiffness;
  for (size_t i = 0; i < n; ++i)
    damping[i] = model.spec().fixed[i] ? Vec3::Zero()
                                : Vec3((alpha * model.mass[i] + model.anchor_kd[i] +
                                        beta * model.anchor_kappa[i]) * v[i]);
  for (size_t k = 0; k < model.spec().springs.size(); ++k) {
    const Spring& s = model.spec().springs[k];
    const size_t i = static_cast<size_t>(s.i), j = static_cast<size_t>(s.j);
    const SpringGeometry g = spring_geometry(x[i].data(), x[j].data(), s.rest_length);
    if (!(g.length > 0)) continue;  // no direction (also NaN): no force, as for the spring (SPEC 1)
    const Vec3 d(g.d[0], g.d[1], g.d[2]);
    const Vec3 vi = model.spec().fixed[i] ? Vec3::Zero() : v[i];
    const Vec3 vj = model.spec().fixed[j] ? Vec3::Zero() : v[j];
    const Vec3 u = vj - vi;
    const double kappa = model.spring_kappa[k];
    const double ratio = g.ratio, tension = g.tension;
    // kd (u . d) d + beta B u with B u = kappa [(1 - l0/l) u + (l0/l) (d . u) d]
    const double along = u.dot(d);
    const Vec3 w = (model.spring_kd[k] * along) * d +
                   beta * (kappa * (tension * u + (ratio * along) * d));
    if (!model.spec().fixed[i]) damping[i] -= w;
    if (!model.spec().fixed[j]) damping[j] += w;
  }
}

}  // namespace dampbound
