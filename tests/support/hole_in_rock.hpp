//! \file hole_in_rock.hpp
//! \brief The coupling tests' pressurised hole: a Gmsh disc of rock with a central hole of the paper's Table 1
//! gas, in Table 1 air, on a square grid (tests/ibm; needs Gmsh).
#pragma once

#include "blastsim/cip/gas_solver.hpp"
#include "validation_courant.hpp"
#include "blastsim/fdem/gmsh_mesh.hpp"
#include "blastsim/fdem/rock_solver.hpp"
#include "blastsim/ibm/coupler.hpp"
#include "catch.hpp"

#include <cmath>
#include <vector>

namespace blastsim::test {

//! The paper's Table 1 hole gas: p = 0.4 x 163 x 4.29e5 = 27.97 MPa; ambient air 1.2 kg/m3 at 2.09e5 J/kg
//! (100.32 kPa); both an ideal gas of gamma 1.4.
inline const cip::GasPoint table1_gas{163.0, 4.29e5, 0.0, 0.0};
inline const cip::GasPoint table1_air{1.20, 2.09e5, 0.0, 0.0};

//! The paper's rock made strong enough to stay intact (elastic constants of Table 2, strengths x 100).
inline fdem::RockMaterial intact_rock() {
  fdem::RockMaterial m = fdem::RockMaterial::paper_table2();
  m.tensile_strength *= 100, m.cohesion *= 100, m.fracture_energy_mode1 *= 1e4, m.fracture_energy_mode2 *= 1e4;
  return m;
}

//! A disc of rock (radius R, central hole a, triangles of size h) in air on an N x N grid over [-w, w]^2; the
//! hole holds the Table 1 gas in every cell centred within 1.5 cells of the hole radius (cut cells included).
//! `cracks`: segments put into the mesh (pre-cut cracks once their joints are broken); `load`: how the gas loads
//! the rock.
struct HoleInRock {
  cip::GasSolver gas;
  fdem::RockSolver rock;
  ibm::GasRockCoupler coupler;
  HoleInRock(int N, double w, double R, double a, double h, const fdem::RockMaterial& m,
             const std::vector<fdem::Segment>& cracks = {}, ibm::GasLoad load = ibm::GasLoad::edge_pressures,
             fdem::GmshAlgorithm mesher = fdem::GmshAlgorithm::delaunay)
      : gas(cip::GasGrid::from_box(N, N, -w, w, -w, w), cip::EquationOfState::ideal(1.4)),
        rock(fdem::build_topology(fdem::gmsh_disc_with_hole(0, 0, R, a, h, cracks, mesher).mesh), m, no_contact()),
        coupler(gas, rock, table1_air, options_for(load)) {
    const double r_fill = a + 1.5 * 2 * w / N;
    gas.initialise([&](double x, double y) { return x * x + y * y < r_fill * r_fill ? table1_gas : table1_air; });
    coupler.rock_to_gas();
  }
  static ibm::CouplerOptions options_for(ibm::GasLoad load) {
    ibm::CouplerOptions o;
    o.gas_load = load;
    return o;
  }
  static fdem::RockOptions no_contact() {
    fdem::RockOptions o;
    o.contact = false;
    return o;
  }
  //! Steps to t: one dt for both solvers, or (subcycle) gas steps at the Courant limit, each filled with as
  //! many rock steps as keep the rock within its stable step.
  void run_to(double t, bool subcycle = false) {
    while (gas.time() < t - 1e-12) step_towards(t, subcycle);
  }
  //! One coupled step towards t (shortened to land on it); returns its dt [s].
  double step_towards(double t, bool subcycle = false) {
    const double dt = std::fmin(subcycle ? gas.courant_dt(blastsim::test::validation_courant(coupler.courant())) : coupler.stable_dt(blastsim::test::validation_courant(coupler.courant())), t - gas.time());
    if (!(dt > 0)) FAIL("no stable step at t = " << gas.time() << ": " << gas.describe_invalid_cell());
    const int substeps = subcycle ? ibm::rock_substeps(dt, 0.9 * rock.stable_dt()) : 1;
    coupler.step(dt, substeps);
    return dt;
  }
};

}  // namespace blastsim::test
