//! \file coupler.cpp
//! \brief GasRockCoupler: rock-to-gas masks and velocities, gas-to-rock edge pressures, the coupled step.
#include "blastsim/ibm/coupler.hpp"

#include "blastsim/ibm/coupling_step_kernels.hpp"
#include "blastsim/core/backend.hpp"
#include "blastsim/core/checkpoint.hpp"

#include <thrust/fill.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace blastsim::ibm {


namespace detail {
//! The coupler's device arrays.
struct CouplerArrays {
  DeviceVector<int> u_owner, v_owner;  // padded shape: triangle covering each x-face / y-face point, -1: none
  DeviceVector<std::uint8_t> new_active, changed;  // padded shape: mask being built, cells whose gas moved
  DeviceVector<double> rho_next, e_next;           // padded shape: density and specific energy after the move
  DeviceVector<double> alpha_next, m1_next;        // padded shape: products fields after the move (two materials)
  DeviceVector<double> ledger;  // 4 per cell: covered, uncovered, mass created [kg/m], energy created [J/m]
};
}  // namespace detail

GasRockCoupler::GasRockCoupler(cip::GasSolver& gas, fdem::RockSolver& rock, const cip::GasPoint& ambient)
    : gas_(gas), rock_(rock), ambient_(ambient), a_(std::make_unique<detail::CouplerArrays>()) {
  const index_t n = gas_.grid().padded_shape().size();
  a_->u_owner.assign(n, -1);
  a_->v_owner.assign(n, -1);
  a_->new_active.assign(n, 1);
  a_->changed.assign(n, 0);
  a_->rho_next.assign(n, 0.0);
  a_->e_next.assign(n, 0.0);
  a_->alpha_next.assign(gas.materials().two ? n : 0, 0.0);
  a_->m1_next.assign(gas.materials().two ? n : 0, 0.0);
  a_->ledger.assign(4 * static_cast<index_t>(gas_.grid().nx) * gas_.grid().ny, 0.0);
}

GasRockCoupler::~GasRockCoupler() = default;

void GasRockCoupler::rock_to_gas() {
  const cip::GasGrid g = gas_.grid();
  const PaddedShape sh = g.padded_shape();
  thrust::fill(thrust::device, a_->u_owner.begin(), a_->u_owner.end(), -1);
  thrust::fill(thrust::device, a_->v_owner.begin(), a_->v_owner.end(), -1);
  const fdem::RockView rock = rock_.view();
  const Field2D<int> uo = make_field_view(a_->u_owner, sh), vo = make_field_view(a_->v_owner, sh);
  for_each_index("ibm.cover", rock.triangles, CoverKernel{rock, g, uo, vo});
  const cip::ImmersedBoundaryView ib = gas_.immersed_boundary();
  for_each_cell("ibm.face_velocity.u", 0, g.nx + 1, 0, g.ny, ImposedVelocityKernel{rock, g, 0, uo, ib.u_prescribed, ib.u_imposed});
  for_each_cell("ibm.face_velocity.v", 0, g.nx, 0, g.ny + 1, ImposedVelocityKernel{rock, g, 1, vo, ib.v_prescribed, ib.v_imposed});
  const Field2D<std::uint8_t> fresh = make_field_view(a_->new_active, sh), changed = make_field_view(a_->changed, sh);
  const Field2D<double> rho_next = make_field_view(a_->rho_next, sh), e_next = make_field_view(a_->e_next, sh);
  for_each_cell("ibm.cells.mask", 0, g.nx, 0, g.ny, NewMaskKernel{uo, vo, fresh});
  const cip::GasStateView s = gas_.state();
  const bool two = gas_.materials().two;
  const cip::MaterialView m = gas_.material_fields();
  const cip::MaterialView next{make_field_view(a_->alpha_next, sh), make_field_view(a_->m1_next, sh)};
  for_each_cell("ibm.cells.transition", 0, g.nx, 0, g.ny,
                TransitionKernel{ib.cell_active, fresh, s.rho.f, s.e.f, s.u.f, s.v.f, rho_next, e_next, two, m, next,
                                 changed, device_ptr(a_->ledger), g.nx, g.ny, g.cell_area(), ambient_.density,
                                 ambient_.internal_energy, !masks_set_});
  for_each_cell("ibm.cells.apply", 0, g.nx, 0, g.ny,
                ApplyTransitionKernel{fresh, changed, rho_next, e_next, ib.u_imposed, ib.v_imposed, ib.cell_active, s,
                                      two, next, m});
  masks_set_ = true;
  gas_.apply_boundaries();
}

void GasRockCoupler::gas_to_rock() {
  const cip::GasGrid g = gas_.grid();
  const cip::GasStateView s = gas_.state();
  const cip::ImmersedBoundaryView ib = gas_.immersed_boundary();
  const fdem::RockView rock = rock_.view();
  const cip::GasMaterials& mat = gas_.materials();
  for_each_index("ibm.edge_pressure", 3 * static_cast<index_t>(rock.triangles),
                 EdgePressureKernel{rock, g, mat, gas_.material_fields(), ib.cell_active, s.rho.f, s.e.f,
                                    mat.air.pressure(ambient_.density, ambient_.internal_energy)});
}

void GasRockCoupler::step(double dt, int rock_substeps) {
  if (rock_substeps < 1) throw std::invalid_argument("GasRockCoupler::step: rock_substeps must be at least 1");
  rock_to_gas();
  gas_.step(dt);
  gas_to_rock();
  const double rock_dt = dt / rock_substeps;
  for (int k = 0; k < rock_substeps; ++k) rock_.step(rock_dt);
}

double GasRockCoupler::stable_dt(double courant) const { return std::min(gas_.courant_dt(courant), rock_.stable_dt()); }


CouplingDiagnostics GasRockCoupler::diagnostics() const {
  CouplingDiagnostics d;
  const Vec2Sum f = reduce_sum("ibm.gas_force", 3 * static_cast<index_t>(rock_.triangle_count()), Vec2Sum{0, 0},
                               EdgeForceOf{rock_.view()});
  d.gas_force_on_rock = {f.x, f.y};
  d.gas_work_on_rock = rock_.energies().pressure_work;
  const double* led = device_ptr(a_->ledger);
  auto total = [&](int c) {
    return reduce_sum("ibm.ledger", static_cast<index_t>(a_->ledger.size() / 4), 0.0,
                      [=] BLAST_HD(index_t k) { return led[4 * k + c]; });
  };
  d.transitions.covered = std::lround(total(0));
  d.transitions.uncovered = std::lround(total(1));
  d.transitions.mass_created = total(2);
  d.transitions.energy_created = total(3);
  return d;
}

long GasRockCoupler::inactive_cells() const {
  const cip::GasGrid g = gas_.grid();
  const Field2D<const std::uint8_t> active = gas_.immersed_boundary().cell_active;
  const int nx = g.nx;
  return static_cast<long>(reduce_sum("ibm.inactive", static_cast<index_t>(g.nx) * g.ny, 0.0, [=] BLAST_HD(index_t k) {
    return active(static_cast<int>(k % nx), static_cast<int>(k / nx)) ? 0.0 : 1.0;
  }));
}

void GasRockCoupler::write_checkpoint(CheckpointWriter& w) const {
  w.value("ibm.masks_set", static_cast<int>(masks_set_));
  w.array("ibm.ledger", a_->ledger);
}

void GasRockCoupler::read_checkpoint(CheckpointReader& r) {
  const int masks = r.value<int>("ibm.masks_set");
  if (masks != 0 && masks != 1) r.fail("ibm.masks_set", "not 0 or 1");
  masks_set_ = masks == 1;
  r.array("ibm.ledger", a_->ledger, a_->ledger.size());
}

}  // namespace blastsim::ibm
