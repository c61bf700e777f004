//! \file eos.hpp
//! \brief Equation of state of the gas behind one interface (ideal gas now; JWL joins as another kind).
#pragma once

#include "blastsim/core/macros.hpp"

#include <cmath>

namespace blastsim::cip {

enum class EosKind { ideal_gas };

//! Plain-data equation of state, copied by value into kernels. p(rho, e) and the sound speed c(rho, e).
//! Ideal gas: p = (gamma - 1) rho e, c^2 = gamma p / rho (paper, Table 1: gamma = 1 + p/(rho e) = 1.40).
struct EquationOfState {
  EosKind kind = EosKind::ideal_gas;
  double gamma = 1.4;  //!< [-] ratio of specific heats, > 1

  //! [Pa] from density [kg/m3] and specific internal energy [J/kg].
  BLAST_HD double pressure(double density, double internal_energy) const {
    return (gamma - 1.0) * density * internal_energy;
  }
  //! [m/s]; NaN when e < 0 (callers treat that as an instability).
  BLAST_HD double sound_speed(double density, double internal_energy) const {
    (void)density;
    return std::sqrt(gamma * (gamma - 1.0) * internal_energy);
  }
  //! [J/kg] specific internal energy that gives pressure p at density rho.
  BLAST_HD double internal_energy(double density, double pressure_pa) const {
    return pressure_pa / ((gamma - 1.0) * density);
  }

  //! Ideal gas; throws InputError unless gamma > 1.
  static EquationOfState ideal(double gamma);
};

}  // namespace blastsim::cip
