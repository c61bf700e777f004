//! \file test_reliability.cpp
//! \brief The driver's promises for the newer features, one class each: no non-finite value is written (a fit
//! that cannot be made is an empty field), a restart changes nothing until it is accepted and a finished run's
//! restart changes nothing at all, physical input checks (holes, charges, delays, gas states, analysis
//! regions), uniform checkpoint value checks, messages that name the key the user set, and a seeded fuzz over
//! the newer tables that holds the exit-code contract with every output finite.
#include "blastsim/core/error.hpp"
#include "blastsim/core/output_files.hpp"
#include "driver_runs.hpp"

#include <cmath>
#include <limits>
#include <random>

namespace fs = std::filesystem;
using namespace blastsim::testing;

namespace {

//! The small coupled case of driver_runs.hpp with one ANFO charge (constant volume, at t = 0) in the hole, which
//! Gmsh cuts from the disc (shape "disc_with_holes").
std::string charge_text(const fs::path& out, double end) {
  std::string s = coupled_text(out, end);
  const std::string region = "[[gas.region]]\nshape = \"circle\"\ncenter = [0.0, 0.0]\nradius = 0.024\ndensity = 163.0\n"
                             "internal_energy = 4.29e5\n";
  s.replace(s.find(region), region.size(), "[gas.explosive]\npreset = \"ANFO\"\n");
  const std::size_t mesh = s.find("[rock.mesh]");
  s.replace(mesh, s.find("[time]") - mesh,
            "[rock.mesh]\nshape = \"disc_with_holes\"\ncenter = [0.0, 0.0]\nradius = 0.06\nelement_size = 0.008\n");
  s += "[[charge]]\ncenter = [0.0, 0.0]\nhole_radius = 0.02\nradius = 0.01\n";
  return s;
}

int refused_count = 0;  //!< check_refused() calls so far

//! Runs `input` with `args` and checks exit 2 with a message that names `what`.
void check_refused(const fs::path& input, const std::vector<std::string>& args, const std::string& what) {
  ++refused_count;
  std::string joined;
  for (const std::string& a : args) joined += a + " ";
  const Run r = run_driver(input, args, "refused");
  INFO(joined << "-> exit " << r.status << ": " << r.err);
  CHECK(r.status == 2);
  CHECK(r.err.find(what) != std::string::npos);
}

}  // namespace

TEST_CASE("Reliability: a value that is not finite is never written, and a fit that cannot be made is an empty "
          "field", "[app][reliability][finite]") {
  using blastsim::CsvRecord;
  // The record every CSV series writes its rows through refuses NaN and infinities, naming the column.
  for (double bad : {std::nan(""), std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity()}) {
    CsvRecord row(CsvRecord::Mode::row);
    row.integer("step", 3);
    CHECK_THROWS_AS(row.real("strain_J_per_m", bad), blastsim::NonFiniteValue);
    CHECK_THROWS_WITH(row.real("strain_J_per_m", bad), Catch::Contains("column strain_J_per_m"));
  }
  CsvRecord ok(CsvRecord::Mode::row);
  ok.integer("step", 3).real("x", 0.5, 3).real_if(false, "fit", std::nan("")).real("y", 2.0, 2);
  CHECK(ok.text() == "3,5.000e-01,,2.00e+00");
  CsvRecord names(CsvRecord::Mode::header);
  names.integer("step", 0).real("x", std::nan("")).real_if(false, "fit", 0.0);
  CHECK(names.text() == "step,x,fit");
  // The intact disc of the small coupled case is one piece: too few fragments for either fit.
  const fs::path dir = fresh_dir("reliability_finite");
  const fs::path out = dir / "out";
  const Run r = run_driver(write_input(dir, "case.toml", coupled_text(out, 1.0e-5)), {}, "finite");
  INFO(r.err);
  REQUIRE(r.status == 0);
  CHECK(csv_all_finite(out));
  std::ifstream sizes(out / "size_distribution.csv");
  std::string header, row;
  std::getline(sizes, header);
  std::getline(sizes, row);
  CHECK(header == "sieve_size_m,passing,swebrec_fit,rosin_rammler_fit");
  CHECK(row.size() > 2);
  CHECK(row.substr(row.size() - 2) == ",,");  // both fits empty
  std::printf("reliability: NaN, +inf and -inf refused by the CSV record; an unfitted size distribution row reads "
              "'%s'\n", row.c_str());
}

TEST_CASE("Reliability: a restart changes nothing until it is accepted, and a finished run's restart changes "
          "nothing", "[app][reliability][restart]") {
  const fs::path dir = fresh_dir("reliability_restart");
  const fs::path out = dir / "out";
  const fs::path input = write_input(dir, "case.toml", charge_text(out, 1.5e-5));
  REQUIRE(run_driver(input, {}, "rr_base").status == 0);
  const auto finished = folder_bytes(out);
  REQUIRE(finished.count("charges.csv") == 1);
  // The same end: nothing to do, every file as it was (a default written out is the same input).
  Run r = run_driver(input, {"--restart", "gas.viscosity_linear=0.25", "crack_gas.enabled=false"}, "rr_same");
  INFO(r.err);
  CHECK(r.status == 0);
  CHECK(folder_bytes(out) == finished);
  // A shortened CSV read late in the checkpoint (charges.csv): refused, and no other file was cut back.
  const std::vector<char> charges = read_bytes(out / "charges.csv");
  write_bytes(out / "charges.csv", std::vector<char>(charges.begin(), charges.begin() + 40));
  auto before = folder_bytes(out);
  r = run_driver(input, {"--restart", "time.end=3e-5"}, "rr_short");
  CHECK(r.status == 2);
  CHECK(r.err.find("charges.csv") != std::string::npos);
  CHECK(folder_bytes(out) == before);
  write_bytes(out / "charges.csv", charges);
#if defined(BLASTSIM_HAVE_VTK)
  {  // a snapshot that a collection names, deleted: refused, nothing changed
    const fs::path vtk_out = dir / "vtk";
    const fs::path vtk_input = write_input(dir, "vtk.toml", coupled_text(vtk_out, 1.5e-5));
    REQUIRE(run_driver(vtk_input, {"output.vtk=true"}, "rr_vtk").status == 0);
    fs::remove(vtk_out / "rock_000001.vtu");
    before = folder_bytes(vtk_out);
    r = run_driver(vtk_input, {"output.vtk=true", "--restart", "time.end=3e-5"}, "rr_snapshot");
    INFO(r.err);
    CHECK(r.status == 2);
    CHECK(r.err.find("rock_000001.vtu") != std::string::npos);
    CHECK(folder_bytes(vtk_out) == before);
  }
#endif
  std::printf("reliability: a finished run's restart left its %zu files unchanged; a shortened charges.csv (and, "
              "with VTK, a deleted snapshot) refused with the folder unchanged\n", finished.size());
}

TEST_CASE("Reliability: holes, charges, delays, gas states and analysis regions are checked against the case",
          "[app][reliability][input]") {
  const fs::path dir = fresh_dir("reliability_input");
  const fs::path out = dir / "out";
  const fs::path coupled = write_input(dir, "coupled.toml", coupled_text(out, 1.0e-5));
  const fs::path charged = write_input(dir, "charged.toml", charge_text(out, 1.0e-5));
  // A hole far smaller than the elements (Gmsh or the ring mesher cannot resolve it).
  check_refused(coupled, {"rock.mesh.hole_radius=0.001"}, "rock.mesh.hole_radius");
  // A delay the step cannot resolve, and a point initiation at a detonation velocity no explosive has.
  check_refused(charged, {"charge.0.initiation_time=1e-18"}, "charge.0.initiation_time");
  check_refused(charged, {"charge.0.initiation=\"point\"", "gas.explosive.detonation_velocity=1e-9"},
                "gas.explosive.detonation_velocity");
  // Gas regions: outside the domain, and a products state without a positive pressure (far above rho0, at a
  // specific energy below the JWL reference curve's).
  check_refused(coupled, {"gas.region.0.center=[10.0, 10.0]"}, "gas.region.0");
  std::string products = charge_text(out, 1.0e-5);
  products += "[[gas.region]]\nshape = \"circle\"\ncenter = [0.0, 0.0]\nradius = 0.005\nmaterial = \"products\"\n"
              "density = 1.0e5\ninternal_energy = 1.0\n";
  check_refused(write_input(dir, "products.toml", products), {}, "gas.region.0");
  // Analysis regions outside the rock (a 0.12 m disc).
  std::string hole = coupled_text(out, 1.0e-5) + "[[analysis.hole]]\ncenter = [5.0, 5.0]\nradius = 0.02\n";
  check_refused(write_input(dir, "hole.toml", hole), {}, "analysis.hole.0.center");
  check_refused(coupled, {"analysis.damage_ring_width=1.0"}, "analysis.damage_ring_width");
  // A charge on a mesh file with no hole at its place (the bundled unit square of two triangles).
  std::string file = charge_text(out, 1.0e-5);
  const std::string mesh = file.substr(file.find("[rock.mesh]"), file.find("[time]") - file.find("[rock.mesh]"));
  file.replace(file.find(mesh), mesh.size(),
               "[rock.mesh]\nshape = \"file\"\nfile = \"" + std::string(BLASTSIM_FDEM_DATA_DIR) + "/square.msh\"\n");
  for (const char* k : {"x_min = -0.075", "y_min = -0.075"}) file.replace(file.find(k), std::string(k).size(), std::string(k).substr(0, 8) + "-0.2");
  for (const char* k : {"x_max = 0.075", "y_max = 0.075"}) file.replace(file.find(k), std::string(k).size(), std::string(k).substr(0, 8) + "1.2");
  file.replace(file.find("[rock]\n"), 7, "[rock]\njoint_penalty_factor = 1000.0\n");  // metre-sized elements
  const std::string charge = "center = [0.0, 0.0]\nhole_radius = 0.02\nradius = 0.01";
  file.replace(file.find(charge), charge.size(), "center = [0.3, 0.6]\nhole_radius = 0.05\nradius = 0.05");
  const std::size_t blasthole = file.find("[monitor.blasthole]");
  file.erase(blasthole, file.find("[[probe.point]]") - blasthole);
  check_refused(write_input(dir, "file.toml", file), {}, "charge.0: no hole");
  std::printf("reliability: %d inputs given to the driver, each to be refused with exit 2 naming the key (hole, "
              "delay, detonation velocity, two gas regions, analysis hole, ring width, charge without a hole)\n",
              refused_count);
}

TEST_CASE("Reliability: forged checkpoint values (snapshot index, CSV size, step count, NaN) are refused naming the "
          "record", "[app][reliability][checkpoint]") {
  const fs::path dir = fresh_dir("reliability_ckpt");
  const fs::path out = dir / "out";
  const fs::path input = write_input(dir, "case.toml", coupled_text(out, 1.5e-5));
  REQUIRE(run_driver(input, {"time.end=1.0e-5"}, "rc_base").status == 0);  // a checkpoint before the end
  const fs::path ckpt = out / "checkpoint.bin";
  const std::vector<char> good = read_bytes(ckpt);
  int forged = 0;
  auto forge = [&](const std::string& record, const void* value, std::size_t bytes) {
    ++forged;
    std::vector<char> bad = good;
    std::memcpy(&bad[record_data(bad, record)], value, bytes);
    reseal(bad);
    write_bytes(ckpt, bad);
    const auto before = folder_bytes(out);
    const Run r = run_driver(input, {"--restart"}, "rc_forged");
    INFO(record << ": exit " << r.status << ": " << r.err);
    CHECK(r.status == 2);
    CHECK(r.err.find(record) != std::string::npos);
    CHECK(folder_bytes(out) == before);
  };
  const int near_wrap = 2147483600;
  forge("out.rock.index", &near_wrap, sizeof near_wrap);
  forge("out.gas.snapshot_index", &near_wrap, sizeof near_wrap);
  const std::uint64_t zero = 0;
  forge("out.coupling.csv_size", &zero, sizeof zero);
  const long long huge = 4000000000000000000LL;
  forge("gas.steps", &huge, sizeof huge);
  const double nan = std::nan("");
  forge("out.blasthole.events", &nan, sizeof nan);
  forge("out.coupling.initial", &nan, sizeof nan);
  forge("gas.time", &nan, sizeof nan);
  forge("ibm.transitions", &nan, sizeof nan);    // a ledger of structs of doubles
  forge("gas.outflow_ledger", &nan, sizeof nan);
  forge("rock.ledger.work", &nan, sizeof nan);
  write_bytes(ckpt, good);
  CHECK(run_driver(input, {"--restart", "time.end=1.5e-5"}, "rc_good").status == 0);
  std::printf("reliability: %d forged checkpoint values, each to be refused with exit 2 naming the record, the "
              "folder unchanged\n", forged);
}

TEST_CASE("Reliability: messages name the key the user set and list every key a table allows",
          "[app][reliability][messages]") {
  const fs::path dir = fresh_dir("reliability_messages");
  const fs::path out = dir / "out";
  const fs::path charged = write_input(dir, "charged.toml", charge_text(out, 1.0e-5));
  // A JWL set with a very large C and a small w: its CJ state is no explosive's; the message names the set.
  std::string jwl = charge_text(out, 1.0e-5);
  jwl.replace(jwl.find("preset = \"ANFO\"\n"), 15,
              "A = 203.582e9\nB = 2.973e9\nC = 1e13\nR1 = 6.651\nR2 = 1.127\nw = 0.02\nrho0 = 800.0\n");
  Run r = run_driver(write_input(dir, "jwl.toml", jwl), {}, "msg_jwl");
  INFO(r.err);
  CHECK(r.status == 2);
  CHECK(r.err.find("the JWL set") != std::string::npos);
  CHECK(r.err.find("detonation_velocity = inf") == std::string::npos);
  // A number beyond a double on the command line.
  r = run_driver(charged, {"time.end=1e400"}, "msg_range");
  CHECK(r.status == 2);
  CHECK(r.err.find("outside the range of a double") != std::string::npos);
  // An empty viscous boundary table: what is missing, not "(one of )".
  std::string viscous = coupled_text(out, 1.0e-5);
  viscous.insert(viscous.find("[rock.mesh]"), "[[rock.viscous_boundary]]\n");
  r = run_driver(write_input(dir, "viscous.toml", viscous), {}, "msg_viscous");
  CHECK(r.status == 2);
  CHECK(r.err.find("rock.viscous_boundary.0.boundary") != std::string::npos);
  CHECK(r.err.find("(one of )") == std::string::npos);
  // Unknown keys: the list of allowed keys holds those read only in some cases.
  r = run_driver(charged, {"charge.0.typo=1"}, "msg_charge");
  CHECK(r.err.find("initiation_point") != std::string::npos);
  r = run_driver(charged, {"gas.explosive.typo=1"}, "msg_explosive");
  CHECK(r.err.find("rho0") != std::string::npos);
  std::string probe = coupled_text(out, 1.0e-5) + "[[probe.rock_point]]\nname = \"p\"\nposition = [0.03, 0.0]\ntypo = 1\n";
  r = run_driver(write_input(dir, "probe.toml", probe), {}, "msg_probe");
  CHECK(r.err.find("until") != std::string::npos);
}

TEST_CASE("Reliability: a seeded fuzz over the newer tables keeps the exit-code contract, every output finite",
          "[app][reliability][fuzz]") {
  const fs::path dir = fresh_dir("reliability_fuzz");
  const std::vector<std::string> keys{
      "charge.0.center",          "charge.0.hole_radius",        "charge.0.radius",
      "charge.0.initiation_time", "charge.0.initiation",         "charge.0.initiation_point",
      "gas.explosive.detonation_energy", "gas.explosive.detonation_velocity", "crack_gas.enabled",
      "crack_gas.residual_aperture", "crack_gas.friction_factor", "analysis.oversize",
      "analysis.damage_ring_width", "analysis.crushed_fraction", "rock.contact",
      "coupling.gas_load",        "rock.mesh.hole_radius",      "rock.mesh.element_size"};
  const std::vector<std::string> values{"0", "-1", "1e308", "1e-300", "nan", "inf", "1e400", "true", "false",
                                        "0.01", "0.02", "3e-6", "2.0e9", "[0.0, 0.0]", "[0.05, 0.0]", "[]",
                                        "\"point\"", "\"faces\"", "\"constant_volume\"", "1e-9"};
  std::mt19937_64 rng(20261203);
  int counts[4] = {0, 0, 0, 0};  // exit 0, 2, 3, other
  for (int k = 0; k < 24; ++k) {
    const fs::path out = dir / ("run" + std::to_string(k));
    const fs::path input = write_input(dir, "case" + std::to_string(k) + ".toml", charge_text(out, 6.0e-6));
    const auto [args, joined] = random_overrides(rng, keys, values);
    const Run r = run_driver(input, args, "fuzz_new");
    INFO(joined << "-> exit " << r.status << ": " << r.err);
    CHECK((r.status == 0 || r.status == 2 || r.status == 3));
    if (r.status != 0) CHECK(!r.err.empty());
    if (r.status != 2 && fs::exists(out)) CHECK(csv_all_finite(out));
    ++counts[r.status == 0 ? 0 : r.status == 2 ? 1 : r.status == 3 ? 2 : 3];
  }
  std::printf("reliability fuzz: 24 override sets over the newer tables: %d ran (exit 0), %d refused (exit 2), %d "
              "unstable (exit 3), %d other; no CSV with a non-finite value\n", counts[0], counts[1], counts[2], counts[3]);
}

namespace {
//! Runs --check on every bundled example input whose file name does (`full`) or does not end in "_full.toml";
//! returns how many passed.
int check_examples(bool full) {
  int checked = 0;
  for (const fs::directory_entry& d : fs::directory_iterator(BLASTSIM_EXAMPLES_DIR)) {
    if (!d.is_directory()) continue;
    for (const fs::directory_entry& e : fs::directory_iterator(d.path())) {
      const std::string name = e.path().filename().string();
      if (e.path().extension() != ".toml") continue;
      const bool is_full = name.size() > 10 && name.compare(name.size() - 10, 10, "_full.toml") == 0;
      if (is_full != full) continue;
      const Run r = run_driver(e.path(), {"--check"}, "example_check");
      INFO(e.path().string() << ": " << r.err);
      CHECK(r.status == 0);
      checked += r.status == 0;
    }
  }
  return checked;
}
}  // namespace

TEST_CASE("Reliability: every bundled example input passes --check", "[app][reliability][examples][heavy]") {
  // The examples are what a user runs first; a key renamed or a bound tightened must not leave one of them
  // refused. --check reads and validates the whole case, the rock model built (mesh, cracks, joints, strengths,
  // boundary groups, probes, charges' holes) but not relaxed, without running it. The full-size inputs
  // (*_full.toml: a third of a million triangles, half a minute to mesh) are the long tier's.
  const int checked = check_examples(false);
  std::printf("Reliability: %d example inputs pass --check\n", checked);
  CHECK(checked >= 9);
}

TEST_CASE("Reliability: the full-size example inputs pass --check", "[app][reliability][examples][long]") {
  const int checked = check_examples(true);
  std::printf("Reliability: %d full-size example inputs pass --check\n", checked);
  CHECK(checked >= 1);
}
