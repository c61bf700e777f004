//! \file gas_types.hpp
//! \brief Plain option and result types of the gas solver (no backend headers: usable from any host code).
#pragma once

#include "blastsim/core/checkpoint_traits.hpp"
#include "blastsim/cip/boundary.hpp"
#include "blastsim/cip/cip_kernels.hpp"

#include <cstdint>
#include <vector>

namespace blastsim::cip {

//! Coefficients of the artificial viscosity, paper eq. (4). The paper does not give them. The defaults
//! c1 = 0.25, c2 = 0.5 suit the (default) conservative transport with the pressure predictor, which puts shocks
//! in the right place whatever the coefficients: less viscosity smears shocks less (the linear term sets the
//! width of a weak shock), more damps the oscillations behind a slowly moving shock (Toro's test 5) and the
//! start-up error behind Sod's contact. Without the predictor the step amplifies short sound waves and needs
//! c1 = 0.5 to damp them (docs/gas-solver.md "Time centring of the pressure"; docs/performance.md "Where the
//! gas's error lies"). The paper's non-conservative transport needs c1 = 1, c2 = 2: with 0.5 and 1 it runs the
//! shock of the 277:1 jump 2.6 % slow, with 1 and 2 0.75 % (recommended_viscosity()).
struct ArtificialViscosity {
  double linear = 0.25;    //!< c1 [-]
  double quadratic = 0.5;  //!< c2 [-]
};

//! How values are carried by the flow (the advection phase).
enum class Transport {
  conservative,  //!< flux form: mass, momentum and total energy conserved (conservative_transport.cpp); default
  paper,         //!< the paper's non-conservative CIP advection of rho, e, u, v (eqs. 1-3)
};

//! The viscosity coefficients measured to suit each transport (docs/gas-solver.md).
inline ArtificialViscosity recommended_viscosity(Transport t) {
  return t == Transport::paper ? ArtificialViscosity{1.0, 2.0} : ArtificialViscosity{0.25, 0.5};
}

//! The paper's Courant number: dt = 0.1 / (largest signal rate).
inline constexpr double kPaperCourant = 0.1;
//! The Courant number measured to keep every gas and coupled check with the conservative transport
//! (docs/performance.md, "The Courant number").
inline constexpr double kConservativeCourant = 0.4;
//! The default Courant number of each transport: the paper's transport keeps the mass of a closed box to its
//! bound (G3) at the paper's number only (docs/performance.md).
inline double recommended_courant(Transport t) { return t == Transport::paper ? kPaperCourant : kConservativeCourant; }

//! GasSolverOptions::fusion.
enum class KernelFusion {
  backend_default,  //!< fused on a GPU (fewer launches, shared arrays read once), separate on host threads
                    //!< (faster there: fewer arrays streamed at once; docs/performance.md)
  fused,
  separate
};

struct GasSolverOptions {
  BoundaryConditions boundaries;
  ArtificialViscosity viscosity;
  Limiter limiter = Limiter::minmax;
  Transport transport = Transport::conservative;
  //! How a step launches its groups of independent kernels (face velocities, mass fluxes, momentum, derivative
  //! update, advection): as one kernel a group (for_each_cell_fused()) or one by one. The bytes are the same
  //! either way (tests/cip/test_fused_step.cpp, G12); only the speed differs.
  KernelFusion fusion = KernelFusion::backend_default;
  //! Conservative transport only: the pressure of the non-advection phase (momentum and work) carries the term
  //! -(dt/2) Gamma p div(u^n) that cancels the lag of the work done with the old velocities, so sound is neither
  //! amplified nor damped by the time stepping (docs/gas-solver.md "Time centring of the pressure"). false: the
  //! step of earlier builds (CHANGELOG.md), which amplifies short sound waves unless the linear viscosity damps
  //! them (c1 = 0.5 did).
  bool pressure_predictor = true;
};

//! Primitive state at a point, used to initialise the grid.
struct GasPoint {
  double density;          //!< [kg/m3]
  double internal_energy;  //!< [J/kg]
  double velocity_x;       //!< [m/s]
  double velocity_y;       //!< [m/s]
  double products_fraction = 0.0;  //!< volume fraction of detonation products [-] (two-material runs)
  double tracer = 0.0;             //!< mass fraction of the traced gas [-] (one-gas runs with a tracer)
};

//! Interpolated state at a sample point (bilinear from the staggered arrays).
struct GasSample {
  double x, y;  //!< [m]
  double rho;   //!< [kg/m3]
  double u, v;  //!< [m/s]
  double p;     //!< [Pa]
  double e;     //!< [J/kg]
  double alpha = 0;  //!< volume fraction of detonation products [-]
  double traced = 0; //!< mass fraction of the traced gas [-]: the products', or the tracer's (0 without either)
};

//! Integrals over the active cells (per unit depth of the 2-D domain). Momentum and kinetic energy are
//! those of the staggered face velocities with the masses of their dual cells (half of each face's share
//! to each of its two cells), the quantities the conservative transport conserves.
struct GasTotals {
  double mass = 0;             //!< [kg/m]
  double momentum_x = 0;       //!< [kg/s]
  double momentum_y = 0;       //!< [kg/s]
  double internal_energy = 0;  //!< [J/m]
  double kinetic_energy = 0;   //!< [J/m], of the face velocities with their dual-cell masses
  double products_mass = 0;    //!< [kg/m] of the traced gas: detonation products, or the tracer's gas
  double total_energy() const { return internal_energy + kinetic_energy; }
};
}  // namespace blastsim::cip
BLASTSIM_CHECKPOINT_REALS(blastsim::cip::GasTotals)
namespace blastsim::cip {

//! A region of the grid selected by cell centre, for totals over part of the domain: a circle, an
//! axis-aligned box, or everything [m].
struct CellRegion {
  enum class Shape : int { all, circle, box } shape = Shape::all;
  double x0 = 0, y0 = 0;  //!< circle centre, or box lower-left corner [m]
  double x1 = 0, y1 = 0;  //!< box upper-right corner [m]
  double radius = 0;      //!< circle radius [m]
  static CellRegion circle(double cx, double cy, double r) { return {Shape::circle, cx, cy, 0, 0, r}; }
  static CellRegion box(double xa, double ya, double xb, double yb) { return {Shape::box, xa, ya, xb, yb, 0}; }
  BLAST_HD bool contains(double x, double y) const {
    if (shape == Shape::circle) return (x - x0) * (x - x0) + (y - y0) * (y - y0) <= radius * radius;
    if (shape == Shape::box) return x >= x0 && x <= x1 && y >= y0 && y <= y1;
    return true;
  }
};

//! What has left the domain through its outer boundary since initialise(), per unit depth (negative:
//! entered). Mass, momentum and energy carried by the flow plus the pressure force and work at the
//! boundary faces; with the totals it closes the balance of the whole domain (the per-step monitor).
struct BoundaryOutflow {
  double mass = 0;        //!< [kg/m]
  double momentum_x = 0;  //!< [kg/s] including the pressure impulse on the boundary
  double momentum_y = 0;  //!< [kg/s]
  double energy = 0;      //!< [J/m] internal + kinetic energy carried out, plus pressure work
  double products_mass = 0;  //!< [kg/m] of detonation products carried out
};
//! What one boundary face let out since initialise() (the solver's outflow ledger, one record a face, summed
//! into a BoundaryOutflow when asked), per unit depth.
struct OutflowLedger {
  double mass;           //!< [kg/m]
  double momentum_x;     //!< [kg/s]
  double momentum_y;     //!< [kg/s]
  double energy;         //!< [J/m]
  double products_mass;  //!< [kg/m]
};
}  // namespace blastsim::cip
BLASTSIM_CHECKPOINT_REALS(blastsim::cip::OutflowLedger)
namespace blastsim::cip {

//! Cell-centred copy of the state on the host (i fastest), for output.
struct HostGasFields {
  int nx = 0, ny = 0;
  std::vector<double> rho, u, v, p, e;
  std::vector<double> alpha;  //!< products volume fraction (empty in a one-material run)
  std::vector<double> traced; //!< mass fraction of the traced gas (products or tracer; empty without either)
  std::vector<std::uint8_t> active;  //!< 1 where the cell is advanced, 0 where inactive (immersed solid)
};

}  // namespace blastsim::cip
