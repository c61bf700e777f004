//! \file rock_outputs.hpp
//! \brief The rock side of a driver run: building the model (mesh, solver, loads) from a rock case, and what
//! the run writes about the rock (VTU series of triangles and joints, rock_series.csv). Shared by rock-only
//! and coupled runs. Include only from kernel sources.
#pragma once

#include "blastsim/core/checkpoint.hpp"
#include "blastsim/fdem/gmsh_mesh.hpp"
#include "blastsim/fdem/rock_solver.hpp"
#include "output_checkpoint.hpp"
#include "rock_config.hpp"

#include <filesystem>
#include <fstream>
#include <memory>

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
//! platen measures).
class RockOutputs {
 public:
  //! `resume`: a restart, whose read_checkpoint() follows (files are kept, not started anew).
  RockOutputs(const RockCaseConfig& c, const RockModel& model, bool resume = false);
  void snapshot();             //!< one .vtu pair (when output.vtk)
  fdem::RockEnergies monitor();  //!< one row of rock_series.csv; returns the energies
  void write_checkpoint(CheckpointWriter& w);  //!< snapshot count, initial energies, series sizes
  void read_checkpoint(CheckpointReader& r);
 private:
  const RockCaseConfig& c_;
  fdem::RockSolver& solver_;
  const std::vector<std::vector<int>>& velocity_nodes_;
  std::filesystem::path dir_;
  PvdSeries rock_pvd_, joints_pvd_;
  CsvSeries series_;
  fdem::RockEnergies e0_;
  int index_ = 0;
};

}  // namespace blastsim::app
