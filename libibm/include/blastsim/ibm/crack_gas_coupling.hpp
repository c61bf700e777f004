//! \file crack_gas_coupling.hpp
//! \brief The gas in the cracks as a coupling process (docs/coupling.md "Gas in the cracks"): every broken
//! joint carries its own gas in a CrackGas channel network, joined at the mesh vertices, opening into the grid
//! gas where a junction lies in an active cell or on the mesh outline beside one; each crack face is loaded by
//! its channel's pressure; a crack whose face meets the grid gas hands its gas to the grid.
#pragma once

#include "blastsim/cip/cell_deposits.hpp"
#include "blastsim/ibm/coupling_process.hpp"
#include "blastsim/ibm/crack_coupling_kernels.hpp"
#include "blastsim/ibm/crack_gas.hpp"

#include <array>
#include <memory>
#include <vector>

namespace blastsim::ibm {

namespace detail {
struct CrackCouplingArrays;
}

//! A coupling process (coupling_process.hpp) that owns the CrackGas of the rock's joints.
class CrackGasCoupling : public CouplingProcess {
 public:
  //! One channel segment per joint of `rock`, one junction per mesh vertex. Throws InputError on bad options,
  //! or if the rock was built without mesh vertices (FdemTopology::node_vertex).
  CrackGasCoupling(const fdem::RockSolver& rock, const cip::GasMaterials& materials, const CrackGasOptions& options);
  ~CrackGasCoupling() override;
  const char* name() const override { return "crack gas"; }

  CrackGas& crack_gas() { return *crack_; }
  const CrackGas& crack_gas() const { return *crack_; }

  std::vector<Stage> stages() const override {
    return {Stage::cover, Stage::after_cells, Stage::after_gas, Stage::before_rock_step, Stage::after_rock};
  }
  void run(Stage stage, CouplingContext& ctx, const StageStep& step) override;

  //! Pre-cut cracks whose faces touch in the mesh but stand `aperture` [m] apart (a hydraulic opening added
  //! to the faces' own; [[rock.crack]] initial_aperture). With CrackGasOptions::joint_closure their asperities
  //! close under the effective normal stress by the Barton-Bandis hyperbola (segment_width()). Throws InputError
  //! for a joint out of range, a negative aperture, or a maximum closure not below the aperture.
  void set_initial_apertures(const std::vector<int>& joints, double aperture);
  //! The crack widths [m] of the hand-over to the grid and back on grid g.
  HandoverGaps handover_gaps(const cip::GasGrid& g) const;
  //! The gap points a crack face's triangle owns lie within half the gap's widest end: 1.5 x the hand-over
  //! width (a gas segment's mean opening is below it) and a cell.
  double owner_margin(const cip::GasGrid& g) const override {
    return 1.5 * handover_gaps(g).handover + std::max(g.dx, g.dy);
  }

  //! Largest traced (blast) gas mass fraction [-] of the cracks at their mouths on the mesh outline farther
  //! than `radius` [m] from `center`, among those whose pressure is at least `min_pressure` [Pa] (a device
  //! reduction): the blast gas reaching the outer free face through the cracks.
  double outer_blast_fraction(const fdem::RockSolver& rock, std::array<double, 2> center, double radius,
                              double min_pressure) const;
  //! The blast gas's front in the cracks [m]: the largest distance from `center` of the midpoint of a crack
  //! whose own gas is at least `min_fraction` blast gas at a pressure of at least `min_pressure` [Pa]; 0 when
  //! none is (a device reduction).
  double blast_front(const fdem::RockSolver& rock, std::array<double, 2> center, double min_fraction,
                     double min_pressure) const;

  //! The crack gas's totals; its energy is held outside the grid and the rock (CouplingDiagnostics).
  void add_diagnostics(const CouplingContext& ctx, CouplingDiagnostics& d) const override;
  //! crack_gas_mass_kg_per_m, crack_gas_energy_J_per_m, crack_gas_segments, crack_wet_segments,
  //! crack_gas_pressure_max_Pa, crack_gas_to_grid_J_per_m, crack_gas_wall_work_J_per_m,
  //! crack_gas_unpaid_work_J_per_m (docs/input.md).
  void report(const CouplingDiagnostics& d, CsvRecord& o) const override;
  void write_checkpoint(CheckpointWriter& w) const override;
  void read_checkpoint(CheckpointReader& r) override;

 private:
  //! Rock -> gas (before the masks are made): every channel's length and aperture from the rock (crack_width());
  //! joints that just broke become empty gas segments; a gas segment whose volume changes does p dV on its
  //! walls; one whose faces are CrackGasOptions::handover_width cells apart hands its gas to the grid
  //! (CrackGeometryKernel); the gaps of the cracks that keep their own gas are solid to the grid
  //! (CrackGapCoverKernel), and the cells beside them the segments' claims.
  void cover(CouplingContext& ctx);
  //! After the cells changed state: each gas segment takes the gas of the cells it claims that were covered with
  //! no stable cell beside them (the reverse hand-over; CrackClaimedGasKernel).
  void after_cells(CouplingContext& ctx);
  //! After the gas step of dt [s]: the mouths from the cells' new gas, and what each may draw on over the step
  //! (the cells they share, sorted by cell).
  void after_gas(CouplingContext& ctx, double dt);
  //! Before every rock substep k of dt [s]: the channels' geometry from the rock as it stands (after substep 0:
  //! joints that broke in the last substep join the network, CrackGeometryKernel), the channels' own steps over
  //! dt (as many as their Courant limit needs), then their gas's pressure on the crack faces for the substep
  //! (CrackCushionKernel). So gas enters a crack one rock substep after it breaks, whatever the gas step.
  void before_rock_step(CouplingContext& ctx, int k, double dt);
  //! After the rock's substeps: what the mouths gave to or took from the cells over them and the gas handed
  //! over, deposited (sorted by cell: the same bytes whatever the thread order).
  void after_rock(CouplingContext& ctx);

  std::unique_ptr<CrackGas> crack_;
  //! Every channel's length, aperture and kind from the rock (CrackGeometryKernel).
  void update_geometry(CouplingContext& ctx);
  //! The deposit records' cell keys, sorted (records: the mouths' samples, then the segments).
  void sort_records(int records, int mouth_records);
  //! The deposit records: kMouthSamples a junction, then kHandoverSamples a segment.
  int record_count() const;
  double interval_ = 0;  //!< [s] the coupled step the rock's substeps fill (after_gas())
  std::unique_ptr<detail::CrackCouplingArrays> a_;
  std::unique_ptr<cip::CellDeposits> deposits_;  //!< the grid's deposit entries (made with the grid, in after_rock)
};

}  // namespace blastsim::ibm
