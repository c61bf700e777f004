//! \file conservative_transport.cpp
//! \brief GasSolver::transport_conservatively(): the flux-form transport phase (transport_kernels.hpp has the
//! scheme and its kernels).
#include "blastsim/cip/gas_solver.hpp"
#include "blastsim/cip/transport_kernels.hpp"
#include "gas_storage.hpp"
#include "ghosts.hpp"

namespace blastsim::cip {

void GasSolver::transport_conservatively(double dt) {
  const GasGrid g = grid_;
  const PaddedShape sh = g.padded_shape();
  const StepViews v = step_views();
  const GasStateView& s = v.starred;
  const Field2D<double> Fx = make_field_view(a_->mass_flux_x, sh), Fy = make_field_view(a_->mass_flux_y, sh);
  const Field2D<double> Ex = make_field_view(a_->energy_flux_x, sh), Ey = make_field_view(a_->energy_flux_y, sh);
  const Field2D<double> rho_e = make_field_view(a_->internal_energy_density, sh);
  const Field2D<double> Du = make_field_view(a_->dissipation_u, sh), Dv = make_field_view(a_->dissipation_v, sh);
  const bool px = options_.boundaries.kind(left) == BoundaryKind::periodic;
  const bool py = options_.boundaries.kind(bottom) == BoundaryKind::periodic;

  const MaterialView m = a_->materials(sh);
  const Field2D<double> Mx = make_field_view(a_->products_flux_x, sh), My = make_field_view(a_->products_flux_y, sh);
  const Field2D<double> Ax = make_field_view(a_->alpha_flux_x, sh), Ay = make_field_view(a_->alpha_flux_y, sh);
  const Field2D<double> Wx = make_field_view(a_->volume_flux_x, sh), Wy = make_field_view(a_->volume_flux_y, sh);
  const GasMaterials& mat = materials_;
  const bool fuse = fuse_kernels();
  const Limiter lim = options_.limiter;
  for_each_cell_fused(
      "cip.transport.flux", fuse,
      cell_part("cip.transport.flux_x", IndexBox{0, g.nx + 1, 0, g.ny},
                MassFluxKernel{0, s, v.active, Fx, Ex, dt, g.dx, g.dy, lim, mat, m, Mx, Ax, Wx}),
      cell_part("cip.transport.flux_y", IndexBox{0, g.nx, 0, g.ny + 1},
                MassFluxKernel{1, s, v.active, Fy, Ey, dt, g.dy, g.dx, lim, mat, m, My, Ay, Wy}));
  for_each_cell("cip.transport.cells", 0, g.nx, 0, g.ny,
                CellFluxUpdateKernel{s, v.now, v.active, Fx, Fy, Ex, Ey, rho_e, dt, g.dx, g.dy, mat.two, m, Mx, My, Ax,
                                     Ay, Wx, Wy});
  if (mat.two) fill_material_ghosts(m, g, options_.boundaries);
  // Interior faces, and wall faces (held at rest, their incoming kinetic energy turned into heat). Outflow
  // faces are set by the ghost fill (characteristic condition); what they carry leaves the domain.
  fill_device("cip.transport.clear_u", a_->dissipation_u, 0.0);
  fill_device("cip.transport.clear_v", a_->dissipation_v, 0.0);
  const BoundaryConditions& bc = options_.boundaries;
  const bool wl = bc.kind(left) == BoundaryKind::wall, wr = bc.kind(right) == BoundaryKind::wall;
  const bool wb = bc.kind(bottom) == BoundaryKind::wall, wt = bc.kind(top) == BoundaryKind::wall;
  for_each_cell_fused(
      "cip.transport.momentum", fuse,
      cell_part("cip.transport.momentum_u", IndexBox{px || wl ? 0 : 1, wr ? g.nx + 1 : g.nx, 0, g.ny},
                MomentumKernel{0, s, v.now, Fx, Fy, v.u_prescribed, v.u_imposed, Du, make_field_view(a_->solid_work_u, sh),
                               g.nx, g.ny, px, py, wl, wr, dt, g.dx, g.dy, lim}),
      cell_part("cip.transport.momentum_v", IndexBox{0, g.nx, py || wb ? 0 : 1, wt ? g.ny + 1 : g.ny},
                MomentumKernel{1, s, v.now, Fx, Fy, v.v_prescribed, v.v_imposed, Dv, make_field_view(a_->solid_work_v, sh),
                               g.nx, g.ny, px, py, wb, wt, dt, g.dx, g.dy, lim}));
  for_each_cell("cip.transport.energy", 0, g.nx, 0, g.ny,
                EnergyUpdateKernel{v.now, v.active, rho_e, Du, Dv, make_field_view(a_->positivity_heat, sh), g.nx, g.ny, px, py,
                                   mat, m});
}

}  // namespace blastsim::cip
