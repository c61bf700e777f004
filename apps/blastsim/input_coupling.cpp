//! \file input_coupling.cpp
//! \brief [coupling] (how the grid gas loads the rock) and [crack_gas] (gas in the cracks) of coupled cases;
//! docs/input.md, docs/coupling.md.
#include "case.hpp"

namespace blastsim::app {

void read_coupling(TableReader& root, Case& c) {
  CouplingSettings& k = c.coupling;
  TableReader coupling = root.table("coupling");
  k.gas_load = coupling.text("gas_load", {"edges", "faces"}, std::string("edges")) == "faces" ? ibm::GasLoad::face_forces
                                                                                              : ibm::GasLoad::edge_pressures;
  coupling.finish();
  TableReader crack = root.table("crack_gas");
  k.crack_gas = crack.boolean("enabled", false);
  ibm::CrackGasOptions& o = k.crack_gas_options;
  o.residual_aperture = crack.number("residual_aperture", "m", Range::positive(), o.residual_aperture);
  o.friction_factor = crack.number("friction_factor", "", Range::non_negative(), o.friction_factor);
  o.viscosity = crack.number("viscosity", "Pa s", Range::non_negative(), o.viscosity);
  o.courant = crack.number("courant", "", Range::half_open(0, 1), o.courant);
  o.second_order = crack.boolean("second_order", o.second_order);
  crack.finish();
}

}  // namespace blastsim::app
