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
  const detail::GasWork<Access::read_write> w = a_->work.view(sh);
  const Field2D<double> Fx = w.mass_flux_x, Fy = w.mass_flux_y, Ex = w.energy_flux_x, Ey = w.energy_flux_y;
  const Field2D<double> rho_e = w.internal_energy_density, Du = w.dissipation_u, Dv = w.dissipation_v;
  const detail::GasLedgers<Access::read_write> ledgers = a_->ledgers.view(sh);
  const Field2D<const std::uint8_t> active = v.ib.cell_active;
  const bool px = options_.boundaries.kind(left) == BoundaryKind::periodic;
  const bool py = options_.boundaries.kind(bottom) == BoundaryKind::periodic;

  const MaterialView m = a_->materials.view(sh);
  const detail::MaterialWork<Access::read_write> mw = a_->material_work.view(sh);
  const Field2D<double> Mx = mw.products_flux_x, My = mw.products_flux_y, Ax = mw.alpha_flux_x, Ay = mw.alpha_flux_y;
  const Field2D<double> Wx = mw.volume_flux_x, Wy = mw.volume_flux_y;
  const Field2D<double> Px = mw.products_energy_flux_x, Py = mw.products_energy_flux_y, E1 = mw.products_energy;
  const GasMaterials& mat = materials_;
  const bool fuse = fuse_kernels();
  const Limiter lim = options_.limiter;
  for_each_cell_fused(
      "cip.transport.flux", fuse,
      cell_part("cip.transport.flux_x", IndexBox{0, g.nx + 1, 0, g.ny},
                MassFluxKernel{0, s, active, Fx, Ex, dt, g.dx, g.dy, lim, mat, m, Mx, Ax, Wx, Px}),
      cell_part("cip.transport.flux_y", IndexBox{0, g.nx, 0, g.ny + 1},
                MassFluxKernel{1, s, active, Fy, Ey, dt, g.dy, g.dx, lim, mat, m, My, Ay, Wy, Py}));
  if (!mat.two && lim != Limiter::none) {
    // Troubled cells take donor-cell fluxes on their faces; a second check catches the neighbours whose
    // update those faces changed (TroubledCellKernel).
    const Field2D<std::uint8_t> troubled = w.troubled;
    fill_device("cip.transport.clear_troubled", a_->work.troubled, std::uint8_t{0});
    for (int pass = 0; pass < kTroubledPasses; ++pass) {
      for_each_cell("cip.transport.check", 0, g.nx, 0, g.ny,
                    TroubledCellKernel{s, active, Fx, Fy, Ex, Ey, troubled, dt, g.dx, g.dy, kTroubledRelax, pass > 0,
                                       g.nx, g.ny, px, py});
      for_each_cell_fused(
          "cip.transport.donor", fuse,
          cell_part("cip.transport.donor_x", IndexBox{0, g.nx + 1, 0, g.ny},
                    DonorCellFluxKernel{0, s, active, troubled, Fx, Ex, mat.tracer, m, Mx, g.nx, g.ny, px}),
          cell_part("cip.transport.donor_y", IndexBox{0, g.nx, 0, g.ny + 1},
                    DonorCellFluxKernel{1, s, active, troubled, Fy, Ey, mat.tracer, m, My, g.nx, g.ny, py}));
    }
  }
  for_each_cell("cip.transport.cells", 0, g.nx, 0, g.ny,
                CellFluxUpdateKernel{s, v.now, active, Fx, Fy, Ex, Ey, rho_e, dt, g.dx, g.dy, mat.two, mat.traced(), m, Mx, My, Ax,
                                     Ay, Wx, Wy, mat, Px, Py, E1});
  if (mat.traced()) fill_material_ghosts(m, g, options_.boundaries);
  // Interior faces, and wall faces (held at rest, their incoming kinetic energy turned into heat). Outflow
  // faces are set by the ghost fill (characteristic condition); what they carry leaves the domain.
  fill_device("cip.transport.clear_u", a_->work.dissipation_u, 0.0);
  fill_device("cip.transport.clear_v", a_->work.dissipation_v, 0.0);
  const BoundaryConditions& bc = options_.boundaries;
  const bool wl = bc.kind(left) == BoundaryKind::wall, wr = bc.kind(right) == BoundaryKind::wall;
  const bool wb = bc.kind(bottom) == BoundaryKind::wall, wt = bc.kind(top) == BoundaryKind::wall;
  const IndexBox u_faces{px || wl ? 0 : 1, wr ? g.nx + 1 : g.nx, 0, g.ny};
  const IndexBox v_faces{0, g.nx, py || wb ? 0 : 1, wt ? g.ny + 1 : g.ny};
  const DualFaces dual_u{0, s, Fx, Fy, g.nx, g.ny, px, py, dt, g.dx, g.dy, lim};
  const DualFaces dual_v{1, s, Fx, Fy, g.nx, g.ny, px, py, dt, g.dx, g.dy, lim};
  const MomentumKernel momentum_u{dual_u, v.now, v.ib.u_prescribed, v.ib.u_imposed, Du, ledgers.solid_work_u, wl, wr, {}};
  const MomentumKernel momentum_v{dual_v, v.now, v.ib.v_prescribed, v.ib.v_imposed, Dv, ledgers.solid_work_v, wb, wt, {}};
  if (fuse) {
    // One launch for both velocities; each face computes its four dual faces' fluxes (on a GPU arithmetic is
    // cheaper than the traffic of storing them).
    for_each_cell_fused("cip.transport.momentum", fuse, cell_part("cip.transport.momentum_u", u_faces, momentum_u),
                        cell_part("cip.transport.momentum_v", v_faces, momentum_v));
  } else {
    // Host threads: each dual face's flux once (DualFluxKernel), then the faces read them; half the swept values.
    const Field2D<double> am = w.dual_along_momentum, ak = w.dual_along_kinetic;
    const Field2D<double> cm = w.dual_across_momentum, ck = w.dual_across_kinetic;
    const SharedDualFluxes shared{am, ak, cm, ck};
    for (const MomentumKernel* k : {&momentum_u, &momentum_v}) {
      const bool x = k->d.axis == 0;
      const IndexBox f = x ? u_faces : v_faces;
      const IndexBox along = x ? IndexBox{f.i0 - 1, f.i1, f.j0, f.j1} : IndexBox{f.i0, f.i1, f.j0 - 1, f.j1};
      const IndexBox across = x ? IndexBox{f.i0, f.i1, f.j0, f.j1 + 1} : IndexBox{f.i0, f.i1 + 1, f.j0, f.j1};
      for_each_cell(x ? "cip.transport.dual_u.along" : "cip.transport.dual_v.along", along.i0, along.i1, along.j0,
                    along.j1, DualFluxKernel{k->d, 0, am, ak});
      for_each_cell(x ? "cip.transport.dual_u.across" : "cip.transport.dual_v.across", across.i0, across.i1,
                    across.j0, across.j1, DualFluxKernel{k->d, 1, cm, ck});
      MomentumKernel with_shared = *k;
      with_shared.shared = shared;
      for_each_cell(x ? "cip.transport.momentum_u" : "cip.transport.momentum_v", f.i0, f.i1, f.j0, f.j1, with_shared);
    }
  }
  for_each_cell("cip.transport.energy", 0, g.nx, 0, g.ny,
                EnergyUpdateKernel{v.now, active, rho_e, Du, Dv, ledgers.positivity_heat, g.nx, g.ny, px, py,
                                   mat, m, E1});
}

}  // namespace blastsim::cip
