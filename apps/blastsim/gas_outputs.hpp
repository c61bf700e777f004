//! \file gas_outputs.hpp
//! \brief What a driver run writes about the gas: VTK snapshots, line and point probes, the conservation
//! monitor (gas_totals.csv); shared by gas-only and coupled runs.
#pragma once

#include "blastsim/cip/balance.hpp"
#include "blastsim/cip/gas_solver.hpp"
#include "blastsim/core/checkpoint.hpp"
#include "case.hpp"
#include "run_loop.hpp"
#include "blastsim/core/output_files.hpp"

#include <filesystem>
#include <ostream>
#include <string>
#include <vector>

namespace blastsim::app {

//! The snapshot times of output.interval and output.times: due() at a time [s] within `tol` of one, then
//! advance() past it.
struct SnapshotSchedule {
  double next = 0;    //!< [s] the next time of the interval's schedule
  size_t listed = 0;  //!< the first of output.times not yet written
  bool due(const OutputSettings& o, double t, double tol) const;
  void advance(const OutputSettings& o, double t, double tol);
};

//! Output state of one run's gas: files, schedules and open CSV streams.
class GasOutputs {
 public:
  //! `gas_alone`: false in a coupled run, where the gas exchanges energy with the rock and cells that the rock
  //! uncovers start with ambient gas: gas_totals.csv is written but not watched (the coupled budget, with
  //! those transitions, is in coupling_series.csv). `resume`: a restart, whose read_checkpoint() follows (files
  //! are kept, not started anew).
  GasOutputs(const Case& c, cip::GasSolver& solver, std::ostream& log, bool gas_alone = true, bool resume = false);

  //! The output schedule, the monitor's reference and the sizes of the CSV files, for a restart.
  void write_checkpoint(CheckpointWriter& w);
  void read_checkpoint(CheckpointReader& r);

  //! Earliest pending event time after t (snapshot, line probe, end), for the Courant-mode dt clip.
  double next_event(double t) const;
  //! Writes whatever is due at the solver's current time (force: snapshot regardless of schedule).
  //! Returns true when a snapshot was due (and written, when output.vtk).
  bool write_due(double dt, bool force_snapshot);
  //! The end of a run, after write_due(dt, false) wrote what the schedule asked for: the snapshot (unless
  //! that call wrote one) and the monitor row (unless the step was a monitor step) that close every run.
  void write_end(double dt, bool snapshot_written);

 private:
  void snapshot();
  void write_line(const ProbeSettings::Line& l, size_t m);
  void sample_points(double t);
  //! The conservation monitor: totals in the domain, what crossed the outer boundary, and the relative
  //! drift of the balance (in domain + out - initial) / initial; a warning when it exceeds the threshold.
  void monitor(double dt);
  void warn_once(bool& warned, const char* what, double drift);
  //! The columns of gas_totals.csv (CsvRecord, blastsim/core/output_files.hpp).
  void totals_columns(CsvRecord& r, double dt, const cip::GasTotals& s, const cip::BoundaryOutflow& o,
                      const cip::BalanceDrift& drift) const;

  const Case& c_;
  cip::GasSolver& solver_;
  std::ostream& log_;
  bool gas_alone_;
  cip::GasTotals initial_;
  bool mass_warned_ = false, energy_warned_ = false;
  std::filesystem::path dir_;
  PvdSeries pvd_;
  CsvSeries totals_;
  std::vector<CsvSeries> point_files_;
  std::vector<double> next_point_;
  std::vector<std::vector<bool>> line_done_;
  SnapshotSchedule schedule_;
  int snapshot_index_ = 0;
};

}  // namespace blastsim::app
