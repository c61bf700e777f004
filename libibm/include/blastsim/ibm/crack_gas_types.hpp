//! \file crack_gas_types.hpp
//! \brief What the gas in the cracks reports (CrackGas::totals(), CrackGasCoupling's diagnostics): plain data, no
//! device arrays, so that the coupling's diagnostics (coupling_process.hpp) need not include the process.
#pragma once

namespace blastsim::ibm {

//! Sums over the gas segments.
struct CrackGasTotals {
  double mass = 0;           //!< [kg/m]
  double energy = 0;         //!< total energy [J/m]
  double products_mass = 0;  //!< [kg/m]
  double volume = 0;         //!< [m2 per m]
  double max_pressure = 0;   //!< [Pa]
  long gas_segments = 0;     //!< segments that hold their own gas (kSegmentGas)
  long wet_segments = 0;     //!< of those, segments above 1.5 times the reference pressure
  double wall_heat = 0;      //!< [J/m] heat the cracks' gas gave their walls since the start (CrackGasOptions::walls)
  // the coupling's ledgers since the start (CrackGasCoupling; 0 for a network alone)
  double to_grid_mass = 0;    //!< [kg/m] given to the grid's cells through mouths and hand-overs (< 0: taken)
  double to_grid_energy = 0;  //!< [J/m] likewise
  double from_cells_mass = 0;    //!< [kg/m] taken from covered cells of the gaps (the reverse hand-over)
  double from_cells_energy = 0;  //!< [J/m] likewise
  double wall_work = 0;       //!< [J/m] work of the cracks' gas on their walls (what the gas paid)
  double unpaid_work = 0;     //!< [J/m] work of the cushions' loads on the rock beyond what their gas paid
};

}  // namespace blastsim::ibm
