//! \file input_coupling.cpp
//! \brief [coupling] (how the grid gas loads the rock) and [crack_gas] (gas in the cracks) of coupled cases;
//! docs/input.md, docs/coupling.md.
#include "blastsim/core/error.hpp"
#include "case.hpp"

#include <fmt/format.h>

#include <algorithm>

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
  const std::string walls = crack.text("walls", {"exchange", "adiabatic", "isothermal"}, std::string("exchange"));
  o.walls = walls == "adiabatic" ? ibm::WallHeat::adiabatic
                                 : (walls == "isothermal" ? ibm::WallHeat::isothermal : ibm::WallHeat::exchange);
  o.prandtl = crack.number("prandtl", "", Range::positive(), o.prandtl);
  o.courant = crack.number("courant", "", Range{ibm::CrackGasOptions::kMinCourant, 1.0, false, false}, o.courant);
  o.second_order = crack.boolean("second_order", o.second_order);
  o.handover_width = crack.number("handover_width", "cells", Range{1.0, 1e6, false, false}, o.handover_width);
  o.vacuum_fraction = crack.number("vacuum_fraction", "", Range{0.0, 1.0, false, true}, o.vacuum_fraction);
  const std::optional<double> stiffness = crack.optional_number("joint_closure_stiffness", "Pa/m", Range::positive());
  const std::optional<double> max_closure = crack.optional_number("joint_max_closure", "m", Range::positive());
  if (stiffness.has_value() != max_closure.has_value())
    throw InputError(fmt::format("crack_gas.{} is given without crack_gas.{}: the closure law of open joints needs both",
                                 stiffness ? "joint_closure_stiffness" : "joint_max_closure",
                                 stiffness ? "joint_max_closure" : "joint_closure_stiffness"));
  if (stiffness) o.joint_closure = ibm::JointClosure{*stiffness, *max_closure};
  crack.finish();
  // An initial aperture is the crack gas's room; the rock's faces touch, so the grid has no gap there, and an
  // aperture as wide as the hand-over gap (where a crack's gas becomes the grid's) would need one.
  const double cell = std::max(c.gas.grid.dx, c.gas.grid.dy), widest = o.handover_width * cell;
  auto check_aperture = [&](const std::string& label, double aperture) {
    if (aperture > 0 && !k.crack_gas)
      throw InputError(fmt::format("{}.initial_aperture = {:g} m: an initial aperture is the crack gas's (give "
                                   "[crack_gas] enabled = true, or leave it 0)", label, aperture));
    if (!(aperture < widest))
      throw InputError(fmt::format("{}.initial_aperture = {:g} m: must be below crack_gas.handover_width x the gas "
                                   "cell ({:g} x {:g} = {:g} m): a crack that open is the grid's gas, and the grid has "
                                   "no gap where the rock's faces touch", label, aperture, o.handover_width, cell, widest));
  };
  for (const fdem::PreCutCrack& cut : c.rock.model.cracks) check_aperture(cut.label, cut.initial_aperture);
  for (const fdem::JointSetSpec& set : c.rock.model.joint_sets) check_aperture(set.label, set.initial_aperture);
  if (o.joint_closure && !k.crack_gas)
    throw InputError("crack_gas.joint_closure_stiffness and joint_max_closure close the open joints' crack gas: give "
                     "[crack_gas] enabled = true, or leave them out");
  if (o.joint_closure) {  // the closure law closes the joints that stand open
    bool any = false;
    auto check_closure = [&](const std::string& label, double aperture) {
      if (!(aperture > 0)) return;
      any = true;
      if (!(o.joint_closure->max_closure < aperture))
        throw InputError(fmt::format("crack_gas.joint_max_closure = {:g} m: must be below {}.initial_aperture = {:g} m "
                                     "(the joint cannot close by more than it stands open)",
                                     o.joint_closure->max_closure, label, aperture));
    };
    for (const fdem::PreCutCrack& cut : c.rock.model.cracks) check_closure(cut.label, cut.initial_aperture);
    for (const fdem::JointSetSpec& set : c.rock.model.joint_sets)
      if (set.open) check_closure(set.label, set.initial_aperture);
    if (!any)
      throw InputError(fmt::format("crack_gas.joint_closure_stiffness and joint_max_closure are given, but no "
                                   "[[rock.crack]] or open [[rock.joint_set]] has an initial_aperture for them to close"));
  }
}

}  // namespace blastsim::app
