//! \file input_coupling.cpp
//! \brief [coupling] (how the grid gas loads the rock) and [crack_gas] (gas in the cracks) of coupled cases;
//! docs/input.md, docs/coupling.md.
#include "blastsim/core/error.hpp"
#include "case.hpp"

#include <fmt/format.h>

namespace blastsim::app {

void read_coupling(TableReader& root, Case& c) {
  CouplingSettings& k = c.coupling;
  TableReader coupling = root.table("coupling");
  const std::string load = coupling.text("gas_load", {"edges", "faces", "edges_paid"}, std::string("edges_paid"));
  k.gas_load = load == "faces" ? ibm::GasLoad::face_forces
                               : (load == "edges_paid" ? ibm::GasLoad::edge_pressures_paid : ibm::GasLoad::edge_pressures);
  coupling.finish();
  TableReader crack = root.table("crack_gas");
  k.crack_gas = crack.boolean("enabled", false);
  ibm::CrackGasOptions& o = k.crack_gas_options;
  o.residual_aperture = crack.number("residual_aperture", "m", Range::positive(), o.residual_aperture);
  o.friction_factor = crack.optional_number("friction_factor", "", Range::non_negative());
  o.roughness = crack.optional_number("roughness", "m", Range::positive());
  o.viscosity = crack.number("viscosity", "Pa s", Range::non_negative(), o.viscosity);
  o.courant = crack.number("courant", "", Range::half_open(0, 1), o.courant);
  o.second_order = crack.boolean("second_order", o.second_order);
  o.handover_width = crack.number("handover_width", "cells", Range{1.0, 1e6, false, false}, o.handover_width);
  crack.finish();
  for (const fdem::PreCutCrack& cut : c.rock.model.cracks)
    if (cut.initial_aperture > 0 && !k.crack_gas)
      throw InputError(fmt::format("{}.initial_aperture = {:g} m: an initial aperture is the crack gas's (give "
                                   "[crack_gas] enabled = true, or leave it 0)", cut.label, cut.initial_aperture));
  for (const fdem::JointSetSpec& set : c.rock.model.joint_sets)
    if (set.initial_aperture > 0 && !k.crack_gas)
      throw InputError(fmt::format("{}.initial_aperture = {:g} m: an initial aperture is the crack gas's (give "
                                   "[crack_gas] enabled = true, or leave it 0)", set.label, set.initial_aperture));
}

}  // namespace blastsim::app
