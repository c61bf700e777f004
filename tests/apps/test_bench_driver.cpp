//! \file test_bench_driver.cpp
//! \brief Driver on the bench example (examples/bench_blast: charges on delays, viscous boundaries): bad charge
//! input gives one clear line naming the key; a shrunk bench fires each charge at its time, and a restart from a
//! checkpoint taken before a charge fired ends byte for byte like the uninterrupted run.
#include "blastsim/core/error.hpp"
#include "case.hpp"
#include "catch.hpp"
#include "run_loop.hpp"
#include "temp_files.hpp"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>

namespace fs = std::filesystem;
using namespace blastsim;
using blastsim::testing::csv_columns;
using blastsim::testing::file_bytes;
using blastsim::testing::fresh_dir;

namespace {
const std::string bench = std::string(BLASTSIM_EXAMPLES_DIR) + "/bench_blast/bench_blast.toml";

app::Case read_bench(const std::vector<std::string>& overrides) {
  return app::read_case(app::load_input(bench, overrides));
}

//! The bench shrunk for a test: 6 mm cells, 12 mm triangles, 30 us; the charges at 0, 12 and 25 us.
std::vector<std::string> small_bench(const fs::path& out) {
  return {"domain.nx=90", "domain.ny=80", "rock.mesh.element_size=0.012", "time.end=3e-5", "output.interval=1e-5",
          "output.monitor_interval=2", "output.vtk=false", "output.progress_interval=0.0",
          "charge.1.initiation_time=1.2e-5", "charge.2.initiation_time=2.5e-5",
          "output.directory=\"" + out.string() + "\""};
}

}  // namespace

TEST_CASE("Bad charges give one clear error naming the key", "[app][charges][bad]") {
  const app::Case c = read_bench({});
  REQUIRE(c.coupling.charges.size() == 3);
  CHECK(c.rock.model.mesh.holes.size() == 3);
  CHECK(c.analysis.holes.size() == 3);
  CHECK_THROWS_WITH(read_bench({"charge.1.radius=0.012"}), Catch::Contains("charge.1.radius") && Catch::Contains("larger than its hole"));
  CHECK_THROWS_WITH(read_bench({"charge.2.center=[0.475, 0.2]"}), Catch::Contains("charge.2") && Catch::Contains("not inside the rock"));
  CHECK_THROWS_WITH(read_bench({"charge.1.center=[0.135, 0.2]"}), Catch::Contains("charge.1") && Catch::Contains("overlaps that of charge.0"));
  CHECK_THROWS_WITH(read_bench({"charge.1.initiation_time=-1e-5"}), Catch::Contains("charge.1.initiation_time"));
  CHECK_THROWS_WITH(read_bench({"gas.explosive.preset=\"C4\""}), Catch::Contains("gas.explosive") && Catch::Contains("C4"));
  CHECK_THROWS_WITH(read_bench({"charge.0.initiation_point=[0.12, 0.2]"}), Catch::Contains("charge.0.initiation_point"));
  CHECK_THROWS_WITH(read_bench({"charge.0.initiation=\"point\"", "charge.0.initiation_point=[0.2, 0.2]"}),
                    Catch::Contains("charge.0.initiation_point") && Catch::Contains("outside the charge"));
  CHECK_THROWS_WITH(read_bench({"rock.mesh.shape=\"rectangle\""}), Catch::Contains("rectangle_with_holes"));
  CHECK_THROWS_WITH(read_bench({"charge.0.radius=0.0005"}), Catch::Contains("charge.0.radius") && Catch::Contains("half a gas cell"));
  CHECK_THROWS_WITH(read_bench({"gas.transport=\"paper\""}), Catch::Contains("gas.transport"));
}

TEST_CASE("A shrunk bench fires each charge at its delay, and a restart before a charge fires ends byte for byte",
          "[long][app][charges][restart]") {
  const fs::path a = fresh_dir("bench_a"), b = fresh_dir("bench_b");
  std::ostringstream log;
  const app::Case ca = read_bench(small_bench(a));
  app::run_coupled_case(ca, log);
  const auto cols = csv_columns(a / "charges.csv");
  const std::vector<double>& t = cols.at("time_s");
  const double ambient = ca.gas.eos.pressure(ca.gas.ambient.density, ca.gas.ambient.internal_energy);
  for (int k = 0; k < 3; ++k) {
    const std::vector<double>& p = cols.at("charge" + std::to_string(k) + "_pressure_Pa");
    const std::vector<double>& e = cols.at("charge" + std::to_string(k) + "_energy_J_per_m");
    const double t0 = ca.coupling.charges[k].initiation_time;
    double before = 0, after = 0, released_before = 0;
    for (size_t r = 0; r < t.size(); ++r) {
      if (t[r] < t0) {
        before = std::fmax(before, std::fabs(p[r] / ambient - 1));
        released_before = std::fmax(released_before, e[r]);
      } else {
        after = std::fmax(after, p[r]);
      }
    }
    CHECK(released_before == 0.0);
    std::printf("bench: charge %d (at %.0f us): largest |p / p_ambient - 1| before %.2e, peak after %.4e Pa, released "
                "%.4e J/m\n", k, 1e6 * t0, before, after, e.back());
    CHECK(before < 0.05);       // only the neighbours' waves moving its hole wall
    CHECK(after > 1e3 * ambient);
    CHECK(e.back() > 0);
  }
  // Killed after the 20 us checkpoint (charge 2 has not fired there), restarted: the same bytes.
  const long steps = std::lround(csv_columns(a / "coupling_series.csv").at("step").back());
  std::vector<std::string> killed = small_bench(b);
  killed.push_back("time.max_steps=" + std::to_string(steps - 3));
  app::run_coupled_case(read_bench(killed), log);
  app::RunOptions restart;
  restart.restart = true;
  app::run_coupled_case(read_bench(small_bench(b)), log, restart);
  int identical = 0;
  for (const char* f : {"charges.csv", "coupling_series.csv", "rock_series.csv", "checkpoint.bin", "summary.txt"}) {
    INFO(f);
    const std::string fa = file_bytes(a / f), fb = file_bytes(b / f);
    CHECK(fa.size() > 0);
    CHECK(fa == fb);
    identical += fa == fb;
  }
  std::printf("bench restart: %ld steps, killed at step %ld, restarted from the 20 us checkpoint (charge 2 fires at 25 "
              "us): %d of 5 files identical\n", steps, steps - 3, identical);
}

TEST_CASE("The jointed bench reads its joint sets, heterogeneity and in-situ stress, and bad joint-set keys give one clear error",
          "[app][rock][jointset][bad]") {
  const std::string jointed = std::string(BLASTSIM_EXAMPLES_DIR) + "/jointed_bench/jointed_bench.toml";
  auto read_jointed = [&](const std::vector<std::string>& overrides) {
    return app::read_case(app::load_input(jointed, overrides));
  };
  const app::Case c = read_jointed({});
  REQUIRE(c.rock.model.joint_sets.size() == 2);
  CHECK_FALSE(c.rock.model.joint_sets[0].open);
  CHECK(c.rock.model.joint_sets[0].properties.tensile_strength == 1.0e6);
  CHECK(c.rock.model.joint_sets[0].properties.friction_angle == c.rock.model.material.friction_angle);
  CHECK(c.rock.model.joint_sets[1].open);
  CHECK(c.rock.model.joint_sets[1].spacing == 0.08);
  CHECK(c.rock.model.heterogeneity.has_value());
  // Its in-situ stress: 5 MPa along the row, held where the viscous boundaries cut the rock mass.
  REQUIRE(c.rock.model.in_situ.has_value());
  CHECK(c.rock.model.in_situ->stress.at_reference[0] == -5.0e6);
  CHECK(c.rock.model.in_situ->held_boundaries == std::vector<std::string>{"bottom", "left", "right"});
  CHECK(c.probes.rock_points.size() == 4);
  CHECK_THROWS_WITH(read_jointed({"rock.joint_set.0.spacing=0.001"}), Catch::Contains("rock.joint_set.0.spacing"));
  CHECK_THROWS_WITH(read_jointed({"rock.joint_set.0.angle=200"}), Catch::Contains("rock.joint_set.0.angle"));
  CHECK_THROWS_WITH(read_jointed({"rock.joint_set.0.persistence=1.5"}), Catch::Contains("rock.joint_set.0.persistence"));
  CHECK_THROWS_WITH(read_jointed({"rock.joint_set.1.persistence=0.5"}), Catch::Contains("rock.joint_set.1.trace_length"));
  CHECK_THROWS_WITH(read_jointed({"rock.joint_set.0.trace_length=0.002"}),
                    Catch::Contains("rock.joint_set.0.trace_length"));
  CHECK_THROWS_WITH(read_jointed({"rock.joint_set.1.cohesion=1e6"}),
                    Catch::Contains("rock.joint_set.1.cohesion") && Catch::Contains("open"));
  CHECK_THROWS_WITH(read_jointed({"rock.joint_set.0.initial_aperture=1e-4"}),
                    Catch::Contains("rock.joint_set.0.initial_aperture"));
  CHECK_THROWS_WITH(read_jointed({"rock.joint_set.1.initial_aperture=1e-4"}),
                    Catch::Contains("rock.joint_set.1.initial_aperture") && Catch::Contains("crack_gas"));
  CHECK_THROWS_WITH(read_jointed({"rock.joint_set.0.dip=10"}), Catch::Contains("rock.joint_set.0.dip"));
}
