//! \file gas_storage.hpp
//! \brief The gas solver's device arrays (internal): the state, the state after the non-advection phase, the
//! immersed-boundary input, and the work arrays of a step, each declared once; views and checkpoint records
//! come from these declarations.
#pragma once

#include "blastsim/cip/gas_state.hpp"
#include "blastsim/core/backend.hpp"

#include <array>
#include <string>

namespace blastsim::cip::detail {

//! Owning storage of one CIP unknown.
struct CipField {
  DeviceVector<double> f, gx, gy;
  void resize(index_t n) {
    f.assign(n, 0.0);
    gx.assign(n, 0.0);
    gy.assign(n, 0.0);
  }
  CipFieldView view(PaddedShape s) {
    return {make_field_view(f, s), make_field_view(gx, s), make_field_view(gy, s)};
  }
};

//! Owning storage of the gas state.
struct GasState {
  CipField rho, e, u, v;
  void resize(index_t n) {
    rho.resize(n);
    e.resize(n);
    u.resize(n);
    v.resize(n);
  }
  GasStateView view(PaddedShape s) { return {rho.view(s), e.view(s), u.view(s), v.view(s)}; }
};

//! Owning storage of the immersed-boundary input; by default every cell active and no face prescribed.
struct ImmersedBoundaryArrays {
  DeviceVector<std::uint8_t> cell_active, u_prescribed, v_prescribed;
  DeviceVector<double> u_imposed, v_imposed;
  void resize(index_t n) {
    cell_active.assign(n, 1);
    u_prescribed.assign(n, 0);
    v_prescribed.assign(n, 0);
    u_imposed.assign(n, 0.0);
    v_imposed.assign(n, 0.0);
  }
  ImmersedBoundaryView view(PaddedShape s) {
    return {make_field_view(cell_active, s), make_field_view(u_prescribed, s), make_field_view(v_prescribed, s),
            make_field_view(u_imposed, s), make_field_view(v_imposed, s)};
  }
};

//! Work arrays of a step, on the padded shape (X(name, comment)).
#define BLASTSIM_GAS_WORK_ARRAYS(X)                                              \
  X(pressure, "P = p + q at cell centres of the last non-advection phase [Pa]")  \
  X(mass_flux_x, "mass flux through x-faces [kg/(m s)] (conservative transport)") \
  X(mass_flux_y, "mass flux through y-faces [kg/(m s)]")                          \
  X(energy_flux_x, "internal-energy flux through x-faces [W/m]")                  \
  X(energy_flux_y, "internal-energy flux through y-faces [W/m]")                  \
  X(internal_energy_density, "rho e of each cell during the transport [J/m3]")    \
  X(dissipation_u, "kinetic energy dissipated per x-face in the transport [J/m3]")\
  X(dissipation_v, "kinetic energy dissipated per y-face [J/m3]")
//! Cumulative arrays on the padded shape, checkpointed (immersed_face_work()).
#define BLASTSIM_GAS_LEDGER_ARRAYS(X)                                                         \
  X(solid_work_u, "energy immersed x-faces gave the gas, per face [J/m3]")                     \
  X(solid_work_v, "energy immersed y-faces gave the gas, per face [J/m3]")                     \
  X(positivity_heat, "energy not taken by the kinetic-energy correction, per cell [J/m3]")
//! Material fields (GasMaterials) and the transport's work arrays for them, on the padded shape; sized only in
//! a run with products (empty otherwise). The first two are state and checkpointed.
#define BLASTSIM_GAS_MATERIAL_ARRAYS(X)                                                     \
  X(alpha, "volume fraction of the detonation products [-]")                                \
  X(m1, "partial density of the products alpha rho1 [kg/m3]")
#define BLASTSIM_GAS_MATERIAL_WORK_ARRAYS(X)                                                \
  X(products_flux_x, "products mass flux through x-faces [kg/(m2 s)]")                      \
  X(products_flux_y, "products mass flux through y-faces [kg/(m2 s)]")                      \
  X(alpha_flux_x, "volume-fraction flux w alpha^ through x-faces [m/s]")                    \
  X(alpha_flux_y, "volume-fraction flux through y-faces [m/s]")                             \
  X(volume_flux_x, "face velocity of open x-faces, 0 on closed ones [m/s]")                 \
  X(volume_flux_y, "face velocity of open y-faces [m/s]")
//! Reference state of the outflow faces (OutflowReference order), set by initialise(), checkpointed.
#define BLASTSIM_GAS_OUTFLOW_ARRAYS(X)                                  \
  X(outflow_pressure, "pressure of the cell beside each boundary face at the start [Pa]") \
  X(outflow_velocity, "outward face velocity at the start [m/s]")

#define BLASTSIM_GAS_DEVICE_ARRAY(name, comment) DeviceVector<double> name;

//! All arrays of one GasSolver.
struct GasArrays {
  GasState state;    //!< current state (n)
  GasState starred;  //!< after the non-advection phase (*)
  ImmersedBoundaryArrays immersed;
  BLASTSIM_GAS_WORK_ARRAYS(BLASTSIM_GAS_DEVICE_ARRAY)
  BLASTSIM_GAS_LEDGER_ARRAYS(BLASTSIM_GAS_DEVICE_ARRAY)
  BLASTSIM_GAS_OUTFLOW_ARRAYS(BLASTSIM_GAS_DEVICE_ARRAY)
  BLASTSIM_GAS_MATERIAL_ARRAYS(BLASTSIM_GAS_DEVICE_ARRAY)
  BLASTSIM_GAS_MATERIAL_WORK_ARRAYS(BLASTSIM_GAS_DEVICE_ARRAY)
  //! What left through each boundary face since initialise() (OutflowReference order), kOutflowLedgerWidth
  //! entries a face, summed only when asked (GasSolver::boundary_outflow()): the step never waits for it.
  //! Checkpointed.
  DeviceVector<double> outflow_ledger;

  MaterialView materials(PaddedShape s) { return {make_field_view(alpha, s), make_field_view(m1, s)}; }

  //! Sizes every array: n points of the padded shape, `boundary_faces` outflow reference entries; the material
  //! arrays only when `two_materials`.
  void resize(index_t n, index_t boundary_faces, bool two_materials) {
#define BLASTSIM_GAS_ASSIGN_MATERIAL(name, comment) name.assign(two_materials ? n : 0, 0.0);
    BLASTSIM_GAS_MATERIAL_ARRAYS(BLASTSIM_GAS_ASSIGN_MATERIAL)
    BLASTSIM_GAS_MATERIAL_WORK_ARRAYS(BLASTSIM_GAS_ASSIGN_MATERIAL)
#undef BLASTSIM_GAS_ASSIGN_MATERIAL
    state.resize(n);
    starred.resize(n);
    immersed.resize(n);
#define BLASTSIM_GAS_ASSIGN(name, comment) name.assign(n, 0.0);
    BLASTSIM_GAS_WORK_ARRAYS(BLASTSIM_GAS_ASSIGN)
    BLASTSIM_GAS_LEDGER_ARRAYS(BLASTSIM_GAS_ASSIGN)
#undef BLASTSIM_GAS_ASSIGN
    outflow_pressure.assign(boundary_faces, 0.0);
    outflow_velocity.assign(boundary_faces, 0.0);
    outflow_ledger.assign(kOutflowLedgerWidth * boundary_faces, 0.0);
  }

  //! Calls fn(record name, array) for every array a checkpoint holds: the state with its derivatives, the
  //! immersed-boundary input, the outflow reference and the ledgers. Self is GasArrays or const GasArrays.
  template <class Self, class Fn>
  static void for_each_checkpoint_array(Self& a, Fn&& fn) {
    const char* unknowns[4] = {"rho", "e", "u", "v"};
    const std::array<decltype(&a.state.rho), 4> fields{&a.state.rho, &a.state.e, &a.state.u, &a.state.v};
    for (int k = 0; k < 4; ++k) {
      fn(std::string("gas.") + unknowns[k] + ".f", fields[k]->f);
      fn(std::string("gas.") + unknowns[k] + ".gx", fields[k]->gx);
      fn(std::string("gas.") + unknowns[k] + ".gy", fields[k]->gy);
    }
    fn("gas.cell_active", a.immersed.cell_active);
    fn("gas.u_prescribed", a.immersed.u_prescribed);
    fn("gas.v_prescribed", a.immersed.v_prescribed);
    fn("gas.u_imposed", a.immersed.u_imposed);
    fn("gas.v_imposed", a.immersed.v_imposed);
#define BLASTSIM_GAS_VISIT(name, comment) fn("gas." #name, a.name);
    BLASTSIM_GAS_OUTFLOW_ARRAYS(BLASTSIM_GAS_VISIT)
    BLASTSIM_GAS_LEDGER_ARRAYS(BLASTSIM_GAS_VISIT)
    BLASTSIM_GAS_MATERIAL_ARRAYS(BLASTSIM_GAS_VISIT)
#undef BLASTSIM_GAS_VISIT
    fn("gas.outflow_ledger", a.outflow_ledger);
  }
};

#undef BLASTSIM_GAS_DEVICE_ARRAY

}  // namespace blastsim::cip::detail
