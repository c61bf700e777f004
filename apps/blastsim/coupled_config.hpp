//! \file coupled_config.hpp
//! \brief The driver's coupled gas-rock case: a gas case and a rock case sharing time and output; plain data.
#pragma once

#include "blastsim/cip/gas_types.hpp"
#include "blastsim/ibm/blasthole_monitor.hpp"
#include "blastsim/ibm/charges.hpp"
#include "blastsim/ibm/coupler.hpp"
#include "blastsim/ibm/crack_gas.hpp"
#include "case_config.hpp"
#include "rock_config.hpp"

#include <optional>
#include <string>
#include <vector>

namespace blastsim::app {

//! A region of the gas whose mass and energy the coupled run writes to coupling_series.csv.
struct MonitorRegion {
  std::string name;
  cip::CellRegion region;
};

struct CoupledCaseConfig {
  CaseConfig gas;       //!< [domain], [gas], [probe]; time and output fields copied from [time], [output]
  RockCaseConfig rock;  //!< [rock]; time and output fields copied likewise
  std::vector<MonitorRegion> regions;  //!< [[monitor.region]]
  bool checkpoint = true;              //!< output.checkpoint: checkpoint.bin with every snapshot
  //! time.rock_subcycling: the gas steps at its own Courant limit and the rock takes as many steps of at most
  //! its stable step as fill each gas step (false: one dt for both, the paper's scheme).
  bool rock_subcycling = false;
  //! coupling.gas_load: how the grid gas loads the rock (docs/coupling.md "Gas -> rock"): "edges" (the
  //! default, the paper's edge pressures) or "faces" (the work the gas did on its immersed faces, exactly)
  ibm::GasLoad gas_load = ibm::GasLoad::edge_pressures;
  //! [monitor.blasthole]: the blasthole monitor (wall_series.csv, summary.txt), when given.
  struct Blasthole {
    ibm::BlastholeGeometry geometry;
    double interval = 1e-6;  //!< [s] between samples
  };
  std::optional<Blasthole> blasthole;
  //! [crack_gas]: broken joints carry their own gas (docs/coupling.md "Gas in the cracks"); off by default
  //! while its energy budget in a fragmenting blast is open (docs/coupling.md).
  bool crack_gas = false;
  ibm::CrackGasOptions crack_gas_options;
  //! [[charge]]: explosive charges in the mesh's holes (docs/coupling.md "Charges"), and the state their
  //! products start from ([gas.explosive]: rho0 and the detonation energy)
  std::vector<ibm::Charge> charges;
  ibm::ChargeProducts charge_products;
  std::vector<std::string> echo;
};

}  // namespace blastsim::app
