//! \file material.cpp
//! \brief The paper's rock preset (Table 2), and the validation of the material and of the solver's options.
#include "blastsim/fdem/material.hpp"
#include "blastsim/fdem/rock_types.hpp"

#include "blastsim/core/error.hpp"

#include <cmath>
#include <sstream>
#include <string>

namespace blastsim::fdem {

RockMaterial RockMaterial::paper_table2() {
  RockMaterial m;
  m.density = 2.60e3;
  m.youngs_modulus = 55.0e9;
  m.poisson_ratio = 0.30;
  m.tensile_strength = 6.30e6;
  m.cohesion = 18.2e6;
  m.friction_angle = 30.0 * M_PI / 180.0;
  m.fracture_energy_mode1 = 50.0;
  m.fracture_energy_mode2 = 250.0;
  m.contact_friction = 0.6;
  return m;
}

void RockMaterial::validate() const {
  auto require = [](bool ok, const char* key, double value, const char* allowed) {
    if (!ok) throw InputError(std::string(key) + " = " + std::to_string(value) + ": must be " + allowed);
  };
  require(density > 0, "density", density, "> 0 kg/m3");
  require(youngs_modulus > 0, "youngs_modulus", youngs_modulus, "> 0 Pa");
  require(poisson_ratio >= 0 && poisson_ratio < 0.5, "poisson_ratio", poisson_ratio, "in [0, 0.5)");
  require(tensile_strength > 0, "tensile_strength", tensile_strength, "> 0 Pa");
  require(cohesion > 0, "cohesion", cohesion, "> 0 Pa");
  require(friction_angle >= 0 && friction_angle < M_PI / 2, "friction_angle", friction_angle, "in [0, pi/2) rad");
  require(fracture_energy_mode1 > 0, "fracture_energy_mode1", fracture_energy_mode1, "> 0 J/m2");
  require(fracture_energy_mode2 > 0, "fracture_energy_mode2", fracture_energy_mode2, "> 0 J/m2");
  require(contact_friction >= 0, "contact_friction", contact_friction, ">= 0");
}


void RockOptions::validate() const {
  auto fail = [](const char* key, double value, const char* allowed) {
    std::ostringstream os;
    os << key << " = " << value << ": must be " << allowed;
    throw InputError(os.str());
  };
  if (!(joint_penalty_factor > 0)) fail("joint_penalty_factor", joint_penalty_factor, "> 0 (p / E, typically 10 to 100)");
  if (!(contact_penalty_factor > 0)) fail("contact_penalty_factor", contact_penalty_factor, "> 0 (p_c / E)");
  if (!(damping_ratio >= 0 && damping_ratio < 1)) fail("damping_ratio", damping_ratio, "in [0, 1)");
  if (!(contact_buffer > 0 && contact_buffer <= 2)) fail("contact_buffer", contact_buffer, "in (0, 2]");
  if (!std::isfinite(gravity[0]) || !std::isfinite(gravity[1])) fail("gravity", gravity[0], "finite");
}

}  // namespace blastsim::fdem
