//! \file crack_gas_coupling.hpp
//! \brief The gas in the cracks as a coupling process (docs/coupling.md "Gas in the cracks"): every broken
//! joint carries its own gas in a CrackGas channel network, joined at the mesh vertices, opening into the grid
//! gas where a junction lies in an active cell or on the mesh outline beside one; each crack face is loaded by
//! its channel's pressure; a crack whose face meets the grid gas hands its gas to the grid.
#pragma once

#include "blastsim/ibm/coupling_process.hpp"
#include "blastsim/ibm/crack_gas.hpp"

#include <array>
#include <memory>

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

  //! Before the gas step: every channel's length and aperture from the rock (crack_width()); joints that just
  //! broke become empty gas segments; a gas segment whose volume changes does p dV on its walls; a segment
  //! whose face meets an active cell hands its gas to that cell (CrackGeometryKernel).
  void before_gas(CouplingContext& ctx, double dt) override;
  //! After the gas step: the mouths from the cells' new gas, the channels' own steps over dt (as many as their
  //! Courant limit needs), then what they gave to or took from the cells (deposits sorted by cell: the same
  //! bytes whatever the thread order).
  void after_gas(CouplingContext& ctx, double dt) override;
  //! The faces of every crack with its own gas take its pressure (after the grid gas's load).
  void load_rock(CouplingContext& ctx) override;

  //! Largest gas pressure [Pa] of the cracks at their mouths on the mesh outline farther than `radius` [m]
  //! from `center` (e.g. on the outer free face of a disc around a hole; a device reduction).
  double mouth_pressure(const fdem::RockSolver& rock, std::array<double, 2> center, double radius) const;
  //! The crack gas's front [m]: the largest distance from `center` of the midpoint of a crack that holds its
  //! own gas above `pressure` [Pa] (e.g. a quarter of the blasthole's pressure: how far the hole's gas has gone
  //! through the crack network); 0 when none does (a device reduction).
  double front(const fdem::RockSolver& rock, std::array<double, 2> center, double pressure) const;

  //! The crack gas's totals; its energy is held outside the grid and the rock (CouplingDiagnostics).
  void add_diagnostics(const CouplingContext& ctx, CouplingDiagnostics& d) const override;
  void write_checkpoint(CheckpointWriter& w) const override;
  void read_checkpoint(CheckpointReader& r) override;

 private:
  std::unique_ptr<CrackGas> crack_;
  std::unique_ptr<detail::CrackCouplingArrays> a_;
};

}  // namespace blastsim::ibm
