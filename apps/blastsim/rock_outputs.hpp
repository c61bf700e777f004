//! \file rock_outputs.hpp
//! \brief What a driver run writes about the rock, shared by rock-only and coupled runs: the VTU series of
//! triangles and joints, rock_series.csv, and the analysis of every snapshot (fragments, sizes, damage zones,
//! PPV).
#pragma once

#include "blastsim/core/checkpoint.hpp"
#include "blastsim/fdem/fragments.hpp"
#include "blastsim/fdem/rock_model.hpp"
#include "blastsim/ibm/crack_gas.hpp"
#include "case.hpp"
#include "rock_setup.hpp"
#include "run_loop.hpp"
#include "blastsim/core/output_files.hpp"

#include <chrono>
#include <filesystem>
#include <optional>
#include <string>

namespace blastsim::app {

//! rock.pvd / rock_NNNNNN.vtu, joints.pvd / joints_NNNNNN.vtu and rock_series.csv in the output folder
//! (energies, cracks, and the support reaction of each [[rock.velocity]] load: the force a testing machine's
//! platen measures); with [analysis] fragments (the default) at every snapshot fragments_NNNNNN.csv,
//! size_distribution.csv and a row of fragmentation_series.csv; with [[probe.rock_point]] rock_probes.csv
//! and ppv.csv (docs/analysis.md).
class RockOutputs {
 public:
  //! `resume`: a restart, whose read_checkpoint() follows (files are kept, not started anew).
  RockOutputs(const Case& c, const fdem::RockModel& model, bool resume = false);
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
  // the columns of rock_series.csv, fragmentation_series.csv and rock_probes.csv (CsvRecord, blastsim/core/output_files.hpp)
  void series_columns(CsvRecord& o, const fdem::RockEnergies& e, double balance,
                      const std::vector<std::array<double, 2>>& reactions) const;
  void fragmentation_columns(CsvRecord& o) const;
  void probe_columns(CsvRecord& o) const;
  const Case& c_;
  fdem::RockSolver& solver_;
  const std::vector<std::vector<int>>& velocity_nodes_;
  const std::vector<int>& joint_set_of_;  //!< the set of each joint (empty without joint sets)
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
