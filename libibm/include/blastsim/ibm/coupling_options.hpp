//! \file coupling_options.hpp
//! \brief The coupling's options, apart from its processes: how the gas loads the rock, the crack gas model's
//! parameters, the coupled step's policy, the blasthole monitor's circles. Host code with no device arrays: the
//! driver's case description includes this header, not the processes'.
#pragma once

#include "blastsim/cip/gas_types.hpp"

#include <array>
#include <optional>

namespace blastsim::ibm {

//! How a covered face point takes the rock's velocity (face_point_coupling()).
enum class FacePointRule {
  shape_functions,  //!< the covering triangle's shape functions at the point (the paper's rule)
  surface_normal,   //!< the normal motion of the exposed edge it stands for (with face forces)
};

//! How the grid gas loads the rock (docs/coupling.md "Gas -> rock"). Crack faces with their own gas (crack gas)
//! take that gas's pressure either way (CrackGasCoupling).
enum class GasLoad {
  //! The paper's rule: every exposed edge takes the pressure of the active cell it faces (or the nearest one).
  edge_pressures,
  //! The force the gas's momentum equation applied at each prescribed face, put on the rock surface it stands
  //! for, along the surface normal, with the weights that gave the face its imposed (normal) velocity: the
  //! rock receives exactly the work the gas did on its immersed faces.
  face_forces,
  //! The paper's edge pressures, with the gas paying the rock's work: after the rock's substeps every active cell
  //! takes back the work its energy equation did on its prescribed faces and pays the work of the edges it loaded,
  //! as the rock's ledger counts it (docs/coupling.md "Edge pressures that the gas pays for").
  edge_pressures_paid,
};
//! "edges", "faces" or "edges_paid" (the driver's `coupling.gas_load`).
const char* gas_load_name(GasLoad load);
//! The face-point rule that goes with a load: face forces need the faces to move with the surface they load.
FacePointRule face_point_rule(GasLoad load);
//! The default Courant number of a coupled run: the transport's (cip::recommended_courant()), and the paper's
//! with its edge pressures, whose energy budget holds at the paper's number only when the rock subcycles
//! (docs/performance.md, "The Courant number"). Face forces and paid edge pressures pay the rock's work over the
//! substeps (docs/coupling.md).
inline double recommended_courant(cip::Transport t, GasLoad load) {
  return load == GasLoad::edge_pressures ? cip::kPaperCourant : cip::recommended_courant(t);
}

//! How the crack walls exchange heat with the gas in the cracks (docs/coupling.md "Heat at the walls").
enum class WallHeat {
  adiabatic,   //!< no heat crosses the walls: friction heats the gas
  isothermal,  //!< the gas takes the walls' temperature at once
  exchange,    //!< a heat flux by the Chilton-Colburn analogy (turbulent) or the laminar Nusselt number
};
//! "adiabatic", "isothermal" or "exchange" (the driver's `crack_gas.walls`).
const char* wall_heat_name(WallHeat walls);

//! The physical parameters of the channel flow (CrackGasOptions' kernel part).
struct ChannelFlowParams {
  double friction_factor;  //!< a constant rough-wall Darcy factor [-], or < 0: Louis's law of the roughness
  double roughness;        //!< asperity height k [m] of Louis's law
  double viscosity;        //!< [Pa s], laminar floor of the friction
  WallHeat walls;          //!< the walls' heat model
  double wall_theta;       //!< [J/kg] p / rho of a gas at the walls' temperature (R T_wall)
  double prandtl;          //!< the gas's Prandtl number [-]
  double colburn;          //!< Pr^(-2/3) [-] (the Chilton-Colburn factor)
};

//! The hyperbolic closure of an open joint's asperities under normal stress (Bandis, Lumsden & Barton 1983):
//! closure = sigma V_m / (K_ni V_m + sigma) (docs/coupling.md "Open joints under stress").
struct JointClosure {
  double stiffness;    //!< initial normal stiffness K_ni [Pa/m]
  double max_closure;  //!< maximum closure V_m [m], below every open joint's initial aperture
};

//! Parameters of the crack gas model (input section [crack_gas], docs/input.md; docs/coupling.md "Gas in the
//! cracks" gives their sources).
struct CrackGasOptions {
  double residual_aperture = 1e-5;  //!< [m] aperture of a crack whose faces touch (its gas volume is L x this)
  //! The closure law of the joints given an initial aperture (CrackGasCoupling::set_initial_apertures()); unset:
  //! they keep their initial aperture under any normal stress.
  std::optional<JointClosure> joint_closure;
  //! A constant rough-wall Darcy friction factor [-]; unset: Louis's law of the relative roughness
  //! roughness / (2 w) (louis_friction()), which falls as the crack opens.
  std::optional<double> friction_factor;
  std::optional<double> roughness;  //!< [m] asperity height of the crack walls; unset: the residual aperture
  double viscosity = 5e-5;          //!< gas dynamic viscosity [Pa s] (laminar friction floor)
  //! How the walls exchange heat with the gas (docs/coupling.md "Heat at the walls").
  WallHeat walls = WallHeat::exchange;
  //! [J/kg] p / rho of a gas at the walls' temperature (R T_wall); unset: the coupler sets the ambient air's
  //! (the rock at the air's temperature). A CrackGas alone needs it unless its walls are adiabatic.
  std::optional<double> wall_theta;
  double prandtl = 0.71;            //!< the gas's Prandtl number [-] (air, 300-1500 K)
  double courant = 0.4;             //!< Courant number of the channel solver's substeps, in [kMinCourant, 1]
  //! The smallest Courant number accepted: the substeps of one coupled step grow as 1 / courant, and below this
  //! a run takes more than 40 times the default's channel work for no accuracy (the scheme's error is that of its
  //! cells, not of its step, at any Courant number below 1).
  static constexpr double kMinCourant = 0.01;
  bool second_order = true;         //!< MUSCL-Hancock along straight chains (first order otherwise)
  //! [-] A segment whose density is below this fraction of the densest gas the network touches (its mouths'
  //! reservoirs and its own segments, at the start of each advance) is vacuum to the channel solver (a freshly
  //! broken joint starts empty): the thin edge of gas expanding into an empty crack carries no pressure and sends
  //! no flux until more gas arrives. Counted as gas, it runs ahead of the rarefaction at u + 2 c / Gamma, its
  //! motion turns into heat at the walls (the laminar friction 12 mu / (rho w^2) grows without bound as rho
  //! falls), and a wisp of it at millions of kelvin sets the channel's substeps. Relative, not absolute: with
  //! fully rough walls the channel flow has no density scale of its own (rho, p and the fluxes scale together; u
  //! and c stay), so a fixed threshold put the fronts of thin sources ahead (docs/coupling.md "vacuum").
  double vacuum_fraction = kDefaultVacuumFraction;
  //! The ratio of the earlier fixed threshold (1e-2 kg/m3) to the 34.5 kg/m3 reservoir of C9, the case it was
  //! measured on (docs/validation-coupling.md C9).
  static constexpr double kDefaultVacuumFraction = 3e-4;
  //! [cells] a crack whose faces are this many grid cells apart is the grid's (its gas handed to the cells it
  //! opens); narrower ones carry their own gas and are solid to the grid (docs/coupling.md "Hand-over")
  double handover_width = kDefaultHandoverWidth;
  static constexpr double kDefaultHandoverWidth = 2.0;
  //! Throws InputError naming the parameter unless residual_aperture > 0, friction_factor >= 0, roughness > 0,
  //! viscosity >= 0, kMinCourant <= courant <= 1, handover_width >= 1, 0 <= vacuum_fraction < 1, prandtl > 0 and
  //! wall_theta > 0 (set unless the walls are adiabatic), joint_closure's stiffness and maximum closure > 0 (all
  //! finite).
  void validate() const;
  //! The kernels' flow parameters: a constant friction factor, or Louis's law with the roughness.
  ChannelFlowParams flow() const;
};

//! How the coupled steps are made (the driver's [time] and [coupling] keys).
struct CouplerOptions {
  GasLoad gas_load = GasLoad::edge_pressures;  //!< how the grid gas loads the rock (gas_loading.hpp)
  //! [-] the gas's Courant number; unset: recommended_courant() of the gas's transport and the gas load
  std::optional<double> courant;
  double rock_dt = 0;            //!< [s] the rock's step (0: its stable step)
  bool rock_subcycling = false;  //!< the rock takes as many steps of at most rock_dt as fill each gas step
  std::optional<double> fixed_dt;  //!< [s] every step's dt (the caller checks it against the limits)
};

//! The hole and the rock's outer surface, circles about one centre [m].
struct BlastholeGeometry {
  std::array<double, 2> center{};
  double hole_radius = 0;
  double outer_radius = 0;
  void validate() const;  //!< InputError unless 0 < hole_radius < outer_radius
};

}  // namespace blastsim::ibm
