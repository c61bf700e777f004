//! \file test_step_scalars.cpp
//! \brief docs/validation.md I7: a coupled step (gas step, rock substeps, coupling) makes the host wait once, for
//! the gas's signal rate and the rock's largest speed read together; both are the values each solver's own
//! reduction gives, and a non-finite rock in any substep still stops the run.
#include "blastsim/core/backend.hpp"
#include "validation_courant.hpp"
#include "blastsim/core/error.hpp"
#include "catch.hpp"
#include "short_blast.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <string>
#include <vector>

using namespace blastsim;

TEST_CASE("I7 one host wait a coupled step: signal rate and rock speed in one reduction", "[ibm][I7]") {
  cip::GasMaterials one_gas;
  one_gas.air = cip::EquationOfState::ideal(1.4);
  test::ShortBlast blast(one_gas, cip::GasPoint{163.0, 4.29e5, 0, 0});
  cip::GasSolver& gas = blast.gas;
  fdem::RockSolver& rock = blast.rock;
  ibm::GasRockCoupler& coupler = *blast.coupler;
  const int substeps = 3;
  auto dt_now = [&] { return std::min(blastsim::test::validation_courant(coupler.courant()) / coupler.signal_rate(), substeps * 0.9 * rock.stable_dt()); };
  coupler.step(std::min(gas.courant_dt(blastsim::test::validation_courant(coupler.courant())), substeps * 0.9 * rock.stable_dt()), substeps);
  const long rebuilds = rock.contact_rebuilds();
  const long rock_steps = rock.steps();
  const LaunchCounts before = LaunchCounts::instance();
  const int steps = 10;
  for (int k = 0; k < steps; ++k) coupler.step(dt_now(), substeps);
  const LaunchCounts after = LaunchCounts::instance();
  const double waits = double(after.host_waits - before.host_waits) / steps;
  const double launches = double(after.launches - before.launches) / steps;
  // The coupler's rate is the gas's own reduction of the same state (a maximum: the same bits on any tree).
  const double own_rate = gas.max_signal_rate();
  std::printf("I7 coupled step with %d rock substeps: %.2f host waits and %.1f launches a step over %d steps (no contact "
              "rebuild: %ld before, %ld after); signal rate %.9e 1/s vs the gas's own %.9e 1/s\n",
              substeps, waits, launches, steps, rebuilds, rock.contact_rebuilds(), coupler.signal_rate(), own_rate);
  REQUIRE(rock.contact_rebuilds() == rebuilds);  // a rebuild would add its own waits (sizes of the new lists)
  CHECK(rock.steps() - rock_steps == static_cast<long>(steps) * substeps);
  CHECK(after.host_waits - before.host_waits == steps);
  CHECK(coupler.signal_rate() == own_rate);

  // A node whose velocity turns non-finite is caught at the end of the step, whichever substep it happened in
  // (node 0: the message names the first non-finite node by index).
  std::vector<double> v(2 * rock.node_count(), 0.0);
  v[0] = std::numeric_limits<double>::quiet_NaN();
  rock.set_velocities(v);
  std::string message;
  try {
    coupler.step(dt_now(), substeps);
  } catch (const InstabilityError& e) {
    message = e.what();
  }
  std::printf("I7 non-finite rock velocity: \"%s\"\n", message.c_str());
  CHECK(message.find("rock velocity not finite") != std::string::npos);
  CHECK(message.find("node 0 ") != std::string::npos);
}
