//! \file test_coupled_driver.cpp
//! \brief Driver on coupled gas-rock cases: the bundled single-hole file (small) runs, writes the gas, rock and
//! coupling files, closes its energy budget; bad coupled input gives one clear error.
#include "blastsim/core/error.hpp"
#include "case.hpp"
#include "catch.hpp"
#include "run_loop.hpp"
#include "temp_files.hpp"

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>

namespace fs = std::filesystem;
using namespace blastsim;
using blastsim::testing::csv_columns;
using blastsim::testing::file_bytes;
using blastsim::testing::fresh_dir;
using blastsim::testing::first_line;

namespace {
const std::string single_hole_toml = std::string(BLASTSIM_EXAMPLES_DIR) + "/single_hole/single_hole.toml";

//! The bundled single-hole case shrunk: a 150 mm disc with a 20 mm hole on 60 x 60 cells, 30 us (CSV output
//! only in a build without VTK, such as the sanitizer preset's).
std::vector<std::string> small_case(const fs::path& out) {
  return {
#if !defined(BLASTSIM_HAVE_VTK)
          "output.vtk=false",
#endif
          "domain.nx=60", "domain.ny=60", "domain.x_min=-0.18", "domain.x_max=0.18", "domain.y_min=-0.18",
          "domain.y_max=0.18", "gas.region.0.radius=0.03", "rock.mesh.radius=0.15", "rock.mesh.hole_radius=0.02",
          "monitor.blasthole.outer_radius=0.15", "monitor.blasthole.hole_radius=0.02",
          "rock.mesh.element_size=0.01", "monitor.region.0.radius=0.15", "time.end=3e-5", "output.interval=1.5e-5",
          "output.monitor_interval=5", "output.directory=\"" + out.string() + "\"",
          // the example's rock probes, moved into this smaller disc (r = 0.03 to 0.13 m along 30 degrees)
          "probe.rock_point.0.position=[0.026, 0.015]", "probe.rock_point.1.position=[0.0433, 0.025]",
          "probe.rock_point.2.position=[0.0606, 0.035]", "probe.rock_point.3.position=[0.0779, 0.045]",
          "probe.rock_point.4.position=[0.0953, 0.055]", "probe.rock_point.5.position=[0.1126, 0.065]"};
}

//! Columns of the last row of a CSV file by header name (an empty field: NaN).
std::map<std::string, double> last_row(const fs::path& p) {
  std::ifstream in(p);
  std::string header, line, last;
  std::getline(in, header);
  while (std::getline(in, line))
    if (!line.empty()) last = line;
  std::map<std::string, double> row;
  std::stringstream h(header), v(last);
  std::string name, value;
  while (std::getline(h, name, ',') && std::getline(v, value, ',')) row[name] = value.empty() ? std::nan("") : std::stod(value);
  return row;
}
}  // namespace

TEST_CASE("Driver runs a coupled case: gas, rock and coupling files, and the energy budget closes", "[app][coupled]") {
  const fs::path out = fresh_dir("coupled");
  const app::Case c = app::read_case(app::load_input(single_hole_toml, small_case(out)));
  std::ostringstream log;
  app::run_coupled_case(c, log);
  INFO(log.str());
  for (const char* f : {"coupling_series.csv", "gas_totals.csv", "rock_series.csv", "point_hole.csv"}) CHECK(fs::exists(out / f));
  if (c.output.vtk) {
    // Snapshots at 0, 15 and 30 us (output.interval) and at 20 us (the example's output.times).
    for (const char* f : {"gas.pvd", "rock.pvd", "joints.pvd", "gas_000003.vti", "rock_000003.vtu", "joints_000003.vtu"})
      CHECK(fs::exists(out / f));
    CHECK_FALSE(fs::exists(out / "gas_000004.vti"));
  }
  CHECK(first_line(out / "coupling_series.csv").rfind("step,time_s,gas_mass_kg_per_m,", 0) == 0);
  const std::map<std::string, double> row = last_row(out / "coupling_series.csv");
  const double work = row.at("gas_work_on_rock_J_per_m"), residual = row.at("budget_residual_J_per_m");
  std::printf("coupled driver: t = %.3e s, gas work on the rock %.4e J/m, budget residual %.3e J/m (%.2f %% of the "
              "work), broken joints %.0f, gas inside the rock radius %.4e kg/m\n", row.at("time_s"), work, residual,
              100 * residual / work, row.at("broken_joints"), row.at("inside_rock_mass_kg_per_m"));
  CHECK(row.at("time_s") == Approx(3e-5));
  CHECK(work > 0);
  // The budget (S4 of docs/validation.md) against the energy that crossed the interface: within 10 % on this
  // coarse grid (the hole is 3 cells across in radius).
  CHECK(std::fabs(residual) < 0.10 * work);
  CHECK(row.at("inside_rock_mass_kg_per_m") > 0);
  // The analysis (docs/analysis.md): fragment files at every snapshot, PPV of the six probes, summary lines.
  for (const char* f : {"fragments_000000.csv", "fragments_000003.csv", "size_distribution.csv", "fragmentation_series.csv",
                        "rock_probes.csv", "ppv.csv"})
    CHECK(fs::exists(out / f));
  // The damage profile of the last snapshot (the run's end): its rings hold every joint of this disc with a hole,
  // so their broken lengths add up to the crack length the rock's series gives at the end (7 digits there).
  const std::map<std::string, std::vector<double>> profile = csv_columns(out / "damage_profile_000003.csv");
  REQUIRE(profile.count("broken_length_m") == 1);
  double profile_broken = 0;
  for (double b : profile.at("broken_length_m")) profile_broken += b;
  const double crack_length = last_row(out / "rock_series.csv").at("crack_length_m");
  std::printf("coupled driver: damage profile %zu rings, broken %.6e m; rock series crack length %.6e m\n",
              profile.at("broken_length_m").size(), profile_broken, crack_length);
  CHECK(profile.at("time_s").front() == Approx(3e-5));
  CHECK(std::fabs(profile_broken - crack_length) <= 1e-6 * crack_length + 1e-12);
  const std::map<std::string, double> frag = last_row(out / "fragmentation_series.csv");
  CHECK(frag.at("fragments") >= 1);
  CHECK(frag.at("hole0_cracked_radius_m") >= 0.02);  // at least the hole radius
  std::ifstream ppv(out / "ppv.csv");
  std::string line;
  int probes = 0;
  double first_ppv = 0;
  std::getline(ppv, line);
  while (std::getline(ppv, line))
    if (!line.empty() && probes++ == 0) {  // name,x_m,y_m,distance_from_hole0_m,ppv_m_per_s,...
      std::stringstream fields(line);
      std::string field;
      for (int k = 0; k < 5; ++k) std::getline(fields, field, ',');
      first_ppv = std::stod(field);
    }
  CHECK(probes == 6);
  CHECK(first_ppv > 0);  // the probe nearest the hole has moved
  std::ifstream summary(out / "summary.txt");
  const std::string text((std::istreambuf_iterator<char>(summary)), std::istreambuf_iterator<char>());
  CHECK(text.find("analysis of the rock") != std::string::npos);
  CHECK(text.find("PPV") != std::string::npos);
}

TEST_CASE("A pre-cut crack of the input is broken at the start and carries the blast gas along it", "[app][coupled]") {
  // The shrunk example with a [[rock.crack]] from the hole wall (r = 20 mm) to r = 100 mm along +x, standing open
  // by 0.1 mm (a channel: the hand-over is at 2 cells, 12 mm). Without it the intact rock holds the gas in the
  // hole for the first microseconds; with it the blast gas must run along the crack beyond the hole wall.
  const fs::path out = fresh_dir("coupled_cut"), input = out / "cut.toml";
  {
    fs::create_directories(out);
    std::ofstream f(input);
    f << file_bytes(single_hole_toml) << "\n[[rock.crack]]\nfrom = [0.02, 0.0]\nto = [0.1, 0.0]\ninitial_aperture = 1e-4\n";
  }
  const app::Case c = app::read_case(app::load_input(input.string(), small_case(out)));
  std::ostringstream log;
  app::run_coupled_case(c, log);
  INFO(log.str());
  CHECK(log.str().find("pre-cut cracks: 1 (") != std::string::npos);
  const auto wall = csv_columns(out / "wall_series.csv");
  const double front = wall.at("blast_gas_front_crack_radius_m").back();
  std::printf("pre-cut crack: blast gas front in the cracks %.4f m from the hole centre at %.1f us (hole wall 0.020 m, "
              "crack end 0.100 m)\n", front, 1e6 * wall.at("time_s").back());
  CHECK(front > 0.03);
  CHECK(front <= 0.1 + 0.01);
}

TEST_CASE("A coupled case's default Courant number follows its transport and gas load", "[app][coupled][input]") {
  auto read = [](const std::vector<std::string>& overrides) {
    return app::read_case(app::load_input(single_hole_toml, overrides));
  };
  auto echoed = [](const app::Case& c) {
    for (const app::EchoLine& e : c.echo)
      if (e.key == "gas.courant") return e.text;
    return std::string();
  };
  // The example sets no gas.courant: face forces with the conservative transport take that transport's number,
  // the paper's edge pressures or the paper's transport the paper's number; a given number is kept.
  const app::Case faces = read({"coupling.gas_load=\"faces\""});
  CHECK(faces.gas.courant == ibm::recommended_courant(cip::Transport::conservative, ibm::GasLoad::face_forces));
  CHECK(faces.gas.courant == cip::kConservativeCourant);
  CHECK(echoed(faces) == std::string("gas.courant = 0.4") + app::kDefaultMark);
  const app::Case edges = read({"coupling.gas_load=\"edges\""});
  CHECK(edges.gas.courant == cip::kPaperCourant);
  CHECK(echoed(edges) == std::string("gas.courant = 0.1") + app::kDefaultMark);
  // Paid edge pressures pay the rock's work over the substeps, as face forces do: the transport's number.
  const app::Case paid = read({"coupling.gas_load=\"edges_paid\""});
  CHECK(paid.coupling.gas_load == ibm::GasLoad::edge_pressures_paid);
  CHECK(paid.gas.courant == cip::kConservativeCourant);
  CHECK(echoed(paid) == std::string("gas.courant = 0.4") + app::kDefaultMark);
  CHECK_THROWS_WITH(read({"coupling.gas_load=\"edge\""}), Catch::Contains("coupling.gas_load") && Catch::Contains("edges_paid"));
  CHECK(read({"coupling.gas_load=\"faces\"", "gas.transport=\"paper\""}).gas.courant == cip::kPaperCourant);
  const app::Case given = read({"coupling.gas_load=\"edges\"", "gas.courant=0.25"});
  CHECK(given.gas.courant == 0.25);
  CHECK(echoed(given) == "gas.courant = 0.25");
}

TEST_CASE("Bad coupled input gives one clear error naming the key", "[app][coupled][bad]") {
  auto read = [](const std::vector<std::string>& overrides) {
    return app::read_case(app::load_input(single_hole_toml, overrides));
  };
  CHECK(app::case_kind(app::load_input(single_hole_toml, {})) == app::CaseKind::coupled);
  // The example's six rock probes and its monitor region, removed by empty arrays of tables.
  CHECK(read({}).probes.rock_points.size() == 6);
  CHECK(read({"probe.rock_point=[]"}).probes.rock_points.empty());
  CHECK(read({"monitor.region=[]"}).monitor.regions.empty());
  CHECK_THROWS_WITH(read({"rock.pressure.0.boundary=\"hole\"", "rock.pressure.0.pressure=1e6"}),
                    Catch::Contains("rock.pressure"));
  CHECK_THROWS_WITH(read({"monitor.region.0.shape=\"ring\""}), Catch::Contains("monitor.region.0.shape"));
  CHECK_THROWS_WITH(read({"monitor.interval=1e-6"}), Catch::Contains("monitor.blasthole.interval"));
  CHECK_THROWS_WITH(read({"monitor.blasthole.outer_radius=0.01"}), Catch::Contains("monitor.blasthole.outer_radius"));
  CHECK_THROWS_WITH(read({"monitor.region.0.name=\"a b\""}), Catch::Contains("monitor.region"));
  CHECK_THROWS_WITH(read({"rock.youngs_modulus=0"}), Catch::Contains("rock.youngs_modulus"));
  CHECK_THROWS_WITH(read({"gas.courant=2"}), Catch::Contains("gas.courant"));
  CHECK_THROWS_WITH(read({"output.times=[2e-5, 1e-5]"}), Catch::Contains("ascending"));
  CHECK_THROWS_WITH(read({"rock.mesh.mesher=\"rings\"", "rock.mesh.shape=\"disc\""}), Catch::Contains("rock.mesh.mesher"));
  CHECK_THROWS_WITH(read({"analysis.oversize=0"}), Catch::Contains("analysis.oversize"));
  CHECK_THROWS_WITH(read({"analysis.min_fragment_triangles=0"}), Catch::Contains("analysis.min_fragment_triangles"));
  CHECK_THROWS_WITH(read({"rock.mesh.jitter=0.5"}), Catch::Contains("rock.mesh.jitter"));
  CHECK_THROWS_WITH(read({"rock.mesh.rotation=400"}), Catch::Contains("rock.mesh.rotation"));
  CHECK(read({"rock.mesh.rotation=30"}).rock.model.mesh.rotation == Approx(M_PI / 6).epsilon(1e-15));
  CHECK(read({}).rock.model.mesh.rotation == 0.0);
  // Gmsh's algorithm: the isotropic Delaunay mesh unless the earlier frontal one is asked for.
  CHECK(read({}).rock.model.mesh.algorithm == fdem::GmshAlgorithm::delaunay);
  CHECK(read({"rock.mesh.algorithm=\"frontal\""}).rock.model.mesh.algorithm == fdem::GmshAlgorithm::frontal);
  CHECK_THROWS_WITH(read({"rock.mesh.algorithm=\"voronoi\""}),
                    Catch::Contains("rock.mesh.algorithm") && Catch::Contains("frontal"));
  // Mesh realisations: Gmsh's own mesh unless one is asked for; a negative one is refused.
  CHECK(read({}).rock.model.mesh.realisation == 0u);
  CHECK(read({"rock.mesh.realisation=3"}).rock.model.mesh.realisation == 3u);
  CHECK_THROWS_WITH(read({"rock.mesh.realisation=-1"}),
                    Catch::Contains("rock.mesh.realisation = -1") && Catch::Contains(">= 0"));
  CHECK_THROWS_WITH(read({"rock.mesh.realisation=1.5"}), Catch::Contains("rock.mesh.realisation"));
  CHECK_THROWS_WITH(read({"probe.rock_point.1.name=\"r010\""}), Catch::Contains("probe.rock_point.1.name"));
  CHECK_THROWS_WITH(read({"analysis.damage_ring_width=-0.1"}), Catch::Contains("analysis.damage_ring_width"));
  CHECK_THROWS_WITH(read({"analysis.crushed_fraction=0"}), Catch::Contains("analysis.crushed_fraction"));
  CHECK_THROWS_WITH(read({"crack_gas.residual_aperture=-1e-5"}), Catch::Contains("crack_gas.residual_aperture"));
  CHECK_THROWS_WITH(read({"coupling.gas_load=\"cells\""}), Catch::Contains("coupling.gas_load"));
  CHECK_THROWS_WITH(read({"crack_gas.courant=1.5"}), Catch::Contains("crack_gas.courant"));
  CHECK_THROWS_WITH(read({"crack_gas.friction_factor=-1"}), Catch::Contains("crack_gas.friction_factor"));
  CHECK_THROWS_WITH(read({"crack_gas.aperture=1e-5"}), Catch::Contains("crack_gas.aperture"));  // unknown key
  CHECK_THROWS_WITH(read({"crack_gas.handover_width=0.5"}), Catch::Contains("crack_gas.handover_width"));
  CHECK_THROWS_WITH(read({"crack_gas.roughness=0"}), Catch::Contains("crack_gas.roughness"));
  CHECK_THROWS_WITH(read({"gas.region.0.blast_gas=1"}), Catch::Contains("gas.region.0.blast_gas"));
  // The blast gas is traced by default (conservative transport); the paper's transport cannot carry it.
  CHECK(read({}).gas.materials().tracer);
  CHECK_FALSE(read({"gas.region.0.blast_gas=false"}).gas.materials().tracer);
  CHECK_THROWS_WITH(read({"gas.transport=\"paper\"", "gas.region.0.blast_gas=true"}), Catch::Contains("blast_gas"));
  // Pre-cut cracks ([[rock.crack]] tables appended to the example): their ends inside the rock; an initial
  // aperture needs the crack gas.
  const std::string text = file_bytes(single_hole_toml);
  auto with_crack = [&](const std::string& crack) {
    return app::read_case(toml::parse(text + "\n[[rock.crack]]\n" + crack + "\n"));
  };
  const app::Case cut = with_crack("from = [0.06, 0.0]\nto = [0.3, 0.0]\ninitial_aperture = 1e-4");
  REQUIRE(cut.rock.model.cracks.size() == 1);
  CHECK(cut.rock.model.cracks[0].initial_aperture == 1e-4);
  CHECK(cut.rock.model.cracks[0].label == "rock.crack.0");
  CHECK_THROWS_WITH(with_crack("from = [0.06, 0.0]\nto = [3.0, 0.0]"), Catch::Contains("rock.crack.0"));
  CHECK_THROWS_WITH(with_crack("from = [0.06, 0.0]\nto = [0.3, 0.0]\ninitial_aperture = -1"),
                    Catch::Contains("rock.crack.0.initial_aperture"));
  CHECK_THROWS_WITH(with_crack("from = [0.06, 0.0]\nto = [0.3, 0.0]\nwidth = 1e-4"), Catch::Contains("rock.crack.0.width"));
  std::string dry = text;  // the example with its crack gas off
  dry.replace(dry.find("enabled = true"), 14, "enabled = false");
  CHECK_THROWS_WITH(app::read_case(toml::parse(dry + "\n[[rock.crack]]\nfrom = [0.06, 0.0]\nto = [0.3, 0.0]\ninitial_aperture = 1e-4\n")),
                    Catch::Contains("rock.crack.0.initial_aperture"));
  // The closure law of open joints: both keys or neither, a maximum closure below every initial aperture it
  // closes, and something for it to close.
  const std::vector<std::string> closure{"crack_gas.joint_closure_stiffness=2e10", "crack_gas.joint_max_closure=5e-5"};
  std::string closing_text = text;  // the example with the closure law, and a pre-cut crack of aperture a0
  closing_text.replace(closing_text.find("[crack_gas]"), 11,
                       "[crack_gas]\njoint_closure_stiffness = 2e10\njoint_max_closure = 5e-5");
  auto closing_crack = [&](const std::string& a0) {
    return app::read_case(toml::parse(closing_text + "\n[[rock.crack]]\nfrom = [0.06, 0.0]\nto = [0.3, 0.0]\n"
                                                     "initial_aperture = " + a0 + "\n"));
  };
  CHECK_THROWS_WITH(read({closure[0]}), Catch::Contains("crack_gas.joint_closure_stiffness") &&
                                            Catch::Contains("crack_gas.joint_max_closure"));
  CHECK_THROWS_WITH(read(closure), Catch::Contains("initial_aperture for them to close"));
  const app::Case closing = closing_crack("1e-4");
  REQUIRE(closing.coupling.crack_gas_options.joint_closure.has_value());
  CHECK(closing.coupling.crack_gas_options.joint_closure->max_closure == 5e-5);
  CHECK_THROWS_WITH(closing_crack("4e-5"),
                    Catch::Contains("crack_gas.joint_max_closure") && Catch::Contains("rock.crack.0.initial_aperture"));
  std::string dry_closing = closing_text;  // the law with the crack gas off
  dry_closing.replace(dry_closing.find("enabled = true"), 14, "enabled = false");
  CHECK_THROWS_WITH(app::read_case(toml::parse(dry_closing)),
                    Catch::Contains("crack_gas.joint_closure_stiffness") && Catch::Contains("enabled = true"));
  // With one dt for both solvers, a fixed dt above the rock's stable step is refused at the start, naming
  // the stable value.
  std::ostringstream log;
  const fs::path out = fresh_dir("coupled_bad");
  std::vector<std::string> o = small_case(out);
  o.push_back("time.rock_subcycling=false");
  o.push_back("time.dt=1e-5");
  CHECK_THROWS_WITH(app::run_coupled_case(read(o), log), Catch::Contains("exceeds the rock's stable step"));
  // A rock probe outside the rock is refused when the mesh is built, naming the probe.
  std::vector<std::string> outside = small_case(out);
  outside.push_back("probe.rock_point.2.position=[0.5, 0.5]");
  CHECK_THROWS_WITH(app::run_coupled_case(read(outside), log), Catch::Contains("probe.rock_point.2.position"));
}


TEST_CASE("A coupled run killed and restarted from its checkpoint ends byte for byte like the uninterrupted run",
          "[long][app][coupled][restart]") {
  // Without and with gas in the cracks (docs/coupling.md) under face forces, and with crack gas under edge
  // pressures that the gas pays for (the case's own load).
  for (const int variant : {0, 1, 2}) {
    const bool crack_gas = variant > 0, paid = variant == 2;
    const std::string tag = paid ? "_paid" : (crack_gas ? "_crack" : "");
    const fs::path a = fresh_dir("restart_a" + tag), b = fresh_dir("restart_b" + tag);
    auto config = [&](const fs::path& out, std::vector<std::string> extra) {
      std::vector<std::string> o = small_case(out);
      o.push_back("time.end=4e-5");
      o.push_back("output.interval=2e-5");  // snapshots, and checkpoints, at 0, 20 and 40 us
      o.push_back(crack_gas ? "crack_gas.enabled=true" : "crack_gas.enabled=false");
      o.push_back(paid ? "coupling.gas_load=\"edges_paid\"" : "coupling.gas_load=\"faces\"");
      o.insert(o.end(), extra.begin(), extra.end());
      return app::read_case(app::load_input(single_hole_toml, o));
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
    const std::map<std::string, double> last = last_row(a / "coupling_series.csv");
    CHECK(last.count("crack_gas_mass_kg_per_m") == (crack_gas ? 1u : 0u));  // the crack gas's columns come with it
    const double crack_mass = crack_gas ? last.at("crack_gas_mass_kg_per_m") : 0.0;
    std::printf("restart%s: %ld steps; killed at step %ld, restarted from the 20 us checkpoint; %zu files identical; "
                "crack gas %.3e kg/m\n", paid ? " with crack gas, paid edge pressures" : (crack_gas ? " with crack gas" : ""),
                total_steps, total_steps - 3, files.size(), crack_mass);
    if (crack_gas) CHECK(crack_mass > 0);  // the cracks held gas across the checkpoint
    // A checkpoint of another case is refused, naming the difference.
    CHECK_THROWS_WITH(app::run_coupled_case(config(b, {"gas.courant=0.2"}), log, restart), Catch::Contains("gas.courant"));
    // A key recorded only away from the earlier builds' value (checkpoint_case_text()) is still compared: the
    // default (true) is recorded, so asking for the earlier step on this checkpoint is refused.
    CHECK_THROWS_WITH(app::run_coupled_case(config(b, {"gas.pressure_predictor=false"}), log, restart),
                      Catch::Contains("gas.pressure_predictor"));
  }
}

namespace {
//! A small single-hole blast: the bundled case's materials and gas states, a 100 mm disc of the paper's rock
//! with a 20 mm hole, 2.5 mm cells, 4 mm triangles of Gmsh's frontal lattice.
std::string small_blast_text(const fs::path& out, double end) {
  std::ostringstream s;
  s << "[domain]\nnx = 96\nny = 96\nx_min = -0.12\nx_max = 0.12\ny_min = -0.12\ny_max = 0.12\n"
    << "[gas.boundary]\nleft = \"outflow\"\nright = \"outflow\"\nbottom = \"outflow\"\ntop = \"outflow\"\n"
    << "[gas.ambient]\ndensity = 1.20\ninternal_energy = 2.09e5\n"
    << "[[gas.region]]\nshape = \"circle\"\ncenter = [0.0, 0.0]\nradius = 0.024\ndensity = 163.0\ninternal_energy = 4.29e5\n"
    << "[rock]\npreset = \"paper_table2\"\n"
    // Gmsh's frontal lattice: its regular triangles keep the elements' stress scatter at the wall below S1's 5 %
    // at this size (a / h = 5), which the isotropic default's does not (6 %; I4, docs/validation.md).
    << "[rock.mesh]\nshape = \"disc_with_hole\"\ncenter = [0.0, 0.0]\nradius = 0.1\nhole_radius = 0.02\nelement_size = 0.004\n"
    << "algorithm = \"frontal\"\n"
    << "[time]\nend = " << end << "\n"
    << "[output]\ndirectory = \"" << out.string() << "\"\ninterval = " << end / 2 << "\nmonitor_interval = 10\n"
    << "vtk = false\nprogress_interval = 0.0\n"
    << "[monitor.blasthole]\ncenter = [0.0, 0.0]\nhole_radius = 0.02\nouter_radius = 0.1\ninterval = 1e-6\n"
    << "[[monitor.region]]\nname = \"disc\"\nshape = \"circle\"\ncenter = [0.0, 0.0]\nradius = 0.1\n"
    << "[[monitor.region]]\nname = \"hole\"\nshape = \"circle\"\ncenter = [0.0, 0.0]\nradius = 0.025\n";
  return s.str();
}

}  // namespace

TEST_CASE("Small single-hole blast end to end: symmetric before cracking, energy budget, cracks that take gas",
          "[long][app][coupled][blast]") {
  // Run three times: the paper's scheme (edge pressures, unpaid; cracks hold gas once they open to the grid
  // scale), gas in the cracks with face forces, and the single-hole example's (gas in the cracks, paid edge
  // pressures, the driver's default load: docs/coupling.md).
  struct Variant {
    const char* tag;
    const char* dir;
    bool crack_gas;
    const char* input;  //!< appended to the case: the crack gas and the load (none: the driver's default)
    ibm::GasLoad load;  //!< the load the case must end up with
  };
  const Variant variants[] = {
      {"paper's scheme", "blast", false, "[coupling]\ngas_load = \"edges\"\n", ibm::GasLoad::edge_pressures},
      {"crack gas on, face forces", "blast_crack_gas", true, "[crack_gas]\nenabled = true\n[coupling]\ngas_load = \"faces\"\n",
       ibm::GasLoad::face_forces},
      {"crack gas on, paid edge pressures", "blast_crack_gas_paid", true, "[crack_gas]\nenabled = true\n",
       ibm::GasLoad::edge_pressures_paid}};
  for (const Variant& v : variants) {
    const bool crack_gas = v.crack_gas;
    const char* tag = v.tag;
    const fs::path out = fresh_dir(v.dir);
    const double end = 4e-4;
    const app::Case c = app::read_case(toml::parse(small_blast_text(out, end) + v.input));
    CHECK(c.coupling.gas_load == v.load);  // the last variant names no load: the driver's default
    std::ostringstream log;
    app::run_coupled_case(c, log);
    INFO(log.str());
    // S1: before the first crack, the gas pressure around the hole wall and the rock's radial stress at the wall
    // (45-degree sector means) are symmetric within 5 %, and they agree (fluid pressure = radial stress).
    const auto wall = csv_columns(out / "wall_series.csv");
    size_t before = 0;
    while (before + 1 < wall.at("broken_joints").size() && wall.at("broken_joints")[before + 1] == 0) ++before;
    const double t1 = wall.at("time_s")[before], p_mean = wall.at("gas_pressure_wall_mean_Pa")[before];
    const double p_spread = (wall.at("gas_pressure_wall_max_Pa")[before] - wall.at("gas_pressure_wall_min_Pa")[before]) / p_mean;
    const double s_spread = wall.at("rock_radial_stress_wall_sector_spread")[before];
    const double s_mean = wall.at("rock_radial_stress_wall_mean_Pa")[before];
    std::printf("blast (%s) S1 at %.1f us (last sample before the first crack): gas pressure at the wall %.4e Pa (spread %.2f %%), "
                "rock radial stress %.4e Pa (sector spread %.2f %%)\n", tag, 1e6 * t1, p_mean, 100 * p_spread, s_mean, 100 * s_spread);
    CHECK(p_spread < 0.05);
    // The rock's sector spread is asserted for the paper's scheme. With face forces it was 7.9 % at its last
    // sample before the first crack (11 us; 2026-12-03): reported, not asserted (docs/validation.md S1 says
    // why; with edge pressures the same measure moves between 3 and 11 % over the first 20 us, and the first
    // crack's time, which sets the sample, moves with the crack gas).
    if (!crack_gas) CHECK(s_spread < 0.05);
    // S4: the budget of gas + rock against the energy the gas gave the rock (the stricter yardstick: against
    // the initial energy of the hole's gas the residual is smaller still).
    const std::map<std::string, double> last = last_row(out / "coupling_series.csv");
    const double work = last.at("gas_work_on_rock_J_per_m"), residual = last.at("budget_residual_J_per_m");
    std::printf("blast (%s) S4 at %.0f us: gas work on the rock %.4e J/m, budget residual %.3e J/m (%.2f %%); %.0f joints broken, "
                "crack length %.3f m\n", tag, 1e6 * last.at("time_s"), work, residual, 100 * residual / work,
                last.at("broken_joints"), last.at("crack_length_m"));
    CHECK(std::fabs(residual) < 0.05 * work);
    // Cracks appear, and gas enters them. Without crack gas the grid carries it: the gas mass in the disc outside
    // the hole region (r > 25 mm) grows well beyond the air that was there. With crack gas the cracks' own gas is
    // the gas in them: it must hold more than three times that air. (With crack gas most of it stays in the cracks:
    // their walls cool it, docs/coupling.md "Heat at the walls", and with paid edge pressures little reaches the
    // grid's cells outside the hole region within 0.4 ms.)
    const auto cs = csv_columns(out / "coupling_series.csv");
    const double annulus0 = cs.at("disc_mass_kg_per_m").front() - cs.at("hole_mass_kg_per_m").front();
    const double annulus1 = cs.at("disc_mass_kg_per_m").back() - cs.at("hole_mass_kg_per_m").back();
    // The crack gas's columns come with the crack gas (each coupling process reports its own), and the log names
    // the processes of each stage.
    CHECK(last.count("crack_gas_mass_kg_per_m") == (crack_gas ? 1u : 0u));
    CHECK(log.str().find(crack_gas ? "coupling stages: cover: immersed boundary, crack gas;"
                                   : "coupling stages: cover: immersed boundary;") != std::string::npos);
    const double crack_mass = crack_gas ? last.at("crack_gas_mass_kg_per_m") : 0.0;
    std::printf("blast (%s): gas in the disc outside the hole %.3e -> %.3e kg/m; in the cracks %.3e kg/m\n", tag, annulus0,
                annulus1, crack_mass);
    CHECK(last.at("broken_joints") > 10);
    CHECK((crack_gas ? crack_mass : annulus1) > 3 * annulus0);
    if (crack_gas) CHECK(crack_mass > 0);
  }
}
