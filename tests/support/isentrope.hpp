//! \file isentrope.hpp
//! \brief Test helper: the specific internal energy along an isentrope of any equation of state, by integrating the
//! first law with no heat (reference for the JWL tests and the charges' lumped states).
#pragma once

#include "blastsim/cip/eos.hpp"

namespace blastsim::test {

//! Integrates the isentrope de/drho = p(rho, e) / rho^2 from (rho, e) to rho_end by classical Runge-Kutta in n
//! steps; returns e at rho_end [J/kg].
inline double isentrope_energy_at(const cip::EquationOfState& eos, double rho, double e, double rho_end, int n = 200) {
  const double h = (rho_end - rho) / n;
  auto f = [&](double r, double en) { return eos.pressure(r, en) / (r * r); };
  for (int k = 0; k < n; ++k) {
    const double k1 = f(rho, e), k2 = f(rho + h / 2, e + h / 2 * k1), k3 = f(rho + h / 2, e + h / 2 * k2),
                 k4 = f(rho + h, e + h * k3);
    e += h / 6 * (k1 + 2 * k2 + 2 * k3 + k4);
    rho += h;
  }
  return e;
}

}  // namespace blastsim::test
