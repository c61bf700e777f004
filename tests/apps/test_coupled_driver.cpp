//! \file test_coupled_driver.cpp
//! \brief Driver on coupled gas-rock cases: the bundled single-hole file (small) runs, writes the gas, rock and
//! coupling files, closes its energy budget; bad coupled input gives one clear error.
#include "blastsim/core/error.hpp"
#include "case_input.hpp"
#include "catch.hpp"
#include "coupled_run.hpp"
#include "temp_files.hpp"

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

namespace fs = std::filesystem;
using namespace blastsim;
using blastsim::testing::fresh_dir;
using blastsim::testing::first_line;

namespace {
const std::string example = std::string(BLASTSIM_EXAMPLES_DIR) + "/single_hole/single_hole.toml";

//! The bundled single-hole case shrunk: a 150 mm disc with a 20 mm hole on 60 x 60 cells, 30 us.
std::vector<std::string> small_case(const fs::path& out) {
  return {"domain.nx=60", "domain.ny=60", "domain.x_min=-0.18", "domain.x_max=0.18", "domain.y_min=-0.18",
          "domain.y_max=0.18", "gas.region.0.radius=0.03", "rock.mesh.radius=0.15", "rock.mesh.hole_radius=0.02",
          "rock.mesh.element_size=0.01", "monitor.region.0.radius=0.15", "time.end=3e-5", "output.interval=1.5e-5",
          "output.monitor_interval=5", "output.directory=\"" + out.string() + "\""};
}

//! Columns of the last row of a CSV file by header name.
std::map<std::string, double> last_row(const fs::path& p) {
  std::ifstream in(p);
  std::string header, line, last;
  std::getline(in, header);
  while (std::getline(in, line))
    if (!line.empty()) last = line;
  std::map<std::string, double> row;
  std::stringstream h(header), v(last);
  std::string name, value;
  while (std::getline(h, name, ',') && std::getline(v, value, ',')) row[name] = std::stod(value);
  return row;
}
}  // namespace

TEST_CASE("Driver runs a coupled case: gas, rock and coupling files; the energy budget closes", "[app][coupled]") {
  const fs::path out = fresh_dir("coupled");
  const app::CoupledCaseConfig c = app::read_coupled_case(app::load_input(example, small_case(out)));
  std::ostringstream log;
  app::run_coupled_case(c, log);
  INFO(log.str());
  for (const char* f : {"coupling_series.csv", "gas_totals.csv", "rock_series.csv", "point_hole.csv"}) CHECK(fs::exists(out / f));
  if (c.gas.vtk) {
    for (const char* f : {"gas.pvd", "rock.pvd", "joints.pvd", "gas_000002.vti", "rock_000002.vtu", "joints_000002.vtu"})
      CHECK(fs::exists(out / f));
  }
  CHECK(first_line(out / "coupling_series.csv").rfind("step,time_s,gas_mass_kg_per_m,", 0) == 0);
  const std::map<std::string, double> row = last_row(out / "coupling_series.csv");
  const double work = row.at("gas_work_on_rock_J_per_m"), residual = row.at("budget_residual_J_per_m");
  std::printf("coupled driver: t = %.3e s, gas work on the rock %.4e J/m, budget residual %.3e J/m (%.2f %% of the "
              "work), broken joints %.0f, gas inside the rock radius %.4e kg/m\n", row.at("time_s"), work, residual,
              100 * residual / work, row.at("broken_joints"), row.at("inside_rock_mass_kg_per_m"));
  CHECK(row.at("time_s") == Approx(3e-5));
  CHECK(work > 0);
  // The budget (S4 of validation.md) against the energy that crossed the interface: within 10 % on this
  // coarse grid (the hole is 3 cells across in radius).
  CHECK(std::fabs(residual) < 0.10 * work);
  CHECK(row.at("inside_rock_mass_kg_per_m") > 0);
}

TEST_CASE("Bad coupled input gives one clear error naming the key", "[app][coupled][bad]") {
  auto read = [](const std::vector<std::string>& overrides) {
    return app::read_coupled_case(app::load_input(example, overrides));
  };
  CHECK(app::case_kind(app::load_input(example, {})) == app::CaseKind::coupled);
  CHECK_THROWS_WITH(read({"rock.pressure.0.boundary=\"hole\"", "rock.pressure.0.pressure=1e6"}),
                    Catch::Contains("rock.pressure"));
  CHECK_THROWS_WITH(read({"monitor.region.0.shape=\"ring\""}), Catch::Contains("monitor.region.0.shape"));
  CHECK_THROWS_WITH(read({"monitor.region.0.name=\"a b\""}), Catch::Contains("monitor.region"));
  CHECK_THROWS_WITH(read({"rock.youngs_modulus=0"}), Catch::Contains("rock.youngs_modulus"));
  CHECK_THROWS_WITH(read({"gas.courant=2"}), Catch::Contains("gas.courant"));
  // A fixed dt above the rock's stable step is refused at the start, naming the stable value.
  std::ostringstream log;
  const fs::path out = fresh_dir("coupled_bad");
  std::vector<std::string> o = small_case(out);
  o.push_back("time.dt=1e-5");
  CHECK_THROWS_WITH(app::run_coupled_case(read(o), log), Catch::Contains("time.dt"));
}

namespace {
std::string file_bytes(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}
}  // namespace

TEST_CASE("A coupled run killed and restarted from its checkpoint ends byte for byte like the uninterrupted run",
          "[app][coupled][restart]") {
  const fs::path a = fresh_dir("restart_a"), b = fresh_dir("restart_b");
  auto config = [&](const fs::path& out, std::vector<std::string> extra) {
    std::vector<std::string> o = small_case(out);
    o.push_back("time.end=4e-5");
    o.push_back("output.interval=2e-5");  // snapshots, and checkpoints, at 0, 20 and 40 us
    o.insert(o.end(), extra.begin(), extra.end());
    return app::read_coupled_case(app::load_input(example, o));
  };
  std::ostringstream log;
  app::run_coupled_case(config(a, {}), log);
  const long total_steps = std::lround(last_row(a / "coupling_series.csv").at("step"));
  // The "killed" run stops 3 steps before the end, well after the 20 us checkpoint: it has written rows and
  // files past the checkpoint that the restart must drop.
  app::run_coupled_case(config(b, {"time.max_steps=" + std::to_string(total_steps - 3)}), log);
  REQUIRE(last_row(b / "coupling_series.csv").at("time_s") < 4e-5);
  app::RunOptions restart;
  restart.restart = true;
  app::run_coupled_case(config(b, {}), log, restart);
  INFO(log.str());
  std::vector<std::string> files{"coupling_series.csv", "rock_series.csv", "gas_totals.csv", "point_hole.csv", "checkpoint.bin"};
  if (fs::exists(a / "gas_000002.vti"))
    files.insert(files.end(), {"gas.pvd", "rock.pvd", "joints.pvd", "gas_000002.vti", "rock_000002.vtu", "joints_000002.vtu"});
  for (const std::string& f : files) {
    INFO(f);
    const std::string fa = file_bytes(a / f), fb = file_bytes(b / f);
    CHECK(fa.size() > 0);
    const bool identical = fa == fb;
    CHECK(identical);
  }
  std::printf("restart: %ld steps; killed at step %ld, restarted from the 20 us checkpoint; %zu files identical\n",
              total_steps, total_steps - 3, files.size());
  // A checkpoint of another case is refused, naming the difference.
  CHECK_THROWS_WITH(app::run_coupled_case(config(b, {"gas.courant=0.2"}), log, restart), Catch::Contains("gas.courant"));
}
