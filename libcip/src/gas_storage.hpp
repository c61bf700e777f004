//! \file gas_storage.hpp
//! \brief The gas solver's device arrays (internal), generated from field lists (core/device_groups.hpp): the
//! state with its derivatives and the state after the non-advection phase (the lists of gas_state.hpp), the
//! material fields, the immersed-boundary input, the outflow reference and ledger, and the work and ledger
//! arrays of a step (declared here); views and checkpoint records come from the same lists.
#pragma once

#include "blastsim/cip/gas_state.hpp"
#include "blastsim/cip/gas_step_kernels.hpp"
#include "blastsim/core/device_groups.hpp"

#include <string>

namespace blastsim::cip::detail {

//! Work arrays of a step, on the padded shape.
#define BLASTSIM_GAS_WORK(X)                                                                        \
  X(double, pressure, "P = p + q at cell centres of the last non-advection phase [Pa]")           \
  X(double, mass_flux_x, "mass flux through x-faces [kg/(m s)] (conservative transport)")         \
  X(double, mass_flux_y, "mass flux through y-faces [kg/(m s)]")                                   \
  X(double, energy_flux_x, "internal-energy flux through x-faces [W/m]")                           \
  X(double, energy_flux_y, "internal-energy flux through y-faces [W/m]")                           \
  X(double, internal_energy_density, "rho e of each cell during the transport [J/m3]")             \
  X(double, dissipation_u, "kinetic energy dissipated per x-face in the transport [J/m3]")         \
  X(double, dissipation_v, "kinetic energy dissipated per y-face [J/m3]")                           \
  X(std::uint8_t, troubled, "1 where the transport fell back to donor-cell fluxes this step")                \
  X(double, dual_along_momentum, "momentum flux through the along dual faces of one velocity (DualFluxKernel)")   \
  X(double, dual_along_kinetic, "kinetic-energy flux through them")                                              \
  X(double, dual_across_momentum, "momentum flux through the across dual faces")                                 \
  X(double, dual_across_kinetic, "kinetic-energy flux through them")
//! Cumulative arrays on the padded shape, checkpointed (GasSolver::immersed_face_work(), positivity_energy()).
#define BLASTSIM_GAS_LEDGERS(X)                                                                     \
  X(double, solid_work_u, "energy immersed x-faces gave the gas, per face [J/m3]")                 \
  X(double, solid_work_v, "energy immersed y-faces gave the gas, per face [J/m3]")                 \
  X(double, positivity_heat, "energy not taken by the kinetic-energy correction, per cell [J/m3]")
//! The transport's work arrays for the material fields, on the padded shape (sized only with products).
#define BLASTSIM_GAS_MATERIAL_WORK(X)                                                               \
  X(double, products_flux_x, "products mass flux through x-faces [kg/(m2 s)]")                     \
  X(double, products_flux_y, "products mass flux through y-faces [kg/(m2 s)]")                     \
  X(double, alpha_flux_x, "volume-fraction flux w alpha^ through x-faces [m/s]")                   \
  X(double, alpha_flux_y, "volume-fraction flux through y-faces [m/s]")                            \
  X(double, volume_flux_x, "face velocity of open x-faces, 0 on closed ones [m/s]")                \
  X(double, volume_flux_y, "face velocity of open y-faces [m/s]")                                 \
  X(double, products_energy_flux_x, "products' internal-energy flux through x-faces [W/m2]")        \
  X(double, products_energy_flux_y, "products' internal-energy flux through y-faces [W/m2]")        \
  X(double, products_energy, "products' internal energy per unit volume after the transport [J/m3]")

BLASTSIM_FIELD_GROUP(GasWork, BLASTSIM_GAS_WORK)
BLASTSIM_FIELD_GROUP(GasLedgers, BLASTSIM_GAS_LEDGERS)
BLASTSIM_FIELD_GROUP(MaterialWork, BLASTSIM_GAS_MATERIAL_WORK)

BLASTSIM_FIELD_STORAGE(CipField, BLASTSIM_CIP_FIELD_PARTS)
BLASTSIM_FIELD_STORAGE(MaterialFields, BLASTSIM_GAS_MATERIAL_FIELDS)
BLASTSIM_FIELD_STORAGE(ImmersedBoundaryInput, BLASTSIM_GAS_IMMERSED_INPUT)
BLASTSIM_FIELD_STORAGE(GasWork, BLASTSIM_GAS_WORK)
BLASTSIM_FIELD_STORAGE(GasLedgers, BLASTSIM_GAS_LEDGERS)
BLASTSIM_FIELD_STORAGE(MaterialWork, BLASTSIM_GAS_MATERIAL_WORK)
BLASTSIM_CONST_STORAGE(OutflowReference, BLASTSIM_GAS_OUTFLOW_REFERENCE)
BLASTSIM_STATE_STORAGE(OutflowLedgers, BLASTSIM_GAS_OUTFLOW_LEDGER)
BLASTSIM_STATE_STORAGE(GasSamples, BLASTSIM_GAS_SAMPLES)

//! Storage of the gas state: one CipField (value and derivatives) per unknown of BLASTSIM_GAS_UNKNOWNS.
struct GasStateArrays {
#define BLASTSIM_GAS_UNKNOWN_STORAGE(name, comment) CipFieldArrays name;
#define BLASTSIM_GAS_UNKNOWN_VIEW(name, comment) name.view<A>(shape),
#define BLASTSIM_GAS_UNKNOWN_READ(name, comment) name.read(shape),
#define BLASTSIM_GAS_UNKNOWN_VISIT(name, comment) \
  name.for_each([&](const char* part, auto& v) { fn(std::string(#name) + "." + part, v); });
  BLASTSIM_GAS_UNKNOWNS(BLASTSIM_GAS_UNKNOWN_STORAGE)
  template <Access A = Access::read_write>
  GasState<A> view(PaddedShape shape) {
    return {BLASTSIM_GAS_UNKNOWNS(BLASTSIM_GAS_UNKNOWN_VIEW)};
  }
  GasState<Access::read> read(PaddedShape shape) const { return {BLASTSIM_GAS_UNKNOWNS(BLASTSIM_GAS_UNKNOWN_READ)}; }
  //! fn("rho.f", array), fn("rho.gx", array), ... for every part of every unknown.
  template <class Fn>
  void for_each(Fn&& fn) {
    BLASTSIM_GAS_UNKNOWNS(BLASTSIM_GAS_UNKNOWN_VISIT)
  }
  template <class Fn>
  void for_each(Fn&& fn) const {
    BLASTSIM_GAS_UNKNOWNS(BLASTSIM_GAS_UNKNOWN_VISIT)
  }
#undef BLASTSIM_GAS_UNKNOWN_VISIT
#undef BLASTSIM_GAS_UNKNOWN_READ
#undef BLASTSIM_GAS_UNKNOWN_VIEW
#undef BLASTSIM_GAS_UNKNOWN_STORAGE
};

//! All arrays of one GasSolver.
struct GasArrays {
  GasStateArrays state;    //!< current state (n)
  GasStateArrays starred;  //!< after the non-advection phase (*)
  ImmersedBoundaryInputArrays immersed;
  MaterialFieldsArrays materials;  //!< state; empty without products
  GasWorkArrays work;
  GasLedgersArrays ledgers;
  MaterialWorkArrays material_work;  //!< empty without products
  OutflowReferenceArrays outflow_reference;  //!< per boundary face, set by initialise()
  OutflowLedgersArrays outflow_ledger;       //!< per boundary face, summed only when asked

  //! Sizes every array: n points of the padded shape, `boundary_faces` outflow entries; the material arrays
  //! only when `two_materials`. The immersed-boundary input starts with every cell active and no face
  //! prescribed.
  void resize(index_t n, index_t boundary_faces, bool two_materials) {
    auto zero = [](index_t size) { return [size](const auto& /*name*/, auto& v) { v.assign(size, 0); }; };
    state.for_each(zero(n));
    starred.for_each(zero(n));
    immersed.for_each(zero(n));
    immersed.cell_active.assign(n, 1);
    materials.for_each(zero(two_materials ? n : 0));
    work.for_each(zero(n));
    ledgers.for_each(zero(n));
    material_work.for_each(zero(two_materials ? n : 0));
    outflow_reference.for_each(zero(boundary_faces));
    outflow_ledger.face.assign(boundary_faces, OutflowLedger{0, 0, 0, 0, 0});
  }

  //! Calls fn(record name, array) for every array a checkpoint holds: the state with its derivatives, the
  //! immersed-boundary input, the outflow reference and ledger, the ledgers and the material fields. Self is
  //! GasArrays or const GasArrays.
  template <class Self, class Fn>
  static void for_each_checkpoint_array(Self& a, Fn&& fn) {
    auto named = [&](const std::string& prefix) {
      return [&fn, prefix](const auto& name, auto& v) { fn(prefix + name, v); };
    };
    a.state.for_each(named("gas."));
    a.immersed.for_each(named("gas."));
    a.outflow_reference.for_each(named("gas.outflow_"));
    a.ledgers.for_each(named("gas."));
    a.materials.for_each(named("gas."));
    fn("gas.outflow_ledger", a.outflow_ledger.face);
  }
};

}  // namespace blastsim::cip::detail
