//! \file short_blast.hpp
//! \brief The short single-hole blast of the coupling tests: a 0.93 m disc of Table 2 rock (ring mesh of 30 mm
//! triangles, no Gmsh) with a 50 mm hole, 192 x 192 cells over 2.24 m, the hole's gas reaching 1.5 cells past the wall.
#pragma once

#include "blastsim/cip/gas_solver.hpp"
#include "validation_courant.hpp"
#include "blastsim/fdem/mesh.hpp"
#include "blastsim/fdem/rock_solver.hpp"
#include "blastsim/ibm/coupler.hpp"

#include <algorithm>
#include <optional>

namespace blastsim::test {

struct ShortBlast {
  static constexpr double half_width = 1.12;  //!< [m] of the grid
  const cip::GasPoint air{1.20, 2.09e5, 0, 0};
  cip::GasSolver gas;
  fdem::FdemTopology topology;
  fdem::RockSolver rock;
  std::optional<ibm::GasRockCoupler> coupler;

  //! `hole_gas` in the hole, air elsewhere; masks set (rock_to_gas()).
  ShortBlast(const cip::GasMaterials& materials, const cip::GasPoint& hole_gas)
      : gas(cip::GasGrid::from_box(192, 192, -half_width, half_width, -half_width, half_width), materials),
        topology(fdem::build_topology(fdem::ring_disc_with_hole(0, 0, 0.93, 0.05, 0.03).mesh)),
        rock(topology, fdem::RockMaterial::paper_table2(), fdem::RockOptions{}) {
    const double r_fill = 0.05 + 1.5 * 2 * half_width / 192;
    gas.initialise([&](double x, double y) { return x * x + y * y < r_fill * r_fill ? hole_gas : air; });
    coupler.emplace(gas, rock, air);
    coupler->rock_to_gas();
  }
  ShortBlast(const ShortBlast&) = delete;  // the coupler holds references to the solvers
  ShortBlast& operator=(const ShortBlast&) = delete;

  //! Coupled steps at the validations' Courant number (validation_courant() of the coupler's) and 0.9 of the rock's stable step to
  //! t_end [s].
  void run_to(double t_end) {
    while (gas.time() < t_end * (1 - 1e-12)) {
      const double dt = std::min({gas.courant_dt(blastsim::test::validation_courant(coupler->courant())), 0.9 * rock.stable_dt(), t_end - gas.time()});
      coupler->step(dt);
    }
  }
};

}  // namespace blastsim::test
