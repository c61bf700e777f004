//! \file crack_gas_kernels.hpp
//! \brief Gas in cracks narrower than a grid cell (docs/coupling.md "Gas in the cracks"): the physics of one
//! channel segment (states, the HLLC flux, the choked nozzle of a crack mouth, wall friction) and the kernels
//! of the 1-D finite-volume Euler solver on the crack graph. Plain header: no backend dependency; tests call
//! the functions directly.
//!
//! Every broken joint is one finite volume of a quasi-1-D channel: length L [m], aperture w [m] (flow width per
//! unit thickness), volume V = L w [m2 per m of thickness]. Its two ends meet other segments at mesh vertices
//! (junctions). Conserved per segment (per unit thickness): mass m [kg/m], axial momentum q = m u [kg/s]
//! (u along the axis from end 0 to end 1), total energy E [J/m], products mass m1 [kg/m] and the
//! volume-fraction-weighted mass am = alpha m [kg/m] (two-material runs).
#pragma once

#include "blastsim/core/checkpoint_traits.hpp"
#include "blastsim/cip/cip_kernels.hpp"
#include "blastsim/cip/eos.hpp"
#include "blastsim/core/access.hpp"
#include "blastsim/core/field2d.hpp"
#include "blastsim/core/macros.hpp"
#include "blastsim/ibm/coupling_options.hpp"

#include <cmath>
#include <cstdint>

namespace blastsim::ibm {

//! Most segments that may meet at one junction (the mesh's largest vertex degree is checked against it).
inline constexpr int kCrackMaxDegree = 16;

//! Segment states: not a crack (intact joint), a crack holding its own gas, or a crack so wide that the grid
//! carries its gas (docs/coupling.md, "Hand-over").
enum CrackSegmentKind : std::uint8_t { kSegmentNone = 0, kSegmentGas = 1, kSegmentGrid = 2 };

//! Conserved variables of one segment, per unit thickness.
struct ChannelConserved {
  double m;   //!< mass [kg/m]
  double q;   //!< axial momentum [kg/s]
  double E;   //!< total energy [J/m]
  double m1;  //!< products mass [kg/m]
  double am;  //!< alpha x mass [kg/m]
};
}  // namespace blastsim::ibm
BLASTSIM_CHECKPOINT_REALS(blastsim::ibm::ChannelConserved)
namespace blastsim::ibm {

//! Primitive state at a point of a channel; u along the frame's axis.
struct ChannelPrimitive {
  double rho;    //!< [kg/m3]
  double u;      //!< [m/s]
  double p;      //!< [Pa]
  double c;      //!< sound speed [m/s]
  double Y;      //!< products mass fraction [-]
  double alpha;  //!< products volume fraction [-]
  double Edens;  //!< total energy per volume [J/m3]
};

//! Rates through one channel cross-section of unit flux area, positive from the left state to the right
//! state: mass [kg/(m2 s)], momentum [Pa], energy [W/m2], products mass and alpha x mass [kg/(m2 s)].
struct ChannelFlux {
  double m, q, E, m1, am;
};

//! A state marked empty: channel_state() gives a density at or below the vacuum density 0.
BLAST_HD inline bool is_vacuum(const ChannelPrimitive& s) { return !(s.rho > 0.0); }

//! Primitive state from density, velocity, specific internal energy and the products fractions; vacuum (density
//! 0) at or below `vacuum_density` [kg/m3] (CrackGas::vacuum_density()).
BLAST_HD inline ChannelPrimitive channel_state(const cip::GasMaterials& mat, double rho, double u, double e, double Y,
                                               double alpha, double vacuum_density) {
  ChannelPrimitive s{rho, u, 0.0, 0.0, Y, alpha, 0.0};
  if (!(rho > vacuum_density)) return {0.0, 0.0, 0.0, 0.0, Y, alpha, 0.0};
  s.p = mat.pressure(rho, e, alpha, Y * rho);
  s.c = mat.sound_speed(rho, e, alpha, Y * rho);
  s.Edens = rho * e + 0.5 * rho * u * u;
  return s;
}

//! Primitive state of a segment from its conserved variables and volume V [m2 per m]; vacuum at or below
//! `vacuum_density` [kg/m3].
BLAST_HD inline ChannelPrimitive segment_state(const cip::GasMaterials& mat, const ChannelConserved& c, double V,
                                               double vacuum_density) {
  if (!(c.m > vacuum_density * V) || !(c.m > 0.0)) return {0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0};
  const double rho = c.m / V, u = c.q / c.m, e = c.E / c.m - 0.5 * u * u;
  return channel_state(mat, rho, u, e, c.m1 / c.m, c.am / c.m, vacuum_density);
}

//! The same state seen in a frame whose axis is reversed.
BLAST_HD inline ChannelPrimitive reversed(ChannelPrimitive s) {
  s.u = -s.u;
  return s;
}

//! Exact physical flux of a state.
BLAST_HD inline ChannelFlux physical_flux(const ChannelPrimitive& s) {
  const double mf = s.rho * s.u;
  return {mf, mf * s.u + s.p, (s.Edens + s.p) * s.u, mf * s.Y, mf * s.alpha};
}

//! HLLC flux (Toro, Spruce & Speares 1994, Shock Waves 4:25; Toro 2009, "Riemann Solvers and Numerical Methods
//! for Fluid Dynamics", 3rd ed., sec. 10.4, eqs. 10.37-10.39 with the speed estimates of eq. 10.48) between a
//! left and a right state, for any equation of state (the star states need only rho, u, p and E). Against a
//! vacuum it is the HLL flux with the vacuum front speed u + 2 c / Gamma (Toro 2009, sec. 4.6).
BLAST_HD inline ChannelFlux hllc_flux(const cip::GasMaterials& mat, const ChannelPrimitive& L, const ChannelPrimitive& R) {
  const bool vl = is_vacuum(L), vr = is_vacuum(R);
  if (vl && vr) return {0, 0, 0, 0, 0};
  if (vl || vr) {
    const ChannelPrimitive& g = vl ? R : L;
    const double front = 2.0 * g.c / mat.mixture_gruneisen(g.alpha);
    const double SL = vl ? g.u - front : g.u - g.c, SR = vl ? g.u + g.c : g.u + front;
    const ChannelFlux F = physical_flux(g);
    if (vr ? SL >= 0 : SR <= 0) return F;
    if (vr ? SR <= 0 : SL >= 0) return {0, 0, 0, 0, 0};
    // HLL with the vacuum side's U = F = 0.
    const double s = vr ? SR : -SL, k = 1.0 / (SR - SL);
    const ChannelFlux U = {g.rho, g.rho * g.u, g.Edens, g.rho * g.Y, g.rho * g.alpha};
    const double w = vr ? -SL * SR : SL * SR;  // the U term's sign: F* = (SR FL - SL FR + SL SR (UR - UL)) / (SR - SL)
    return {(s * F.m + w * U.m) * k, (s * F.q + w * U.q) * k, (s * F.E + w * U.E) * k, (s * F.m1 + w * U.m1) * k,
            (s * F.am + w * U.am) * k};
  }
  const double SL = fmin(L.u - L.c, R.u - R.c), SR = fmax(L.u + L.c, R.u + R.c);
  if (SL >= 0) return physical_flux(L);
  if (SR <= 0) return physical_flux(R);
  const double dl = L.rho * (SL - L.u), dr = R.rho * (SR - R.u);
  const double SM = (R.p - L.p + L.u * dl - R.u * dr) / (dl - dr);
  const ChannelPrimitive& K = SM >= 0 ? L : R;
  const double S = SM >= 0 ? SL : SR, d = SM >= 0 ? dl : dr;
  const double f = d / (S - SM);  // rho*_K
  const ChannelFlux F = physical_flux(K);
  const double Estar = f * (K.Edens / K.rho + (SM - K.u) * (SM + K.p / d));
  return {F.m + S * (f - K.rho), F.q + S * (f * SM - K.rho * K.u), F.E + S * (Estar - K.Edens),
          F.m1 + S * (f * K.Y - K.rho * K.Y), F.am + S * (f * K.alpha - K.rho * K.alpha)};
}

//! Pressure on a closed channel end [Pa]: the momentum flux of the HLLC solution between the state arriving
//! at the wall (u towards it) and its mirror image; mass and energy do not cross.
BLAST_HD inline double wall_pressure(const cip::GasMaterials& mat, const ChannelPrimitive& s) {
  if (is_vacuum(s)) return 0.0;
  return hllc_flux(mat, s, reversed(s)).q;
}

//! Steady isentropic nozzle from a reservoir at rest (density rho0 [kg/m3], pressure p0 [Pa], isentropic
//! exponent k = rho0 c0^2 / p0) into a back pressure pb [Pa]: mass flux G [kg/(m2 s)], exit pressure and
//! velocity. The flow chokes (M = 1) when pb < p0 (2 / (k + 1))^(k / (k - 1)): G then stays at its maximum
//! (e.g. Anderson 2003, "Modern Compressible Flow", 3rd ed., eqs. 5.20-5.21). Exact for an ideal gas; for
//! JWL products and mixtures k is the local exponent at the reservoir (the expansion through a mouth is
//! short).
struct NozzleFlow {
  double G, p, u;
};
BLAST_HD inline NozzleFlow nozzle_flow(double rho0, double p0, double k, double pb) {
  if (!(rho0 > 0.0) || !(p0 > pb)) return {0.0, p0, 0.0};
  const double r_choke = pow(2.0 / (k + 1.0), k / (k - 1.0));
  const double r = fmax(pb / p0, r_choke);
  const double rho = rho0 * pow(r, 1.0 / k);
  const double u = sqrt(fmax(0.0, 2.0 * k / (k - 1.0) * p0 / rho0 * (1.0 - pow(r, (k - 1.0) / k))));
  return {rho * u, r * p0, u};
}

//! Darcy friction factors of a rough channel of relative roughness r = k / D_h (asperity height k over the
//! hydraulic diameter D_h = 2 w), after Louis (1969, "A study of groundwater flow in jointed rock and its
//! influence on the stability of rock masses", Imperial College Rock Mech. Res. Rep. 10; the laws are
//! reproduced in Hoek & Bray 1981, "Rock Slope Engineering", 3rd ed., ch. 6): fully rough turbulent flow
//! 1 / sqrt(f) = 2 log10(3.7 / r) for r <= 0.033 (Nikuradse's law, the rough end of Moody's chart) and
//! 1 / sqrt(f) = 2 log10(1.9 / r) above (Louis's joints of high relative roughness); laminar flow f = 96 / Re,
//! times 1 + 8.8 r^1.5 above r = 0.033. r is capped at 1 (Louis's data end near 0.5; beyond 1.9 his law has no
//! value).
struct RoughChannelFriction {
  double turbulent;       //!< fully rough Darcy factor [-]
  double laminar_factor;  //!< multiplier of the smooth laminar 96 / Re [-]
};
BLAST_HD inline RoughChannelFriction louis_friction(double r) {
  r = r > 1.0 ? 1.0 : r;
  if (!(r > 0.0)) return {0.0, 1.0};
  const bool high = r > 0.033;
  const double l = 2.0 * log10((high ? 1.9 : 3.7) / r);
  return {1.0 / (l * l), high ? 1.0 + 8.8 * r * sqrt(r) : 1.0};
}


//! The rough-wall factors of a channel of aperture w [m]: flow.friction_factor when >= 0, else
//! louis_friction(k / (2 w)): a crack's walls are rougher the narrower it is.
BLAST_HD inline RoughChannelFriction wall_friction(double w, const ChannelFlowParams& flow) {
  return flow.friction_factor >= 0.0 ? RoughChannelFriction{flow.friction_factor, 1.0}
                                     : louis_friction(0.5 * flow.roughness / w);
}

//! Friction rate [1/s] of a channel of aperture w [m]: dq/dt = -rate q, from the Darcy-Weisbach wall shear
//! tau = f rho u |u| / 8 on both walls (hydraulic diameter 2 w): rate = f |u| / (4 w), with f the larger of the
//! rough-wall factor (wall_friction()) and the laminar one, 96 / Re (Re = rho |u| 2 w / mu; parallel plates)
//! times Louis's roughness factor, so a slow flow follows the cubic law (mean velocity w^2 / (12 mu) times the
//! pressure gradient, reduced by the roughness).
BLAST_HD inline double friction_rate(double rho, double u, double w, const ChannelFlowParams& flow) {
  const RoughChannelFriction f = wall_friction(w, flow);
  const double turbulent = f.turbulent * fabs(u) / (4.0 * w);
  if (!(rho > 0.0)) return turbulent;
  return fmax(turbulent, f.laminar_factor * 12.0 * flow.viscosity / (rho * w * w));
}

//! The flux between two gas segments, or between a mouth's reservoir and the first segment, where the walls'
//! friction acts (JunctionFluxKernel). Where the friction rate sigma [1/s] is large the momentum equation relaxes
//! to the balance of the pressure gradient and the wall shear (rho sigma u = -dp/dx) and the flow becomes a
//! nonlinear diffusion: the friction-dominated flow of docs/coupling.md "Front in a rigid crack". An upwind
//! Riemann flux keeps its dissipation lambda (U_R - U_L) / 2 there, a diffusion lambda d / 2 against the flow's
//! own c^2 / (n sigma): at the resolutions of a blast's cracks it carries gas ahead of a front at the sound
//! speed, and the front runs ahead (the diffusion limit of hyperbolic relaxation: Jin & Levermore 1996,
//! J. Comput. Phys. 126:449; Gosse & Toscani 2002, C. R. Math. Acad. Sci. Paris 334:337). So the flux is
//! alpha F_Riemann + (1 - alpha) F_D, F_D the two-point flux of the relaxed momentum equation: the donor's gas
//! (the face state on the side of higher pressure) at the velocity u_D that balances the pressure difference
//! between the two centres over their distance d against the wall shear, u_D rate(u_D) = |p_L - p_R| /
//! (rho_d d) for friction_rate() (the smaller of the laminar cubic-law and the fully rough velocities), capped
//! at the donor's sound speed (a friction flow cannot pass the choked limit). The weight alpha is the largest of
//! - 1 / (1 + Pi), Pi = sigma d / u_D: the wall shear against the flow's inertia across the distance d (for fully
//!   rough walls f d / (4 w)); the Riemann flux carries the inertia, the Darcy flux neglects it;
//! - the least weight that keeps the explicit step stable: F_D is a diffusion of coefficient c^2 / (n sigma)
//!   (n = 1 laminar, u_D ~ dp/dx; n = 2 fully rough, u_D ~ sqrt(dp/dx)), nu = c^2 dt / (n sigma d^2), and
//!   alpha C + 2 (1 - alpha) nu <= 1 (C = lambda dt / d): 0 while 2 nu <= 1, else (2 nu - 1) / (2 nu - C);
//! - the weight that keeps the Darcy flux's own Courant number (1 - alpha) u_D dt / d at most 1/2.
//! Without friction alpha = 1 (the Riemann flux alone). c, lambda: the larger of the two centres'.
struct FrictionWeightedFlux {
  ChannelFlux darcy;  //!< F_D per unit flux area, positive from left to right
  double alpha;       //!< the Riemann flux's weight [-]
};
BLAST_HD inline FrictionWeightedFlux friction_weighted_flux(const ChannelPrimitive& L, const ChannelPrimitive& R,
                                                            const ChannelPrimitive& face_L,
                                                            const ChannelPrimitive& face_R, double d, double w,
                                                            double dt, const ChannelFlowParams& flow) {
  const FrictionWeightedFlux riemann{{0, 0, 0, 0, 0}, 1.0};
  const double dp = L.p - R.p;
  const ChannelPrimitive& D = dp >= 0.0 ? face_L : face_R;  // the donor
  if (is_vacuum(D) || dp == 0.0 || !(d > 0.0)) return riemann;
  const double grad = fabs(dp) / d;  // [Pa/m]
  const RoughChannelFriction f = wall_friction(w, flow);
  const double none = 1e300;
  const double u_lam = flow.viscosity > 0.0 ? grad * w * w / (12.0 * flow.viscosity * f.laminar_factor) : none;
  const double u_turb = f.turbulent > 0.0 ? sqrt(4.0 * w * grad / (f.turbulent * D.rho)) : none;
  const double u = fmin(u_lam, u_turb);
  if (!(u < none)) return riemann;  // no friction
  const double sigma = grad / (D.rho * u), n = u_lam <= u_turb ? 1.0 : 2.0;
  const double c = fmax(is_vacuum(L) ? 0.0 : L.c, is_vacuum(R) ? 0.0 : R.c);
  const double lambda = fmax(is_vacuum(L) ? 0.0 : fabs(L.u) + L.c, is_vacuum(R) ? 0.0 : fabs(R.u) + R.c);
  const double nu = c * c * dt / (n * sigma * d * d), C = lambda * dt / d;
  const double a_stab = 2.0 * nu <= 1.0 ? 0.0 : fmin(1.0, (2.0 * nu - 1.0) / fmax(2.0 * nu - C, 1e-300));
  const double a_inertia = 1.0 / (1.0 + sigma * d / u);
  const double ud = fmin(u, D.c);  // [m/s] the Darcy velocity, at most the sound speed
  const double a_courant = 1.0 - 0.5 * d / (ud * dt);
  const double alpha = fmin(1.0, fmax(a_stab, fmax(a_inertia, a_courant)));
  const double sign = dp >= 0.0 ? 1.0 : -1.0, G = sign * D.rho * ud;  // [kg/(m2 s)] from left to right
  const double h = (D.Edens + D.p) / D.rho;                            // the donor's total enthalpy [J/kg]
  return {{G, G * sign * ud + 0.5 * (face_L.p + face_R.p), G * h, G * D.Y, G * D.alpha}, alpha};
}

//! Nusselt number Nu = h D_h / k of fully developed laminar flow between parallel plates at one uniform
//! temperature (Shah & London 1978, "Laminar Flow Forced Convection in Ducts", Academic Press; D_h = 2 w).
inline constexpr double kParallelPlateNusselt = 7.541;

//! Heat exchange rate [1/s] of a channel's gas with its walls: d(e - e_w)/dt = -rate (e - e_w) for the specific
//! internal energy e and its value e_w at the walls' temperature, from a wall heat flux q = h (T - T_w) on both
//! walls (per unit length 2 q against the gas's rho w c_v (T - T_w)): rate = 2 h / (rho w c_v). h is the larger
//! of the turbulent one of the Chilton-Colburn analogy, St = h / (rho c_p |u|) = (f / 8) Pr^(-2/3) with the
//! rough-wall factor f of the friction (Chilton & Colburn 1934, Ind. Eng. Chem. 26:1183; Incropera & DeWitt,
//! "Fundamentals of Heat and Mass Transfer", ch. 8, with the Darcy factor), rate = gamma Pr^(-2/3) f |u| / (4 w),
//! and the laminar one, Nu = 7.541 (kParallelPlateNusselt), k = mu c_p / Pr: rate = Nu gamma mu / (Pr rho w^2).
//! gamma = c_p / c_v = 1 + Gamma, the mixture's Gruneisen coefficient.
BLAST_HD inline double wall_heat_rate(double rho, double u, double w, double gamma, const ChannelFlowParams& flow) {
  const double turbulent = gamma * flow.colburn * wall_friction(w, flow).turbulent * fabs(u) / (4.0 * w);
  if (!(rho > 0.0)) return turbulent;
  return fmax(turbulent, kParallelPlateNusselt * gamma * flow.viscosity / (flow.prandtl * rho * w * w));
}

//! A state from density, velocity, pressure and the products fractions (the MUSCL-Hancock face values).
BLAST_HD inline ChannelPrimitive channel_state_rup(const cip::GasMaterials& mat, double rho, double u, double p, double Y,
                                                   double alpha, double vacuum_density) {
  const double rho_e = mat.internal_energy_density(rho, p, alpha, Y);
  return channel_state(mat, rho, u, rho_e / rho, Y, alpha, vacuum_density);
}

// ---- the crack graph and its kernels (CrackGas runs them; docs/coupling.md "Gas in the cracks") ----------

//! The network's arrays (CrackGas holds them, crack_gas.cpp), as field lists X(element type, name, comment)
//! from which the views below and the storage come (core/access.hpp, core/device_groups.hpp). The graph:
//! segment s has ends 2 s (end 0) and 2 s + 1 (end 1) at junctions segment_junction[2 s + e]; junction J lists
//! its ends in junction_entry[junction_offset[J] .. junction_offset[J + 1]) (ascending).
#define BLASTSIM_CRACK_GRAPH(X)                                                   \
  X(int, segment_junction, "per end: its junction")                              \
  X(int, junction_offset, "per junction (+1): start of its entries")             \
  X(int, junction_entry, "the ends at each junction, ascending")
//! Per segment, set from the rock every step (or by CrackGas::set_geometry()).
#define BLASTSIM_CRACK_GEOMETRY(X)                                                        \
  X(double, length, "length L [m]")                                                        \
  X(double, aperture, "aperture w [m]")                                                    \
  X(double, axis_x, "x component of the unit vector from end 0 to end 1 (0 0: a network without places)") \
  X(double, axis_y, "its y component")
//! Per segment: what evolves.
#define BLASTSIM_CRACK_SEGMENTS(X)                                                     \
  X(std::uint8_t, kind, "CrackSegmentKind")                                            \
  X(ChannelConserved, cons, "its gas, per unit thickness")                             \
  X(double, volume, "the volume [m2 per m] cons refers to")                            \
  X(ChannelPrimitive, prim, "state of the last primitive pass")                       \
  X(double, wall_heat, "heat [J/m] its gas gave the walls since the start (< 0: took)")
//! Per end (2 a segment), the step's work arrays: the states at the ends, then the fluxes through them.
#define BLASTSIM_CRACK_END_STATES(X) X(ChannelPrimitive, face, "the MUSCL-Hancock state at the end, segment frame")
#define BLASTSIM_CRACK_END_FLUXES(X)                                                   \
  X(ChannelFlux, out, "outflow rates x flux area [per m of thickness]")               \
  X(double, end_area, "total flux area [m]")
//! Per junction, set by the coupling every step (or by CrackGas::set_reservoirs()): the mouths.
#define BLASTSIM_CRACK_MOUTHS(X)                                                       \
  X(std::uint8_t, open, "1: opens into a gas reservoir (a grid cell)")                 \
  X(ChannelPrimitive, reservoir, "the reservoir's state (at rest)")                    \
  X(double, reservoir_mass, "the gas [kg/m] the reservoir holds (infinity: unlimited)")
//! Per junction: what went into its reservoir since the last clear (mass, energy, products; the part of it drawn
//! from it; the momentum of the gas that left the cracks, along each end's axis out of its segment).
#define BLASTSIM_CRACK_DEPOSITS(X)                                                                          \
  X(ChannelConserved, deposit, "net m, E, m1, am [per m of thickness] (q unused)")                          \
  X(ChannelConserved, drawn, "what the cracks drew from the reservoir (<= 0; part of deposit; q unused)")    \
  X(double, momentum_x, "x momentum [kg/s] of the gas that left the cracks into the reservoir")             \
  X(double, momentum_y, "y momentum [kg/s] of the gas that left the cracks into the reservoir")

BLASTSIM_CONST_GROUP(CrackGraph, BLASTSIM_CRACK_GRAPH)
BLASTSIM_VIEW_GROUP(CrackGeometry, BLASTSIM_CRACK_GEOMETRY)
BLASTSIM_VIEW_GROUP(CrackSegments, BLASTSIM_CRACK_SEGMENTS)
BLASTSIM_VIEW_GROUP(CrackEndStates, BLASTSIM_CRACK_END_STATES)
BLASTSIM_VIEW_GROUP(CrackEndFluxes, BLASTSIM_CRACK_END_FLUXES)
BLASTSIM_VIEW_GROUP(CrackMouths, BLASTSIM_CRACK_MOUTHS)
BLASTSIM_VIEW_GROUP(CrackDeposits, BLASTSIM_CRACK_DEPOSITS)

//! Primitive state of every segment that holds gas.
struct SegmentPrimitiveKernel {
  cip::GasMaterials mat;
  CrackSegments<Access::read_write> seg;  //!< writes prim
  double vacuum_density;                  //!< [kg/m3] (CrackGas::vacuum_density())
  BLAST_HD void operator()(index_t si) const {
    const int s = static_cast<int>(si);
    seg.prim[s] = seg.kind[s] == kSegmentGas ? segment_state(mat, seg.cons[s], seg.volume[s], vacuum_density)
                                             : ChannelPrimitive{0, 0, 0, 0, 0, 0, 0};
  }
};

//! The one segment across end e of segment s when their junction joins exactly two gas segments and is no
//! mouth (a straight-through chain); -1 otherwise. `other_end` receives the neighbour's end at the junction.
BLAST_HD inline int chain_neighbour(const CrackGraph& g, const CrackMouths<Access::read>& mouths,
                                    const CrackSegments<Access::read>& seg, int s, int e, int& other_end) {
  const int J = g.segment_junction[2 * s + e];
  if (mouths.open[J]) return -1;
  int found = -1, count = 0;
  for (int k = g.junction_offset[J]; k < g.junction_offset[J + 1]; ++k) {
    const int entry = g.junction_entry[k], o = entry / 2;
    if (o == s || seg.kind[o] != kSegmentGas) continue;
    ++count;
    found = entry;
  }
  if (count != 1) return -1;
  other_end = found % 2;
  return found / 2;
}

//! States at the two ends of every gas segment after half a step (MUSCL-Hancock: Toro 2009, sec. 14.4, with
//! van Leer's (1977, J. Comput. Phys. 23:276) monotonized central slopes of rho, u, p, Y, alpha between chain
//! neighbours, cip::mc_slope(); first order where a segment has no neighbour on one side or a reconstructed value
//! is not positive).
struct FaceStateKernel {
  cip::GasMaterials mat;
  CrackGraph g;
  CrackGeometry<Access::read> geo;
  CrackSegments<Access::read> seg;
  CrackMouths<Access::read> mouths;
  CrackEndStates<Access::read_write> ends;
  bool second_order;
  double vacuum_density;  //!< [kg/m3] a reconstructed face state at or below it: first order
  double dt;
  BLAST_HD void operator()(index_t si) const {
    const int s = static_cast<int>(si);
    if (seg.kind[s] != kSegmentGas) return;
    const ChannelPrimitive P = seg.prim[s];
    ends.face[2 * s] = P, ends.face[2 * s + 1] = P;
    if (!second_order || is_vacuum(P)) return;
    int eo0 = 0, eo1 = 0;
    const int o0 = chain_neighbour(g, mouths, seg, s, 0, eo0), o1 = chain_neighbour(g, mouths, seg, s, 1, eo1);
    if (o0 < 0 || o1 < 0) return;
    const ChannelPrimitive Q0 = seg.prim[o0], Q1 = seg.prim[o1];
    if (is_vacuum(Q0) || is_vacuum(Q1)) return;
    const double L = geo.length[s];
    const double d0 = 0.5 * (L + geo.length[o0]), d1 = 0.5 * (L + geo.length[o1]);
    // Neighbour velocities in this segment's frame: reversed when the two axes meet head to head or tail to tail.
    const double u0 = eo0 == 0 ? -Q0.u : Q0.u, u1 = eo1 == 1 ? -Q1.u : Q1.u;
    const double rx = cip::mc_slope((P.rho - Q0.rho) / d0, (Q1.rho - P.rho) / d1);
    const double ux = cip::mc_slope((P.u - u0) / d0, (u1 - P.u) / d1);
    const double px = cip::mc_slope((P.p - Q0.p) / d0, (Q1.p - P.p) / d1);
    const double Yx = cip::mc_slope((P.Y - Q0.Y) / d0, (Q1.Y - P.Y) / d1);
    const double ax = cip::mc_slope((P.alpha - Q0.alpha) / d0, (Q1.alpha - P.alpha) / d1);
    // Half-step time derivatives of the primitive equations.
    const double h = 0.5 * dt;
    const double rt = -(P.u * rx + P.rho * ux), ut = -(P.u * ux + px / P.rho), pt = -(P.u * px + P.rho * P.c * P.c * ux);
    const double Yt = -P.u * Yx, at = -P.u * ax;
    const double r0 = P.rho - 0.5 * L * rx + h * rt, r1 = P.rho + 0.5 * L * rx + h * rt;
    const double p0 = P.p - 0.5 * L * px + h * pt, p1 = P.p + 0.5 * L * px + h * pt;
    if (!(r0 > vacuum_density && r1 > vacuum_density && p0 > 0 && p1 > 0)) return;
    ends.face[2 * s] = channel_state_rup(mat, r0, P.u - 0.5 * L * ux + h * ut, p0, P.Y - 0.5 * L * Yx + h * Yt,
                                         P.alpha - 0.5 * L * ax + h * at, vacuum_density);
    ends.face[2 * s + 1] = channel_state_rup(mat, r1, P.u + 0.5 * L * ux + h * ut, p1, P.Y + 0.5 * L * Yx + h * Yt,
                                             P.alpha + 0.5 * L * ax + h * at, vacuum_density);
  }
};

//! Scales a flux by a flux area [m].
BLAST_HD inline ChannelFlux scaled(const ChannelFlux& f, double a) { return {f.m * a, f.q * a, f.E * a, f.m1 * a, f.am * a}; }

//! The ends' outflows at every junction (one thread per junction: each end belongs to one junction, so no two
//! threads write the same entry). Momentum is in each segment's outward direction at that end.
//! - a mouth: every end exchanges with the reservoir through a steady nozzle (nozzle_flow(): gas flows from
//!   the side of higher pressure, from that side's stagnation state, choked at M = 1), flux area = its aperture;
//!   the inflow's mass flux weighted against the walls' friction (friction_weighted_flux());
//!   what leaves the cracks is added to the junction's deposit (in entry order: deterministic). The reservoir
//!   (a grid cell) keeps its state over the channel's substeps, so what the cracks draw from it over the whole
//!   interval is held to a quarter of the gas it holds (the nozzles scaled down together, each to a nozzle of
//!   that fraction of its width: mass, momentum and energy alike); gas that
//!   reaches the mouth faster than sound leaves with its own flux (no nozzle can pass more);
//! - one gas segment, no mouth: a closed end (wall_pressure());
//! - k >= 2 gas segments: every pair exchanges an HLLC flux weighted against the friction's two-point flux
//!   (friction_weighted_flux()) through min(w_a, w_b) / (k - 1) (a straight chain: the smaller aperture),
//!   computed once per pair and given to both with opposite signs (exact conservation).
struct JunctionFluxKernel {
  cip::GasMaterials mat;
  CrackGraph g;
  CrackGeometry<Access::read> geo;
  CrackSegments<Access::read> seg;
  CrackMouths<Access::read> mouths;
  CrackEndStates<Access::read> faces;
  CrackEndFluxes<Access::read_write> fluxes;
  CrackDeposits<Access::read_write> deposits;
  ChannelFlowParams flow;  //!< the walls' friction (friction_weighted_flux())
  double dt;
  double interval;  //!< [s] the whole step the substeps of dt fill (the reservoirs' states are held over it)
  BLAST_HD void operator()(index_t ji) const {
    const int J = static_cast<int>(ji);
    int ends[kCrackMaxDegree];
    int k = 0;
    for (int e = g.junction_offset[J]; e < g.junction_offset[J + 1]; ++e)
      if (seg.kind[g.junction_entry[e] / 2] == kSegmentGas) ends[k++] = g.junction_entry[e];
    if (k == 0) return;
    // State at each end in the frame pointing into the junction.
    auto inward = [&](int end) {
      const ChannelPrimitive f = faces.face[end];
      return end % 2 == 1 ? f : reversed(f);
    };
    if (mouths.open[J]) {
      const ChannelPrimitive r = mouths.reservoir[J];
      ChannelConserved dep = deposits.deposit[J];
      ChannelConserved dep_drawn = deposits.drawn[J];
      double dep_px = deposits.momentum_x[J], dep_py = deposits.momentum_y[J];
      double drawn = 0.0;  // [kg/(m s)] the nozzles' inflow from the reservoir
      for (int a = 0; a < k; ++a) {
        const ChannelPrimitive s = inward(ends[a]);
        if (r.p > s.p) drawn += nozzle_flow(r.rho, r.p, r.rho * r.c * r.c / r.p, s.p).G * geo.aperture[ends[a] / 2];
      }
      const double held = 0.25 * mouths.reservoir_mass[J];
      const double scale = drawn * interval > held ? held / (drawn * interval) : 1.0;
      for (int a = 0; a < k; ++a) {
        const int end = ends[a];
        const double w = geo.aperture[end / 2];
        const ChannelPrimitive s = inward(end);
        ChannelFlux o{0, 0, 0, 0, 0};
        double area = w;        // [m] of the end's flux
        double exit_speed = 0;  // [m/s] of the gas leaving the crack, along its axis out of the segment
        if (r.p > s.p) {  // into the crack from the reservoir at rest
          // Held to `scale` of its draw, the nozzle is one of width scale w: mass, momentum (its pressure term
          // too) and energy all scale, so the gas enters at the nozzle's own state. Scaling the mass alone left
          // the pressure's push on less gas, which then entered faster than the nozzle allows, its kinetic energy
          // above its total below scale ~ 0.49 (a crack wider than about two cells: negative pressure, NaN).
          // The nozzle's mass flux weighted against the walls' friction over the half segment from the mouth to
          // the segment's centre (friction_weighted_flux(): the reservoir's gas at rest is the donor).
          const NozzleFlow nf = nozzle_flow(r.rho, r.p, r.rho * r.c * r.c / r.p, s.p);
          const FrictionWeightedFlux D = friction_weighted_flux(r, reversed(seg.prim[end / 2]), r, reversed(s),
                                                                0.5 * geo.length[end / 2], w, dt, flow);
          const double Gw = D.darcy.m > 0.0 ? D.alpha * nf.G + (1.0 - D.alpha) * D.darcy.m : nf.G;
          const double h0 = (r.Edens + r.p) / r.rho, G = scale * Gw;
          o = {-G * w, (G * nf.u + scale * nf.p) * w, -G * h0 * w, -G * r.Y * w, -G * r.alpha * w};
          area = scale * w;
        } else if (!is_vacuum(s) && s.u >= s.c) {  // out of the crack at its own supersonic speed: no nozzle
          o = scaled(physical_flux(s), w);
          exit_speed = s.u;
        } else if (!is_vacuum(s)) {  // out of the crack from its stagnation state
          const double kx = s.rho * s.c * s.c / s.p;
          const double M = s.u > 0 ? s.u / s.c : 0.0, T = 1.0 + 0.5 * (kx - 1.0) * M * M;
          const NozzleFlow nf = nozzle_flow(s.rho * pow(T, 1.0 / (kx - 1.0)), s.p * pow(T, kx / (kx - 1.0)), kx, r.p);
          const double h0 = (s.Edens + s.p) / s.rho;
          o = {nf.G * w, (nf.G * nf.u + nf.p) * w, nf.G * h0 * w, nf.G * s.Y * w, nf.G * s.alpha * w};
          exit_speed = nf.u;
        } else {
          o = {0, s.p * w, 0, 0, 0};
        }
        fluxes.out[end] = o;
        fluxes.end_area[end] = area;
        dep.m += dt * o.m, dep.E += dt * o.E, dep.m1 += dt * o.m1, dep.am += dt * o.am;
        if (o.m < 0.0)
          dep_drawn = {dep_drawn.m + dt * o.m, 0.0, dep_drawn.E + dt * o.E, dep_drawn.m1 + dt * o.m1, dep_drawn.am + dt * o.am};
        // the leaving gas's momentum, its mass flux times its speed along the end's axis out of the segment (the
        // pressure term of the end's momentum flux acts on the walls and the reservoir, and moves nothing)
        const double out = (end % 2 == 1 ? 1.0 : -1.0) * dt * (o.m > 0.0 ? o.m * exit_speed : 0.0);
        dep_px += out * geo.axis_x[end / 2], dep_py += out * geo.axis_y[end / 2];
      }
      deposits.deposit[J] = dep;
      deposits.drawn[J] = dep_drawn, deposits.momentum_x[J] = dep_px, deposits.momentum_y[J] = dep_py;
      return;
    }
    if (k == 1) {
      const double w = geo.aperture[ends[0] / 2];
      fluxes.out[ends[0]] = {0, wall_pressure(mat, inward(ends[0])) * w, 0, 0, 0};
      fluxes.end_area[ends[0]] = w;
      return;
    }
    ChannelFlux acc[kCrackMaxDegree];
    double area[kCrackMaxDegree];
    for (int a = 0; a < k; ++a) acc[a] = {0, 0, 0, 0, 0}, area[a] = 0;
    // a segment's centre state in the frame pointing into the junction (the Darcy flux's two points)
    auto centre = [&](int end) {
      const ChannelPrimitive P = seg.prim[end / 2];
      return end % 2 == 1 ? P : reversed(P);
    };
    for (int a = 0; a < k; ++a)
      for (int b = a + 1; b < k; ++b) {
        const double wf = fmin(geo.aperture[ends[a] / 2], geo.aperture[ends[b] / 2]), A = wf / (k - 1);
        const ChannelPrimitive La = inward(ends[a]), Rb = reversed(inward(ends[b]));
        const ChannelFlux H = hllc_flux(mat, La, Rb);
        const FrictionWeightedFlux D =
            friction_weighted_flux(centre(ends[a]), reversed(centre(ends[b])), La, Rb,
                                   0.5 * (geo.length[ends[a] / 2] + geo.length[ends[b] / 2]), wf, dt, flow);
        const double r = D.alpha, t = 1.0 - D.alpha;
        const ChannelFlux F = scaled({r * H.m + t * D.darcy.m, r * H.q + t * D.darcy.q, r * H.E + t * D.darcy.E,
                                      r * H.m1 + t * D.darcy.m1, r * H.am + t * D.darcy.am},
                                     A);
        acc[a] = {acc[a].m + F.m, acc[a].q + F.q, acc[a].E + F.E, acc[a].m1 + F.m1, acc[a].am + F.am};
        acc[b] = {acc[b].m - F.m, acc[b].q + F.q, acc[b].E - F.E, acc[b].m1 - F.m1, acc[b].am - F.am};
        area[a] += A, area[b] += A;
      }
    for (int a = 0; a < k; ++a) fluxes.out[ends[a]] = acc[a], fluxes.end_area[ends[a]] = area[a];
  }
};

//! Empties every junction's deposit (one thread per junction).
struct ClearDepositsKernel {
  CrackDeposits<Access::read_write> deposits;
  BLAST_HD void operator()(index_t J) const {
    deposits.deposit[J] = {0, 0, 0, 0, 0};
    deposits.drawn[J] = {0, 0, 0, 0, 0}, deposits.momentum_x[J] = 0.0, deposits.momentum_y[J] = 0.0;
  }
};

//! Conservative update of every gas segment from its two ends' outflows, the pressure of the walls where the
//! flux area changes (p (A1 - A0): a uniform gas at rest stays at rest in a channel of varying aperture), then
//! the wall friction, implicit (q / (1 + dt k), friction_rate()); friction turns kinetic energy into heat, so
//! E does not change. Then the walls' heat (flow.walls): none (adiabatic); the specific internal energy set to the
//! walls' e_w = wall_theta / Gamma (isothermal: a gas at the walls' temperature, p / rho = R T_w); or relaxed
//! towards it, implicit (e_w + (e - e_w) / (1 + dt rate), wall_heat_rate()). The heat given is booked in
//! wall_heat.
struct SegmentUpdateKernel {
  cip::GasMaterials mat;
  CrackGeometry<Access::read> geo;
  CrackSegments<Access::read_write> seg;  //!< writes cons and wall_heat
  CrackEndFluxes<Access::read> ends;
  ChannelFlowParams flow;
  double vacuum_density;  //!< [kg/m3] at or below it a segment holds no momentum and exchanges no heat
  double dt;
  BLAST_HD void operator()(index_t si) const {
    const int s = static_cast<int>(si);
    if (seg.kind[s] != kSegmentGas) return;
    const ChannelFlux o0 = ends.out[2 * s], o1 = ends.out[2 * s + 1];
    ChannelConserved c = seg.cons[s];
    c.m -= dt * (o0.m + o1.m);
    c.E -= dt * (o0.E + o1.E);
    c.m1 -= dt * (o0.m1 + o1.m1);
    c.am -= dt * (o0.am + o1.am);
    c.q -= dt * (o1.q - o0.q - seg.prim[s].p * (ends.end_area[2 * s + 1] - ends.end_area[2 * s]));
    const double V = seg.volume[s];
    if (c.m > vacuum_density * V && c.m > 0.0) {
      const double w = geo.aperture[s];
      const double k = friction_rate(c.m / V, c.q / c.m, w, flow);
      c.q /= 1.0 + dt * k;
      if (flow.walls != WallHeat::adiabatic) {
        const double u = c.q / c.m, e = (c.E - 0.5 * c.q * u) / c.m;
        const double G = mat.mixture_gruneisen(c.am / c.m), e_w = flow.wall_theta / G;
        const double keep =
            flow.walls == WallHeat::isothermal ? 0.0 : 1.0 / (1.0 + dt * wall_heat_rate(c.m / V, u, w, 1.0 + G, flow));
        const double heat = c.m * (e - e_w) * (1.0 - keep);
        c.E -= heat;
        seg.wall_heat[s] += heat;
      }
    } else {
      c.q = 0.0;  // vacuum holds no momentum
    }
    seg.cons[s] = c;
  }
};

//! True when x is neither infinite nor NaN (x - x is NaN for both), without <cmath> in kernels.
BLAST_HD inline bool finite_value(double x) { return x - x == 0.0; }

//! A gas segment's state is valid when its mass is finite and >= 0, its momentum, energy and volume finite.
BLAST_HD inline bool segment_state_valid(const ChannelConserved& c, double volume) {
  return c.m >= 0.0 && finite_value(c.m) && finite_value(c.q) && finite_value(c.E) && finite_value(volume);
}

//! The rate SegmentRateOf gives a segment whose state is not valid: CrackGas::advance() stops the run on it.
inline constexpr double kInvalidSegmentRate = 1e308;

//! The largest signal speed over length of a gas segment [1/s]: (|u| + c max(1, 2 / Gamma)) / L (the vacuum
//! front of a rarefaction runs at u + 2 c / Gamma); kInvalidSegmentRate for a state that is not valid.
struct SegmentRateOf {
  cip::GasMaterials mat;
  CrackGeometry<Access::read> geo;
  CrackSegments<Access::read> seg;
  BLAST_HD double operator()(index_t si) const {
    const int s = static_cast<int>(si);
    if (seg.kind[s] != kSegmentGas) return 0.0;
    if (!segment_state_valid(seg.cons[s], seg.volume[s])) return kInvalidSegmentRate;
    const ChannelPrimitive P = seg.prim[s];
    if (is_vacuum(P)) return 0.0;
    const double G = mat.mixture_gruneisen(P.alpha);
    return (fabs(P.u) + P.c * fmax(1.0, 2.0 / G)) / geo.length[s];
  }
};

//! The largest signal rate [1/s] at mouth J: its reservoir's gas enters at up to its vacuum front speed, over the
//! length of each gas segment that meets the mouth (CrackGas::stable_dt()).
struct MouthRateOf {
  cip::GasMaterials mat;
  CrackGraph g;
  CrackGeometry<Access::read> geo;
  CrackSegments<Access::read> seg;
  CrackMouths<Access::read> mouths;
  BLAST_HD double operator()(index_t ji) const {
    const int J = static_cast<int>(ji);
    if (!mouths.open[J]) return 0.0;
    const ChannelPrimitive r = mouths.reservoir[J];
    const double speed = r.c * fmax(1.0, 2.0 / mat.mixture_gruneisen(r.alpha));
    double best = 0.0;
    for (int k = g.junction_offset[J]; k < g.junction_offset[J + 1]; ++k) {
      const int s = g.junction_entry[k] / 2;
      if (seg.kind[s] == kSegmentGas) best = fmax(best, speed / geo.length[s]);
    }
    return best;
  }
};

//! What segment s holds when it holds gas, 0 otherwise (CrackGas::totals()): its mass, energy, products mass or
//! volume, 1 (a count), 1 above the pressure `wet` (a count of wet segments), or its pressure.
struct GasSegmentValue {
  enum What { mass, energy, products_mass, volume, count, wet_count, pressure };
  CrackSegments<Access::read> seg;
  What what;
  double wet;  //!< [Pa] for wet_count
  BLAST_HD double operator()(index_t s) const {
    if (seg.kind[s] != kSegmentGas) return 0.0;
    switch (what) {
      case mass: return seg.cons[s].m;
      case energy: return seg.cons[s].E;
      case products_mass: return seg.cons[s].m1;
      case volume: return seg.volume[s];
      case count: return 1.0;
      case wet_count: return seg.prim[s].p > wet ? 1.0 : 0.0;
      case pressure: return seg.prim[s].p;
    }
    return 0.0;
  }
};

//! The heat [J/m] segment s's gas gave its walls since the start (CrackGas::totals()).
struct WallHeatOf {
  CrackSegments<Access::read> seg;
  BLAST_HD double operator()(index_t s) const { return seg.wall_heat[s]; }
};

//! The densities [kg/m3] the network touches, over one index space (CrackGas::vacuum_density(), one reduction):
//! k < segments: segment k's gas (0 unless it holds gas); then junction k - segments's reservoir (0 unless open).
struct DensestGasOf {
  CrackSegments<Access::read> seg;
  CrackMouths<Access::read> mouths;
  index_t segments;
  BLAST_HD double operator()(index_t k) const {
    if (k >= segments) return mouths.open[k - segments] ? mouths.reservoir[k - segments].rho : 0.0;
    return seg.kind[k] == kSegmentGas && seg.volume[k] > 0.0 ? seg.cons[k].m / seg.volume[k] : 0.0;
  }
};

}  // namespace blastsim::ibm
