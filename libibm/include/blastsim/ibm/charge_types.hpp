//! \file charge_types.hpp
//! \brief Explosive charges in blastholes (docs/coupling.md "Charges"): the plain types that describe them and
//! what they released (the process itself is Charges, charges.hpp).
#pragma once

#include <array>
#include <vector>

namespace blastsim::ibm {

//! How the 2-D section of a charge detonates.
enum class Initiation {
  constant_volume,  //!< all of it at its initiation time (a column charge's section crossed by the front)
  point             //!< a front from a point at the detonation velocity (programmed burn, lighting times)
};

//! One charge: a circle of explosive in a blasthole of the rock. Before the grid cells of the charge burn, the
//! charge is a solid that keeps its volume: its cells are inactive and their faces walls at rest, so no gas
//! enters. A cell burns when the detonation front reaches its centre; it then holds the detonation products
//! at the explosive's density and detonation energy, at rest (a constant-volume explosion of that cell).
struct Charge {
  std::array<double, 2> center{};  //!< [m] of the hole and the charge
  double hole_radius = 0;          //!< [m] (for the borehole pressure: the cells within it)
  double radius = 0;               //!< [m] of the charge, <= hole_radius (decoupled: the gap holds air)
  double initiation_time = 0;      //!< [s]
  Initiation initiation = Initiation::constant_volume;
  std::array<double, 2> point{};   //!< [m] initiation point (Initiation::point)
  double detonation_velocity = 0;  //!< [m/s] (Initiation::point)
};

//! The state the products of every charge start from: the explosive's density and its detonation energy per
//! unit mass (in the products' equation of state, so that rho0 e0 is the energy per unit volume E0).
struct ChargeProducts {
  double density = 0;          //!< rho0 [kg/m3]
  double specific_energy = 0;  //!< e0 = E0 / rho0 [J/kg]
};

//! What the charges put into the gas so far, per unit thickness.
struct ChargeTotals {
  double products_mass = 0;    //!< [kg/m] of the burnt cells' products
  double detonation_energy = 0;  //!< [J/m] their energy rho0 e0 A
  double replaced_mass = 0;    //!< [kg/m] of the gas the burnt cells held before (the ambient state)
  double replaced_energy = 0;  //!< [J/m] its internal energy
  long burnt_cells = 0;
};

}  // namespace blastsim::ibm
