//! \file gas_solver.cpp
//! \brief The CIP gas step (paper eqs. 1-5; Yabe & Aoki 1991; Yabe, Xiao & Utsumi 2001) as device kernels.
#include "blastsim/cip/gas_solver.hpp"

#include "blastsim/core/checkpoint.hpp"
#include "blastsim/core/device_groups.hpp"

#include "blastsim/core/error.hpp"
#include "blastsim/cip/gas_step_kernels.hpp"
#include "gas_storage.hpp"
#include "ghosts.hpp"

#include <cmath>
#include <limits>
#include <sstream>
#include <utility>

namespace blastsim::cip {

GasGrid GasGrid::from_box(int nx, int ny, double x0, double x1, double y0, double y1) {
  if (nx < 3 || ny < 3) throw InputError("gas grid needs at least 3 cells along x and y");
  if (!(x1 > x0) || !(y1 > y0)) throw InputError("gas grid box is empty (need x_max > x_min, y_max > y_min)");
  return GasGrid{nx, ny, x0, y0, (x1 - x0) / nx, (y1 - y0) / ny};
}



void GasSolver::accumulate_boundary_outflow(double dt) {
  const PaddedShape sh = grid_.padded_shape();
  const detail::GasWork<Access::read> w = a_->work.read(sh);
  const detail::MaterialWork<Access::read> mw = a_->material_work.read(sh);
  for_each_index(
      "cip.boundary_outflow", 2 * static_cast<index_t>(grid_.nx + grid_.ny),
      OutflowLedgerKernel{BoundaryFlowKernel{a_->starred.read(sh), w.pressure, w.mass_flux_x, w.mass_flux_y,
                                             w.energy_flux_x, w.energy_flux_y, mw.products_flux_x, mw.products_flux_y,
                                             options_.transport == Transport::conservative, materials_.traced(), grid_,
                                             options_.boundaries},
                          a_->outflow_ledger.view(), dt});
}

BoundaryOutflow GasSolver::boundary_outflow() const {
  const TotalsSum t = reduce_sum("cip.outflow_total", 2 * static_cast<index_t>(grid_.nx + grid_.ny),
                                 TotalsSum{0, 0, 0, 0, 0, 0}, OutflowLedgerTotals{a_->outflow_ledger.read()});
  BoundaryOutflow out;
  out.mass = t.m;
  out.momentum_x = t.mx;
  out.momentum_y = t.my;
  out.energy = t.ei;
  out.products_mass = t.m1;
  return out;
}

namespace {
GasMaterials one_material(const EquationOfState& eos) {
  GasMaterials m;
  m.air = eos;
  m.products = eos;
  return m;
}
}  // namespace

GasSolver::GasSolver(const GasGrid& grid, const EquationOfState& eos, const GasSolverOptions& options)
    : GasSolver(grid, one_material(eos), options) {}

GasSolver::GasSolver(const GasGrid& grid, const GasMaterials& materials, const GasSolverOptions& options)
    : grid_(grid), materials_(materials), options_(options), a_(std::make_unique<detail::GasArrays>()) {
  if (materials.tracer && materials.two)
    throw InputError("a tracer needs a one-gas run: with detonation products the products are the traced gas");
  if (materials.tracer && options.transport != Transport::conservative)
    throw InputError("a tracer of the blast gas needs gas.transport = \"conservative\" (the paper's transport carries no "
                     "passive scalar)");
  if (materials.two && options.transport != Transport::conservative)
    throw InputError("detonation products beside air need gas.transport = \"conservative\" (the paper's transport "
                     "carries one gas)");
  if (grid.nx < 3 || grid.ny < 3) throw InputError("gas grid needs at least 3 cells along x and y");
  if (!(grid.dx > 0) || !(grid.dy > 0)) throw InputError("gas grid spacing must be positive");
  if (options.boundaries.unpaired_periodic_axis() >= 0)
    throw InputError("a periodic boundary must be set on both opposite sides");
  a_->resize(grid.padded_shape().size(), 2 * static_cast<index_t>(grid.nx + grid.ny), materials.traced());
  if (fuse_kernels() || options.transport != Transport::conservative) {  // only the host-thread momentum transport
    for (auto* dual : {&a_->work.dual_along_momentum, &a_->work.dual_along_kinetic, &a_->work.dual_across_momentum,
                       &a_->work.dual_across_kinetic})
      dual->assign(0, 0.0);
  }
}

GasSolver::~GasSolver() = default;
GasSolver::GasSolver(GasSolver&&) noexcept = default;
GasSolver& GasSolver::operator=(GasSolver&&) noexcept = default;

GasStateView GasSolver::state() { return a_->state.view(grid_.padded_shape()); }
GasStateReadView GasSolver::state() const { return a_->state.read(grid_.padded_shape()); }
MaterialView GasSolver::material_fields() { return a_->materials.view(grid_.padded_shape()); }
MaterialReadView GasSolver::material_fields() const { return a_->materials.read(grid_.padded_shape()); }
GasCells GasSolver::cells() {
  return {state(), material_fields(), materials_.two, materials_.traced(),
          a_->ledgers.view(grid_.padded_shape()).positivity_heat};
}
GasCellsRead GasSolver::cells() const {
  return {state(), material_fields(), materials_.two, materials_.traced(),
          a_->ledgers.read(grid_.padded_shape()).positivity_heat};
}
ImmersedBoundaryView GasSolver::immersed_boundary() { return a_->immersed.view(grid_.padded_shape()); }
ImmersedBoundaryReadView GasSolver::immersed_boundary() const { return a_->immersed.read(grid_.padded_shape()); }
Field2D<double> GasSolver::pressure_with_viscosity() { return a_->work.view(grid_.padded_shape()).pressure; }

void GasSolver::initialise(const std::function<GasPoint(double, double)>& state_at) {
  const PaddedShape sh = grid_.padded_shape();
  std::vector<double> rho(sh.size(), 0.0), e(sh.size(), 0.0), u(sh.size(), 0.0), v(sh.size(), 0.0);
  std::vector<double> alpha(materials_.traced() ? sh.size() : 0, 0.0), m1(alpha.size(), 0.0);
  for (int j = 0; j <= grid_.ny; ++j) {
    for (int i = 0; i <= grid_.nx; ++i) {
      if (i < grid_.nx && j < grid_.ny) {
        const GasPoint c = state_at(grid_.cell_x(i), grid_.cell_y(j));
        rho[sh.offset(i, j)] = c.density;
        e[sh.offset(i, j)] = c.internal_energy;
        if (!(c.products_fraction >= 0.0 && c.products_fraction <= 1.0))
          throw InputError("products volume fraction " + std::to_string(c.products_fraction) + " outside [0, 1]");
        if (c.products_fraction > 0.0 && !materials_.two)
          throw InputError("detonation products in the initial state of a one-material gas (no explosive given)");
        if (!(c.tracer >= 0.0 && c.tracer <= 1.0))
          throw InputError("traced gas mass fraction " + std::to_string(c.tracer) + " outside [0, 1]");
        if (c.tracer > 0.0 && !materials_.tracer)
          throw InputError("a traced gas in the initial state of a run without a tracer");
        if (materials_.two) {
          // Both phases at the cell's density: the cell is all products, all air, or (rarely) a blend.
          alpha[sh.offset(i, j)] = c.products_fraction;
          m1[sh.offset(i, j)] = c.products_fraction * c.density;
        } else if (materials_.tracer) {
          m1[sh.offset(i, j)] = c.tracer * c.density;
        }
      }
      if (j < grid_.ny) u[sh.offset(i, j)] = state_at(grid_.face_x(i), grid_.cell_y(j)).velocity_x;
      if (i < grid_.nx) v[sh.offset(i, j)] = state_at(grid_.cell_x(i), grid_.face_y(j)).velocity_y;
    }
  }
  // Reference state of the outflow faces (OutflowReference order): the initial boundary state.
  const int nx = grid_.nx, ny = grid_.ny;
  auto p_at = [&](int i, int j) {
    const index_t k = sh.offset(i, j);
    return materials_.two ? materials_.pressure(rho[k], e[k], alpha[k], m1[k]) : materials_.air.pressure(rho[k], e[k]);
  };
  std::vector<double> p_ref(2 * static_cast<size_t>(nx + ny)), w_ref(p_ref.size());
  for (int j = 0; j < ny; ++j) {
    p_ref[j] = p_at(0, j);
    w_ref[j] = -u[sh.offset(0, j)];
    p_ref[ny + j] = p_at(nx - 1, j);
    w_ref[ny + j] = u[sh.offset(nx, j)];
  }
  for (int i = 0; i < nx; ++i) {
    p_ref[2 * ny + i] = p_at(i, 0);
    w_ref[2 * ny + i] = -v[sh.offset(i, 0)];
    p_ref[2 * ny + nx + i] = p_at(i, ny - 1);
    w_ref[2 * ny + nx + i] = v[sh.offset(i, ny)];
  }
  copy_from_host(a_->outflow_reference.pressure, p_ref);
  copy_from_host(a_->outflow_reference.velocity, w_ref);
  a_->state.for_each([&](const auto&, auto& v) { v.assign(sh.size(), 0.0); });
  copy_from_host(a_->state.rho.f, rho);
  copy_from_host(a_->state.e.f, e);
  copy_from_host(a_->state.u.f, u);
  copy_from_host(a_->state.v.f, v);
  if (materials_.traced()) {
    copy_from_host(a_->materials.alpha, alpha);
    copy_from_host(a_->materials.m1, m1);
  }
  time_ = 0.0;
  steps_ = 0;
  fill_device("cip.clear_ledgers", a_->outflow_ledger.face, OutflowLedger{0, 0, 0, 0, 0});
  a_->ledgers.for_each([](const char*, DeviceVector<double>& v) { fill_device("cip.clear_ledgers", v, 0.0); });
  apply_boundaries();
  // Derivatives: zero in uniform regions and next to jumps between them (the paper's Table 1), centred
  // differences where the initial data are smooth (zero there would cost CIP its order of accuracy).
  for_each_cell("cip.initial_derivatives", 0, grid_.nx + 1, 0, grid_.ny + 1,
                InitialDerivativesKernel{state(), grid_.dx, grid_.dy});
  apply_boundaries();
}

void GasSolver::apply_boundaries() {
  if (materials_.traced()) fill_material_ghosts(material_fields(), grid_, options_.boundaries);
  fill_ghosts(state(), grid_, boundary_context());
}

BoundaryContext GasSolver::boundary_context() const {
  return {options_.boundaries, materials_, material_fields(), a_->outflow_reference.view()};
}

SignalRate GasSolver::signal_rate_kernel() const {
  return SignalRate{state(), material_fields(), immersed_boundary().cell_active, materials_, grid_.nx, grid_.dx, grid_.dy};
}

double GasSolver::max_signal_rate() const {
  return reduce_max("cip.signal_rate", static_cast<index_t>(grid_.nx) * grid_.ny, 0.0, signal_rate_kernel());
}

bool GasSolver::fuse_kernels() const {
  if (options_.fusion == KernelFusion::backend_default) return kBackendIsGpu;
  return options_.fusion == KernelFusion::fused;
}

StepViews GasSolver::step_views() const {
  const PaddedShape sh = grid_.padded_shape();
  return {a_->state.view(sh), a_->starred.view(sh), a_->immersed.read(sh)};
}

void GasSolver::step(double dt) {
  const GasGrid g = grid_;
  const PaddedShape sh = g.padded_shape();
  const StepViews v = step_views();
  const GasStateView& n = v.now;
  const GasStateView& s = v.starred;
  const auto& active = v.ib.cell_active;
  const auto &u_pres = v.ib.u_prescribed, &v_pres = v.ib.v_prescribed;
  const auto &u_imp = v.ib.u_imposed, &v_imp = v.ib.v_imposed;
  const Field2D<double> P = pressure_with_viscosity();
  const Field2D<const double> Pc{P.data, sh}, rho_n{n.rho.f.data, sh};
  const Field2D<const double> us{s.u.f.data, sh}, vs{s.v.f.data, sh};

  const BoundaryContext ctx = boundary_context();
  // 1. P = p + q (paper eqs. 4-5). The ghosts of the current state are valid: initialise(), the end of
  //    the previous step, or apply_boundaries() after an outside write to state() filled them.
  for_each_cell("cip.pressure", 0, g.nx, 0, g.ny,
                PressureKernel{n, material_fields(), active, P, materials_, options_.viscosity.linear,
                               options_.viscosity.quadratic,
                               options_.pressure_predictor && options_.transport == Transport::conservative ? 0.5 * dt : 0.0,
                               g.dx, g.dy});
  for_each_index("cip.pressure.ghosts", 2 * static_cast<index_t>(g.nx + g.ny),
                 PressureGhostKernel{P, g.nx, g.ny, options_.boundaries});
  // 2. Non-advection phase: face velocities, then density and energy (paper eqs. 1-3).
  const bool fuse = fuse_kernels();
  const IndexBox cells{0, g.nx, 0, g.ny}, x_faces{0, g.nx + 1, 0, g.ny}, y_faces{0, g.nx, 0, g.ny + 1};
  for_each_cell_fused(
      "cip.face_velocity", fuse,
      cell_part("cip.face_velocity.u", x_faces, FaceVelocityKernel{0, n, s.u.f, rho_n, Pc, active, u_pres, u_imp, g, ctx, dt}),
      cell_part("cip.face_velocity.v", y_faces, FaceVelocityKernel{1, n, s.v.f, rho_n, Pc, active, v_pres, v_imp, g, ctx, dt}));
  for_each_cell("cip.cell_nonadvection", 0, g.nx, 0, g.ny,
                CellNonAdvectionKernel{options_.transport == Transport::conservative, n, s.rho.f, s.e.f, us, vs, Pc, active, dt, g.dx, g.dy});
  fill_ghosts(s, g, ctx);
  if (options_.transport == Transport::paper) accumulate_boundary_outflow(dt);
  // 3. Derivative update (Yabe, Xiao & Utsumi 2001).
  for_each_cell_fused("cip.derivatives", fuse,
                      cell_part("cip.derivatives.cell", cells, CellDerivativeKernel{n, s, active, dt, g.dx, g.dy}),
                      cell_part("cip.derivatives.u", x_faces, FaceDerivativeKernel{0, n, s, u_pres, dt, g.dx, g.dy}),
                      cell_part("cip.derivatives.v", y_faces, FaceDerivativeKernel{1, n, s, v_pres, dt, g.dx, g.dy}));
  fill_ghosts(s, g, ctx);
  // 4. Transport. Conservative: values in flux form (conservative_transport.cpp); the paper's: values by
  // CIP. Either way the derivatives are advected by CIP with the updated velocity.
  const bool conservative = options_.transport == Transport::conservative;
  if (conservative) {
    transport_conservatively(dt);
    accumulate_boundary_outflow(dt);
  }
  const Limiter lim = options_.limiter;
  for_each_cell_fused(
      "cip.advection", fuse,
      cell_part("cip.advection.cell", cells, CellAdvectionKernel{s, n, active, dt, g.dx, g.dy, lim, conservative}),
      cell_part("cip.advection.u", x_faces, FaceAdvectionKernel{0, s, n, u_pres, u_imp, dt, g.dx, g.dy, lim, conservative}),
      cell_part("cip.advection.v", y_faces, FaceAdvectionKernel{1, s, n, v_pres, v_imp, dt, g.dx, g.dy, lim, conservative}));
  fill_ghosts(n, g, ctx);
  time_ += dt;
  ++steps_;
}

GasTotals GasSolver::totals(const CellRegion& region) const {
  const TotalsSum t = reduce_sum(
      "cip.totals", static_cast<index_t>(grid_.nx) * grid_.ny, TotalsSum{0, 0, 0, 0, 0, 0},
      TotalsOfCell{state(), material_fields(), materials_.traced(), immersed_boundary().cell_active, grid_.nx,
                   grid_.cell_area(), grid_, region});
  GasTotals out;
  out.mass = t.m;
  out.momentum_x = t.mx;
  out.momentum_y = t.my;
  out.internal_energy = t.ei;
  out.kinetic_energy = t.ek;
  out.products_mass = t.m1;
  return out;
}

std::vector<GasSample> GasSolver::sample(const std::vector<std::array<double, 2>>& points) const {
  if (points.empty()) return {};
  std::vector<double> xy(2 * points.size());
  for (size_t k = 0; k < points.size(); ++k) {
    xy[2 * k] = points[k][0];
    xy[2 * k + 1] = points[k][1];
  }
  detail::GasSamplesArrays samples;
  copy_from_host(samples.xy, xy);
  samples.out.resize(points.size());
  for_each_index("cip.sample", static_cast<index_t>(points.size()),
                 SampleKernel{state(), material_fields(), grid_, materials_, samples.view()});
  return blastsim::to_host(samples.out);
}

double GasSolver::traced_reach(std::array<double, 2> center, double min_fraction, double min_pressure,
                               double max_radius) const {
  if (!materials_.traced()) return 0.0;
  return reduce_max("cip.traced_reach", static_cast<index_t>(grid_.nx) * grid_.ny, 0.0,
                    TracedCellDistance{state(), material_fields(), immersed_boundary().cell_active, materials_, grid_,
                                       center[0], center[1], min_fraction, min_pressure, max_radius});
}

HostGasFields GasSolver::to_host() const {
  const PaddedShape sh = grid_.padded_shape();
  const std::vector<double> rho = blastsim::to_host(a_->state.rho.f), e = blastsim::to_host(a_->state.e.f);
  const std::vector<double> u = blastsim::to_host(a_->state.u.f), v = blastsim::to_host(a_->state.v.f);
  const std::vector<std::uint8_t> active = blastsim::to_host(a_->immersed.cell_active);
  const std::vector<double> alpha = blastsim::to_host(a_->materials.alpha), m1 = blastsim::to_host(a_->materials.m1);
  HostGasFields h;
  h.nx = grid_.nx;
  h.ny = grid_.ny;
  const size_t n = static_cast<size_t>(grid_.nx) * grid_.ny;
  h.rho.resize(n);
  h.e.resize(n);
  h.p.resize(n);
  h.u.resize(n);
  h.v.resize(n);
  h.active.resize(n);
  if (materials_.two) h.alpha.resize(n);
  if (materials_.traced()) h.traced.resize(n);
  for (int j = 0; j < grid_.ny; ++j) {
    for (int i = 0; i < grid_.nx; ++i) {
      const size_t k = static_cast<size_t>(j) * grid_.nx + i;
      h.rho[k] = rho[sh.offset(i, j)];
      h.e[k] = e[sh.offset(i, j)];
      if (materials_.two) {
        const index_t o = sh.offset(i, j);
        h.alpha[k] = alpha[o];
        h.p[k] = materials_.pressure(h.rho[k], h.e[k], alpha[o], m1[o]);
      } else {
        h.p[k] = materials_.air.pressure(h.rho[k], h.e[k]);
      }
      h.u[k] = 0.5 * (u[sh.offset(i, j)] + u[sh.offset(i + 1, j)]);
      h.v[k] = 0.5 * (v[sh.offset(i, j)] + v[sh.offset(i, j + 1)]);
      h.active[k] = active[sh.offset(i, j)];
      if (materials_.traced()) h.traced[k] = m1[sh.offset(i, j)] / h.rho[k];
    }
  }
  return h;
}

std::string GasSolver::describe_invalid_cell() const {
  const PaddedShape sh = grid_.padded_shape();
  const std::vector<double> rho = blastsim::to_host(a_->state.rho.f), e = blastsim::to_host(a_->state.e.f);
  const std::vector<double> u = blastsim::to_host(a_->state.u.f), v = blastsim::to_host(a_->state.v.f);
  const std::vector<std::uint8_t> active = blastsim::to_host(a_->immersed.cell_active);
  const std::vector<double> alpha = blastsim::to_host(a_->materials.alpha), m1 = blastsim::to_host(a_->materials.m1);
  for (int j = 0; j < grid_.ny; ++j) {
    for (int i = 0; i < grid_.nx; ++i) {
      const index_t k = sh.offset(i, j);
      if (!active[k]) continue;
      const char* what = nullptr;
      double value = 0.0;
      if (!(rho[k] > 0.0) || !std::isfinite(rho[k])) what = "density", value = rho[k];
      else if (materials_.two) {
        // Products' internal energy may be negative (it is measured from the JWL reference curve): the
        // pressure and the sound speed must be positive.
        const double p = materials_.pressure(rho[k], e[k], alpha[k], m1[k]);
        if (!(p > 0.0) || !std::isfinite(p)) what = "pressure", value = p;
        else if (!(materials_.sound_speed(rho[k], e[k], alpha[k], m1[k]) > 0.0)) what = "internal energy (no real sound speed)", value = e[k];
      } else if (!(e[k] > 0.0) || !std::isfinite(e[k])) what = "internal energy", value = e[k];
      if (!what && materials_.two && !(alpha[k] >= 0.0 && alpha[k] <= 1.0)) what = "products volume fraction", value = alpha[k];
      else if (!std::isfinite(u[k])) what = "x-velocity", value = u[k];
      else if (!std::isfinite(v[k])) what = "y-velocity", value = v[k];
      if (what) {
        std::ostringstream os;
        os << what << " = " << value << " in cell (" << i << ", " << j << ") at x = " << grid_.cell_x(i)
           << " m, y = " << grid_.cell_y(j) << " m";
        return os.str();
      }
    }
  }
  return "";
}

void mark_static_solid(GasSolver& solver, const std::function<bool(double, double)>& inside) {
  const GasGrid& g = solver.grid();
  const PaddedShape sh = g.padded_shape();
  std::vector<std::uint8_t> active(sh.size(), 1), up(sh.size(), 0), vp(sh.size(), 0);
  for (int j = 0; j <= g.ny; ++j) {
    for (int i = 0; i <= g.nx; ++i) {
      if (j < g.ny && inside(g.face_x(i), g.cell_y(j))) up[sh.offset(i, j)] = 1;
      if (i < g.nx && inside(g.cell_x(i), g.face_y(j))) vp[sh.offset(i, j)] = 1;
    }
  }
  for (int j = 0; j < g.ny; ++j) {
    for (int i = 0; i < g.nx; ++i) {
      const bool all = up[sh.offset(i, j)] && up[sh.offset(i + 1, j)] && vp[sh.offset(i, j)] && vp[sh.offset(i, j + 1)];
      if (all) active[sh.offset(i, j)] = 0;
    }
  }
  ImmersedBoundaryView ib = solver.immersed_boundary();
  copy_from_host(ib.cell_active, active);
  copy_from_host(ib.u_prescribed, up);
  copy_from_host(ib.v_prescribed, vp);
  fill_device("cip.mask.u_imposed", ib.u_imposed, 0.0);
  fill_device("cip.mask.v_imposed", ib.v_imposed, 0.0);
}

namespace {
std::string fmt_shape_mismatch(const std::string& path, int nx, int ny, int gx, int gy) {
  return "checkpoint " + path + ": its grid is " + std::to_string(nx) + " x " + std::to_string(ny) + " cells, this case's " +
         std::to_string(gx) + " x " + std::to_string(gy);
}
}  // namespace

void GasSolver::write_checkpoint(CheckpointWriter& w) const {
  w.value("gas.shape", std::array<int, 2>{grid_.nx, grid_.ny});
  detail::GasArrays::for_each_checkpoint_array(*a_, [&](const std::string& name, const auto& v) { write_array(w, name, v); });
  w.value("gas.time", time_);
  w.value("gas.steps", steps_);
}

double GasSolver::immersed_face_work() const {
  const detail::GasLedgers<Access::read> l = a_->ledgers.read(grid_.padded_shape());
  return grid_.dx * grid_.dy * reduce_sum("cip.solid_work", static_cast<index_t>(a_->ledgers.solid_work_u.size()), 0.0,
                                          PaddedEntries{l.solid_work_u, l.solid_work_v});
}

double GasSolver::positivity_energy() const {
  const detail::GasLedgers<Access::read> l = a_->ledgers.read(grid_.padded_shape());
  return grid_.dx * grid_.dy * reduce_sum("cip.positivity_energy", static_cast<index_t>(a_->ledgers.positivity_heat.size()),
                                          0.0, PaddedEntries{l.positivity_heat, {}});
}

void GasSolver::read_checkpoint(CheckpointReader& r) {
  const std::array<int, 2> shape = r.value<std::array<int, 2>>("gas.shape");
  if (shape[0] != grid_.nx || shape[1] != grid_.ny)
    throw InputError(fmt_shape_mismatch(r.path(), shape[0], shape[1], grid_.nx, grid_.ny));
  // Every array keeps the size the constructor gave it.
  detail::GasArrays::for_each_checkpoint_array(*a_, [&](const std::string& name, auto& v) { read_array(r, name, v, v.size()); });
  time_ = r.value<double>("gas.time");
  steps_ = r.value<long long>("gas.steps");
  if (!std::isfinite(time_) || time_ < 0) r.fail("gas.time", "not a finite time >= 0");
  if (steps_ < 0 || steps_ > kMaxCheckpointSteps) r.fail("gas.steps", "negative or above 1e15");
  // The material fields exist exactly in a run with products or a tracer (an empty record matches a one-gas
  // case without a tracer only).
  const size_t material_size = materials_.traced() ? static_cast<size_t>(grid_.padded_shape().size()) : 0;
  if (a_->materials.alpha.size() != material_size || a_->materials.m1.size() != material_size)
    r.fail("gas.alpha", materials_.traced()
                            ? "empty: a checkpoint of a one-gas run without a tracer, this case has products or a tracer"
                            : "present: a checkpoint of a run with products or a tracer, this case has neither");
  // The masks are flags: anything but 0 and 1 is damage.
  const std::pair<const char*, const DeviceVector<std::uint8_t>*> masks[] = {
      {"gas.cell_active", &a_->immersed.cell_active},
      {"gas.u_prescribed", &a_->immersed.u_prescribed},
      {"gas.v_prescribed", &a_->immersed.v_prescribed}};
  for (const auto& [name, mask] : masks)
    for (const std::uint8_t flag : blastsim::to_host(*mask))
      if (flag > 1) r.fail(name, "holds a flag other than 0 or 1");
}

}  // namespace blastsim::cip
