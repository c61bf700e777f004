//! \file sod_with_blastsim.cpp
//! \brief Example of linking libcip from another code: Sod's shock tube, printing the density profile.
#include <blastsim/cip/gas_solver.hpp>

#include <cmath>
#include <cstdio>

int main() {
  using namespace blastsim::cip;
  GasSolverOptions options;
  options.boundaries = BoundaryConditions::all(BoundaryKind::outflow).set(bottom, BoundaryKind::wall).set(top, BoundaryKind::wall);
  const EquationOfState eos = EquationOfState::ideal(1.4);
  GasSolver gas(GasGrid::from_box(200, 3, 0.0, 1.0, 0.0, 0.015), eos, options);
  gas.initialise([&](double x, double) {
    const bool left_side = x < 0.5;
    const double rho = left_side ? 1.0 : 0.125, p = left_side ? 1.0 : 0.1;
    return GasPoint{rho, eos.internal_energy(rho, p), 0.0, 0.0};
  });
  while (gas.time() < 0.2) gas.step(std::fmin(gas.courant_dt(0.1), 0.2 - gas.time() + 1e-15));
  const HostGasFields h = gas.to_host();
  std::printf("Sod at t = %.3f with %s backend: rho(x = 0.75) = %.4f (exact star state 0.2656)\n", gas.time(),
              blastsim::backend_name(), h.rho[200 + 150]);
  return std::fabs(h.rho[200 + 150] - 0.2656) < 0.02 ? 0 : 1;
}
