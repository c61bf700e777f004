//! \file material.hpp
//! \brief Rock material of the FDEM solver (elastic constants, strength, fracture energies) with the paper's preset.
#pragma once

#include "blastsim/core/macros.hpp"

#include <cmath>

namespace blastsim::fdem {

//! Rock parameters (SI). Elastic triangles are in plane strain.
struct RockMaterial {
  double density = 0;                //!< [kg/m3]
  double youngs_modulus = 0;         //!< [Pa]
  double poisson_ratio = 0;          //!< [-], in [0, 0.5)
  double tensile_strength = 0;       //!< [Pa] of the cohesive joints
  double cohesion = 0;               //!< [Pa] Mohr-Coulomb cohesion of the joints
  double friction_angle = 0;         //!< [rad] internal friction angle of the joints
  double fracture_energy_mode1 = 0;  //!< [J/m2] G_I
  double fracture_energy_mode2 = 0;  //!< [J/m2] G_II
  double contact_friction = 0;       //!< [-] Coulomb coefficient between pieces

  //! Lame's first parameter lambda [Pa] (3-D value, used in plane strain).
  BLAST_HD double lame_lambda() const {
    return youngs_modulus * poisson_ratio / ((1 + poisson_ratio) * (1 - 2 * poisson_ratio));
  }
  //! Shear modulus mu [Pa].
  BLAST_HD double shear_modulus() const { return youngs_modulus / (2 * (1 + poisson_ratio)); }
  //! Plane-strain P-wave speed sqrt((lambda + 2 mu) / rho) [m/s].
  double p_wave_speed() const { return std::sqrt((lame_lambda() + 2 * shear_modulus()) / density); }
  //! S-wave speed sqrt(mu / rho) [m/s].
  double s_wave_speed() const { return std::sqrt(shear_modulus() / density); }

  //! The paper's intact rock (Table 2): 2600 kg/m3, 55 GPa, 0.30, 6.3 MPa, 18.2 MPa, 30 deg, 50 and 250 J/m2,
  //! contact friction 0.6.
  static RockMaterial paper_table2();
  //! Throws InputError naming the first parameter outside its physical range.
  void validate() const;
};

}  // namespace blastsim::fdem
