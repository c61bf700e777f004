//! \file crack_gas.hpp
//! \brief CrackGas: compressible gas in a network of channels narrower than a grid cell (the broken joints of
//! the rock), a 1-D finite-volume Euler solver on the crack graph with wall friction and choked mouths
//! (docs/coupling.md "Gas in the cracks"). Usable alone (tests build a straight channel) or through
//! CrackGasCoupling (a process of GasRockCoupler), which sets its geometry from the rock and its mouths from
//! the grid each step.
#pragma once

#include "blastsim/core/checkpoint_fwd.hpp"
#include "blastsim/cip/eos.hpp"
#include "blastsim/ibm/crack_gas_kernels.hpp"
#include "blastsim/ibm/crack_gas_types.hpp"

#include <array>
#include <memory>
#include <optional>
#include <vector>

namespace blastsim::ibm {


//! Per segment (joint), for output: the aperture [m] of a crack (0 for an intact joint), and the pressure [Pa]
//! and mass [kg/m] of its own gas (0 where it has none).
struct CrackSegmentFields {
  std::vector<double> aperture, gas_pressure, gas_mass;
  std::vector<double> blast_gas_fraction;  //!< mass fraction of the blast gas (products or traced gas) [-]
};

namespace detail {
struct CrackArrays;
}

class CrackGas {
 public:
  //! A network of `junctions` junctions and one segment per entry of `segment_ends` (its end 0 and end 1
  //! junctions). Throws InputError if a junction index is out of range or a junction has more than
  //! kCrackMaxDegree ends. Every segment starts as kSegmentNone (no crack), every junction closed.
  CrackGas(int junctions, const std::vector<std::array<int, 2>>& segment_ends, const cip::GasMaterials& materials,
           const CrackGasOptions& options);
  ~CrackGas();
  CrackGas(CrackGas&&) noexcept;
  CrackGas& operator=(CrackGas&&) noexcept;

  // --- host set-up (standalone use and tests) ---
  //! Length and aperture [m] of every segment.
  void set_geometry(const std::vector<double>& length, const std::vector<double>& aperture);
  //! Every segment's kind and gas (mass, momentum, energy, products) with its volume [m2 per m].
  void set_gas(const std::vector<std::uint8_t>& kind, const std::vector<ChannelConserved>& gas,
               const std::vector<double>& volume);
  //! Opens the listed junctions into reservoirs at rest in the given states (the others are closed).
  void set_reservoirs(const std::vector<int>& junctions, const std::vector<ChannelPrimitive>& states);

  // --- stepping ---
  //! Largest channel step [s]: courant / max over gas segments (and mouths) of the signal speed over length
  //! (a device reduction); infinity when no segment holds gas, 0 when a gas segment's state is not valid.
  double stable_dt() const;
  //! One step of dt [s] (no check of dt): primitives, MUSCL-Hancock faces, junction fluxes, update.
  void step(double dt);
  //! Advances by dt [s] in ceil(dt / stable_dt()) equal substeps; returns their number. InstabilityError
  //! (describe_invalid_segment()) when a gas segment's state is not valid (segment_state_valid()), or when dt
  //! would take more than kMaxSubsteps substeps (a segment whose signal crosses it far faster than the step
  //! allows: the run cannot go on at any useful speed).
  static constexpr int kMaxSubsteps = 100000;
  int advance(double dt) { return advance(dt, dt); }
  //! The same, as one of the pieces of a longer `interval` [s] >= dt over which the mouths' reservoirs stay as
  //! they are: each piece draws on them at most dt / interval of what they lend over the interval
  //! (JunctionFluxKernel), so the pieces together draw no more than the whole interval would.
  int advance(double dt, double interval);
  //! The first gas segment whose state is not valid, with its mass, momentum, energy, volume and aperture.
  std::string describe_invalid_segment() const;
  //! Recomputes the segments' primitive states (pressures for the faces' loads) from their gas.
  void update_primitives();
  //! [kg/m3] the density at or below which a segment is vacuum: options().vacuum_fraction times the densest gas
  //! the network touched (open mouths' reservoirs and gas segments) at the start of the last advance(); 0 before
  //! the first. In the checkpoint, so that a restart sees the same states.
  double vacuum_density() const { return vacuum_density_; }

  // --- device views (the coupling's kernels: crack_coupling_kernels.hpp) ---
  CrackGraph graph() const;
  CrackGeometry<Access::read_write> geometry();  //!< length and aperture, set from the rock each step
  CrackGeometry<Access::read> geometry() const;
  CrackSegments<Access::read_write> segments();  //!< kind, gas, volume, primitives
  CrackSegments<Access::read> segments() const;
  CrackMouths<Access::read_write> mouths();      //!< which junctions open into a reservoir, and its state
  CrackMouths<Access::read> mouths() const;
  CrackDeposits<Access::read> deposit_view() const;  //!< what the mouths gave their reservoirs in this step

  // --- results (host copies) ---
  CrackGasTotals totals(double reference_pressure = 0) const;
  std::vector<ChannelConserved> gas() const;
  std::vector<ChannelPrimitive> primitives() const;
  std::vector<std::uint8_t> kinds() const;
  std::vector<double> apertures() const;
  std::vector<double> volumes() const;
  CrackSegmentFields segment_fields() const;
  //! What went into each junction's reservoir since the last clear_deposits() (mass, energy, products).
  std::vector<ChannelConserved> deposits() const;
  void clear_deposits();

  void write_checkpoint(CheckpointWriter& w) const;
  void read_checkpoint(CheckpointReader& r);

  int segment_count() const { return segments_; }
  int junction_count() const { return junctions_; }
  const cip::GasMaterials& materials() const { return mat_; }
  const CrackGasOptions& options() const { return options_; }

 private:
  //! step() once the primitives are current: a substep of dt within an advance() of `interval` [s]
  void step_from_primitives(double dt, double interval);
  void check_kinds(const CheckpointReader& r) const;  //!< every restored kind is a CrackSegmentKind
  void update_vacuum_density();                        //!< from the reservoirs and segments as they stand
  int segments_ = 0, junctions_ = 0;
  double vacuum_density_ = 0.0;
  cip::GasMaterials mat_;
  CrackGasOptions options_;
  std::unique_ptr<detail::CrackArrays> a_;
};

}  // namespace blastsim::ibm
