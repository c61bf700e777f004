//! \file test_products_coupling.cpp
//! \brief docs/validation.md I6: JWL detonation products (ANFO) in the hole of an elastic disc, air around it: the
//! coupled step with two gas materials keeps the products mass, closes the energy budget and pushes the rock.
#include "blastsim/cip/gas_solver.hpp"
#include "blastsim/fdem/mesh.hpp"
#include "blastsim/fdem/rock_solver.hpp"
#include "blastsim/ibm/budget.hpp"
#include "blastsim/ibm/coupler.hpp"
#include "catch.hpp"
#include "short_blast.hpp"

#include <algorithm>
#include <cmath>

using namespace blastsim;

TEST_CASE("I6 ANFO products in a hole of elastic rock: products mass kept, budget closed", "[ibm][I6][heavy]") {
  cip::GasMaterials mat;
  mat.air = cip::EquationOfState::ideal(1.4);
  mat.products = cip::EquationOfState::jwl_products(cip::EquationOfState::jwl_preset("ANFO").p);
  mat.two = true;
  // Products expanded to 100 MPa at 200 kg/m3 (a quarter of the explosive's density).
  test::ShortBlast blast(mat, cip::GasPoint{200.0, mat.products.internal_energy(200.0, 1e8), 0, 0, 1.0});
  const cip::GasSolver& gas = blast.gas;
  const fdem::RockSolver& rock = blast.rock;
  const double m1_start = gas.totals().products_mass, e0 = ibm::initial_energy(gas, rock);
  blast.run_to(30e-6);
  const ibm::CoupledBudget b = ibm::coupled_budget(gas, rock, *blast.coupler, e0);
  const double m1_end = gas.totals().products_mass + gas.boundary_outflow().products_mass;
  std::printf("I6 ANFO products in the hole, 30 us: products mass %.6e -> %.6e kg/m (%+.1e), gas work on the rock "
              "%.4e J/m, budget residual %.3e J/m (%+.2f %% of that work)\n",
              m1_start, m1_end, m1_end / m1_start - 1, b.coupling.gas_work_on_rock, b.residual,
              100 * b.residual / b.coupling.gas_work_on_rock);
  CHECK(m1_start > 0);
  // Covered cells hand their products to their neighbours; none is lost while the hole wall holds.
  CHECK(std::fabs(m1_end / m1_start - 1) <= 1e-12);
  CHECK(b.coupling.gas_work_on_rock > 0);
  CHECK(std::fabs(b.residual) <= 0.05 * b.coupling.gas_work_on_rock);  // the bound of the one-gas budget test
}
