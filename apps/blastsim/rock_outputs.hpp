//! \file rock_outputs.hpp
//! \brief The rock side of a driver run: building the model (mesh, solver, loads) from a rock case, and what
//! the run writes about the rock (VTU series of triangles and joints, rock_series.csv). Shared by rock-only
//! and coupled runs. Include only from kernel sources.
#pragma once

#include "blastsim/core/checkpoint.hpp"
#include "blastsim/fdem/fragments.hpp"
#include "blastsim/fdem/gmsh_mesh.hpp"
#include "blastsim/fdem/rock_solver.hpp"
#include "blastsim/ibm/crack_gas.hpp"
#include "output_checkpoint.hpp"
#include "rock_config.hpp"

#include <chrono>
#include <filesystem>
#include <fstream>
#include <memory>
#include <optional>
#include <string>

namespace blastsim::app {

//! The mesh, its FDEM topology and the solver with the case's initial velocities, prescribed velocities and
//! boundary pressures (none in a coupled case: its input refuses them).
struct RockModel {
  fdem::NamedMesh mesh;
  fdem::FdemTopology topology;
  std::unique_ptr<fdem::RockSolver> solver;
  std::vector<std::vector<int>> velocity_nodes;  //!< the nodes of each [[rock.velocity]] load
};
RockModel make_rock_model(const RockCaseConfig& c);

//! dt [s] of the rock: the fixed time.dt (refused above the stable step, naming it) or step_fraction x stable.
double rock_time_step(const RockCaseConfig& c, const fdem::RockSolver& solver);

//! rock.pvd / rock_NNNNNN.vtu, joints.pvd / joints_NNNNNN.vtu and rock_series.csv in the output folder
//! (energies, cracks, and the support reaction of each [[rock.velocity]] load: the force a testing machine's
//! platen measures); with [analysis] fragments (the default) at every snapshot fragments_NNNNNN.csv,
//! size_distribution.csv and a row of fragmentation_series.csv; with [[probe.rock_point]] rock_probes.csv
//! and ppv.csv (docs/analysis.md).
class RockOutputs {
 public:
  //! `resume`: a restart, whose read_checkpoint() follows (files are kept, not started anew).
  RockOutputs(const RockCaseConfig& c, const RockModel& model, bool resume = false);
  void snapshot();             //!< one .vtu pair (when output.vtk) and the analysis files
  //! A coupled run's crack gas, whose aperture, pressure and mass the joints' VTU then carries.
  void set_crack_gas(const ibm::CrackGas* crack) { crack_ = crack; }
  fdem::RockEnergies monitor();  //!< one row of rock_series.csv (and rock_probes.csv); returns the energies
  void write_checkpoint(CheckpointWriter& w);  //!< snapshot count, initial energies, series sizes
  void read_checkpoint(CheckpointReader& r);
  //! The analysis part of summary.txt: fragments and sizes, damage zones, PPV at each probe.
  std::string summary() const;
  //! summary.txt of a rock-only run (a coupled run adds summary() to its own).
  void write_summary() const;
  //! One log line: the wall time the analysis took and its share of the run (not in summary.txt, which a
  //! run repeated with the same input reproduces byte for byte).
  std::string cost_note() const;

 private:
  void analyse(const fdem::RockSnapshot& s, const std::vector<int>& labels);  //!< the analysis files of a snapshot
  const RockCaseConfig& c_;
  fdem::RockSolver& solver_;
  const std::vector<std::vector<int>>& velocity_nodes_;
  const ibm::CrackGas* crack_ = nullptr;
  std::filesystem::path dir_;
  PvdSeries rock_pvd_, joints_pvd_;
  CsvSeries series_;
  std::optional<CsvSeries> fragmentation_, probes_;
  fdem::RockEnergies e0_;
  int index_ = 0;
  double ring_width_ = 0;  // [m] of the damage-zone rings
  // the last analysis (for summary.txt) and its cost
  fdem::SizeDistribution sizes_;
  std::vector<fdem::DamageZone> zones_;
  double largest_fraction_ = 0, analysed_at_ = -1;
  double analysis_seconds_ = 0;
  int analyses_ = 0;
  std::chrono::steady_clock::time_point started_ = std::chrono::steady_clock::now();
};

}  // namespace blastsim::app
