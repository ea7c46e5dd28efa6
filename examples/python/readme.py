import dampbound, numpy as np
mon = dampbound.Monitor(np.ones(2), np.array([[0, 1]]), np.array([4.0]), np.ones(1))
print("gamma_lo =", mon.lower_bounds())  # eq. 5: 2 sqrt(m kappa) = 4
x, v = np.array([[0.0, 0, 0], [1.5, 0, 0]]), np.array([[0.0, 0, 0], [1.0, 0, 0]])
print(mon.check(v, mon.internal_forces(x), np.full(2, 4.0), dt=0.1)[0].ok)
