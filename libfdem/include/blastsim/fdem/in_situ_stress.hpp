//! \file in_situ_stress.hpp
//! \brief In-situ stress of a rock mass: the stress field, the triangles' prestretch and the joints' preload that
//! carry it at rest, and the options of the static equilibration (dynamic relaxation) that follows (host code).
#pragma once

#include "blastsim/fdem/joint_kernels.hpp"
#include "blastsim/fdem/mesh.hpp"
#include "blastsim/fdem/triangle_kernels.hpp"

#include <array>
#include <functional>
#include <vector>

namespace blastsim::fdem {

//! In-situ stress [Pa], tension positive (so the compression of rock at depth is negative), linear in y:
//! sigma(y) = at_reference + (y - reference_y) gradient. A uniform state has no gradient; under gravity
//! g = (g_x, g_y) equilibrium (div sigma + rho g = 0 with sigma depending on y alone) needs the gradient of
//! sigma_yy to be -rho g_y and that of tau_xy -rho g_x; sigma_xx may grow with depth at any rate.
struct InSituStress {
  std::array<double, 3> at_reference{};  //!< sigma_xx, sigma_yy, tau_xy [Pa] at y = reference_y
  double reference_y = 0;                //!< [m]
  std::array<double, 3> gradient{};      //!< d/dy of sigma_xx, sigma_yy, tau_xy [Pa/m]
  //! The stress at height y [m] as a symmetric matrix [[xx, xy], [xy, yy]] [Pa].
  Mat2 at(double y) const;
};

//! Symmetric stretch F_s (no rotation) whose Cauchy stress in triangle_stress() (no damping) is `sigma` [Pa]:
//! the shape change from a stress-free triangle to the stressed rock. Hooke's plane-strain compliance gives the
//! first guess and the correction of each iteration. Throws InputError when the stress is beyond what the
//! solid can take (no convergence, or an inverted stretch: |sigma| of the order of the moduli).
Mat2 prestretch(const Mat2& sigma, double lambda, double mu);

//! Offsets of opening and slip [m] at which the joint law gives given tractions at rest.
struct JointPreload {
  double opening, slip;
};

//! The preload at which joint_traction() gives normal traction `normal` and shear traction `shear` [Pa] (tension
//! positive) without damage: a compressed joint sits in its penalty branch, one under tension or shear on the
//! rising branch before the peak. Throws InputError when the joint cannot carry them (normal >= f_t, or |shear|
//! >= its Mohr-Coulomb shear strength c - sigma tan(phi)).
JointPreload joint_preload(double normal, double shear, const JointStrength& strength);

//! The weight of the rock that holes took from a rock mass, put on its held boundaries. The field s is in
//! equilibrium with gravity in the uncut rock mass, so its tractions on the whole boundary balance the weight of
//! the rock in the model; a hole's wall is free, so the tractions it would carry (the weight of the rock cut out,
//! and its moment) are missing from the balance, and a model held by the field's tractions alone would never come
//! to rest. This adds that resultant, force and moment, to the held nodes' dead loads `load` [N/m per node]: the
//! holes are the boundary's closed loops with no held edge (`held_slot`, indexed by edge slot = first node), their
//! tractions sigma(midpoint) N taken half per node as on the held edges, and the resultant spread over the held
//! nodes in proportion to each one's share w_n of held edge length, as f_n = w_n (A + B z x (r_n - r_c)) about the
//! shares' centroid r_c. It adds nothing without holes; with a uniform field the holes' tractions cancel.
//! `x0`, `y0` [m] per node, `node_vertex` the mesh vertex of each node (which joins the loops' edges).
void carry_cut_weight(const InSituStress& s, const std::vector<BoundaryEdge>& boundary_edges,
                      const std::vector<int>& node_vertex, const std::vector<double>& x0, const std::vector<double>& y0,
                      const std::vector<char>& held_slot, std::vector<Vec2>& load);

//! Static equilibration by viscous dynamic relaxation (equilibrate(), rock_model.hpp; Otter 1966, Underwood 1983):
//! explicit steps at the stable step with mass-proportional damping c = 2 omega, omega = pi c_s / (2 L) an
//! estimate of the slowest mode of a model of size L (its bounding box's diagonal), so every mode's amplitude
//! decays as exp(-omega t). Once the kinetic energy is below `tolerance` x the elastic energy the rock holds, the
//! steps go on undamped for the time a P wave takes to cross the model twice; if the kinetic energy stays below the
//! tolerance all that time the rock is at rest, else the damping resumes. (Kinetic damping, which stops the nodes
//! at each peak of kinetic energy, stalls here: the stiff joint penalties peak every few steps.)
struct EquilibriumOptions {
  double tolerance = 1e-8;  //!< kinetic / elastic energy [-]
  long max_steps = 200000;
  //! Called every `progress_interval` steps with the steps so far and the kinetic / elastic energy (a log line).
  std::function<void(long, double)> progress;
  long progress_interval = 10000;
};
//! What an equilibration did.
struct EquilibriumReport {
  long steps = 0;
  int checks = 0;              //!< undamped checks begun (the last one passed when converged)
  double kinetic_ratio = 0;    //!< largest kinetic / elastic energy over the final undamped window
  double elastic_energy = 0;   //!< [J/m] held by the triangles and joints at the end
  bool converged = false;
  int broken_joints = 0;       //!< at the end (joints the in-situ stress broke where the rock was cut)
};

}  // namespace blastsim::fdem
