//! \file rock_types.hpp
//! \brief Plain types of the rock solver's interface (options, energies, host snapshot); no backend headers.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

namespace blastsim::fdem {

//! Values of RockSolver::edge_exposed(): not exposed, a mesh boundary edge, a face of a broken joint.
inline constexpr std::uint8_t kEdgeInside = 0, kEdgeBoundary = 1, kEdgeCrackFace = 2;

//! Kinds of work accumulated per node: pressure, joint, contact, support, gravity, viscous boundary.
inline constexpr int kWorkKinds = 6;

//! Numerical parameters of the rock model (the physical ones are in RockMaterial).
struct RockOptions {
  double joint_penalty_factor = 10.0;    //!< joint penalty p / E [-] (docs/fdem-solver.md: 10 to 100)
  double contact_penalty_factor = 10.0;  //!< contact penalty p_c / E [-]
  double damping_ratio = 0.0;            //!< beta in eta = 2 h beta sqrt(E rho), in [0, 1)
  std::array<double, 2> gravity{0.0, 0.0};  //!< [m/s2]
  bool contact = true;                   //!< contact between pieces on or off
  double contact_buffer = 0.25;          //!< broad-phase buffer as a fraction of the largest element size
  void validate() const;
};

//! Cumulative energies per unit thickness [J/m]. Balance: kinetic + strain + joint_work + contact_work +
//! damping = initial kinetic + initial strain + external_work (to time-integration error).
struct RockEnergies {
  double kinetic = 0;
  double strain = 0;               //!< elastic energy of the triangles (hyperelastic potential of the stress)
  double joint_work = 0;           //!< work done on the cohesive joints (stored + dissipated)
  double joint_stored = 0;         //!< elastic energy still held by the joints (secant estimate)
  double fracture_dissipated = 0;  //!< joint_work - (joint_stored - the joints' stored energy at the start)
  double contact_work = 0;         //!< work done on contacts (penalty energy + friction)
  double friction_dissipated = 0;  //!< of which dissipated by Coulomb friction
  double damping_dissipated = 0;   //!< by the triangles' viscous damping
  double external_work = 0;        //!< of pressures, gravity, prescribed-velocity supports and viscous boundaries
  double boundary_work = 0;        //!< of the viscous boundaries alone (<= 0: minus the energy radiated out)
  double pressure_work = 0;        //!< of the edge pressures alone (in a coupled run: the gas's work on the rock)
  int broken_joints = 0;
  double crack_length = 0;         //!< total length of broken joints [m]
};

//! A velocity probe's reading (RockSolver::probe_samples()).
struct ProbeSample {
  double vx = 0, vy = 0;      //!< current velocity [m/s]
  double peak_speed = 0;      //!< peak particle velocity so far: the largest |v| (peak vector sum) [m/s]
  double peak_time = 0;       //!< [s] when it occurred
  double peak_vx = 0, peak_vy = 0;  //!< the velocity then [m/s]
};

//! Host copy of the rock for output.
struct RockSnapshot {
  std::vector<double> x, y, vx, vy;     //!< per node [m], [m/s]
  std::vector<double> x0, y0;           //!< initial node positions [m]
  std::vector<double> stress;           //!< per triangle: sxx, sxy, syy [Pa] (3 per triangle)
  std::vector<double> joint_damage;     //!< per joint: largest damage of its three points, in [0, 1]
  std::vector<std::uint8_t> joint_broken;
  std::vector<std::array<int, 4>> joint_nodes;  //!< a0, a1, b0, b1
};

}  // namespace blastsim::fdem
