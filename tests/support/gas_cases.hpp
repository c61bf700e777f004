//! \file gas_cases.hpp
//! \brief Helpers shared by the gas tests: run a solver to a time, shock-tube set-ups, error norms.
#pragma once

#include "blastsim/cip/gas_solver.hpp"
#include "exact_riemann.hpp"

#include <cmath>
#include <cstdio>

namespace blastsim::test {

//! Advances to t_end with dt from the Courant number (last step shortened to land on t_end).
inline void run_to(cip::GasSolver& s, double t_end, double courant) {
  while (s.time() < t_end * (1 - 1e-12)) {
    const double rate = s.max_signal_rate();
    if (!std::isfinite(rate)) throw std::runtime_error("unstable: " + s.describe_invalid_cell());
    s.step(std::fmin(courant / rate, t_end - s.time()));
  }
}

enum class Axis { x, y };

//! A 1-D Riemann problem on a strip of n x 3 cells (or 3 x n) over [0, length], diaphragm at x0,
//! outflow at the ends and slip walls along the strip.
inline cip::GasSolver make_shock_tube(int n, Axis axis, Primitive L, Primitive R, double x0, double length = 1.0,
                                      double gamma = 1.4, cip::GasSolverOptions opt = {}) {
  using cip::BoundaryKind;
  const bool along_x = axis == Axis::x;
  const double w = 3 * length / n;
  const cip::GasGrid grid = along_x ? cip::GasGrid::from_box(n, 3, 0, length, 0, w)
                                    : cip::GasGrid::from_box(3, n, 0, w, 0, length);
  // Outflow at the tube's ends, walls along its sides.
  opt.boundaries = cip::BoundaryConditions::all(BoundaryKind::wall)
                       .set(along_x ? cip::left : cip::bottom, BoundaryKind::outflow)
                       .set(along_x ? cip::right : cip::top, BoundaryKind::outflow);
  const cip::EquationOfState eos = cip::EquationOfState::ideal(gamma);
  cip::GasSolver s(grid, eos, opt);
  s.initialise([=](double x, double y) {
    const double xi = along_x ? x : y;
    const Primitive& q = xi < x0 ? L : R;
    const double ux = along_x ? q.u : 0.0, uy = along_x ? 0.0 : q.u;
    return cip::GasPoint{q.rho, eos.internal_energy(q.rho, q.p), ux, uy};
  });
  return s;
}

//! Cell-centred values along the strip (middle row or column) from the host copy.
inline std::vector<double> strip(const cip::HostGasFields& h, const std::vector<double>& f, Axis axis) {
  std::vector<double> out;
  if (axis == Axis::x)
    for (int i = 0; i < h.nx; ++i) out.push_back(f[static_cast<size_t>(1) * h.nx + i]);
  else
    for (int j = 0; j < h.ny; ++j) out.push_back(f[static_cast<size_t>(j) * h.nx + 1]);
  return out;
}

}  // namespace blastsim::test
