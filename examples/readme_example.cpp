#include <cstdio>
#include <dampbound/monitor.hpp>
int main() {
  double mass[] = {1, 1}, k[] = {4}, l0[] = {1};
  int pairs[] = {0, 1};
  dampbound::Monitor mon(dampbound::node_scalars(mass, 2), dampbound::spring_pairs(pairs, 1),
                         dampbound::node_scalars(k, 1), dampbound::node_scalars(l0, 1));
  double lo[2];
  mon.lower_bounds(dampbound::node_scalars_out(lo, 2));
  std::printf("gamma_lo = %g %g (eq. 5: 2 sqrt(m kappa) = 4)\n", lo[0], lo[1]);
}
