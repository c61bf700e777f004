//! \file test_backend_agreement.cpp
//! \brief Backend agreement: a short coupled blast (gas, rock, coupling) ends with the same totals on this
//! backend as the CPU backend's run recorded in data/coupled_fingerprint_cpu.txt.
//!
//! The case is the single-hole blast at a small size: Table 1 gas in the 50 mm hole of a 0.93 m disc meshed in
//! rings of 30 mm triangles (no Gmsh: it runs on the GPU machine), 192 x 192 cells over 2.24 m, 20 us (before the first crack, so
//! the run is not chaotic: backends that differ only in rounding, fused multiply-adds and the order of
//! reductions should stay far closer than the tolerance). Tolerance: 1e-6 of each quantity, far above
//! rounding and far below what a wrong kernel or a race makes. (Written 2026-11-23 without a GPU machine:
//! its first CUDA run is in scripts/gpu-bench.sh's test suite.) The file is the CPU backend's output; after a change that
//! moves results beyond rounding, rewrite it on the CPU backend with BLASTSIM_WRITE_REFERENCE=1 and say why in
//! the commit.
#include "blastsim/cip/gas_solver.hpp"
#include "blastsim/fdem/mesh.hpp"
#include "blastsim/fdem/rock_solver.hpp"
#include "blastsim/ibm/coupler.hpp"
#include "catch.hpp"
#include "short_blast.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <map>
#include <sstream>
#include <string>

using namespace blastsim;

namespace {

const std::string reference_file = std::string(BLASTSIM_TEST_DATA_DIR) + "/coupled_fingerprint_cpu.txt";

//! The quantities compared, by name.
std::map<std::string, double> short_blast_fingerprint() {
  cip::GasMaterials one_gas;
  one_gas.air = cip::EquationOfState::ideal(1.4);
  test::ShortBlast blast(one_gas, cip::GasPoint{163.0, 4.29e5, 0, 0});
  blast.run_to(20e-6);
  const cip::GasSolver& gas = blast.gas;
  const fdem::RockSolver& rock = blast.rock;
  const ibm::GasRockCoupler& coupler = *blast.coupler;
  const cip::GasTotals g = gas.totals();
  const fdem::RockEnergies e = rock.energies();
  const fdem::RockSnapshot s = rock.snapshot();
  double travel = 0;  // sum over nodes of |x - x0| + |y - y0| [m]
  for (size_t n = 0; n < s.x.size(); ++n) travel += std::fabs(s.x[n] - s.x0[n]) + std::fabs(s.y[n] - s.y0[n]);
  return {{"gas_mass", g.mass},
          {"gas_internal_energy", g.internal_energy},
          {"gas_kinetic_energy", g.kinetic_energy},
          {"rock_kinetic_energy", e.kinetic},
          {"rock_strain_energy", e.strain},
          {"gas_work_on_rock", e.pressure_work},
          {"rock_node_travel", travel},
          {"broken_joints", static_cast<double>(e.broken_joints)},
          {"inactive_cells", static_cast<double>(coupler.inactive_cells())},
          {"gas_steps", static_cast<double>(gas.steps())}};
}

}  // namespace

TEST_CASE("Backend agreement: a short coupled blast ends with the CPU backend's totals", "[ibm][backend][heavy]") {
  const std::map<std::string, double> now = short_blast_fingerprint();
  if (std::getenv("BLASTSIM_WRITE_REFERENCE")) {
    REQUIRE(std::string(backend_name()).rfind("cpu", 0) == 0);  // the reference is the CPU backend's
    std::ofstream out(reference_file);
    out << "# blastsim: totals of the short coupled blast of tests/ibm/test_backend_agreement.cpp, CPU backend\n";
    char line[128];
    for (const auto& [name, value] : now) {
      std::snprintf(line, sizeof line, "%s %.17g\n", name.c_str(), value);
      out << line;
    }
    REQUIRE(out.good());
    WARN("reference written: " << reference_file);
    return;
  }
  std::ifstream in(reference_file);
  REQUIRE(in.good());
  std::map<std::string, double> ref;
  std::string line;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#') continue;
    std::istringstream row(line);
    std::string name;
    double value = 0;
    row >> name >> value;
    ref[name] = value;
  }
  REQUIRE(ref.size() == now.size());
  for (const auto& [name, value] : now) {
    INFO(name << ": " << backend_name() << " " << value << ", CPU reference " << ref[name]);
    std::printf("backend agreement (%s): %-20s %.12e vs CPU %.12e (%+.2e)\n", backend_name(), name.c_str(), value,
                ref[name], ref[name] != 0 ? value / ref[name] - 1 : value);
    REQUIRE(ref.count(name) == 1);
    CHECK(std::fabs(value - ref[name]) <= 1e-6 * std::fabs(ref[name]));
  }
  CHECK(now.at("gas_work_on_rock") > 0);  // the gas has pushed the rock: the case tests the coupling
  CHECK(now.at("rock_strain_energy") > 0);
}
