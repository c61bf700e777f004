//! \file test_rock_mass_inputs.cpp
//! \brief The rock-mass inputs, pre-cut cracks, the command line and a seeded fuzz of their keys: boundary groups
//! that cracks and joints cannot corrupt, input loops bounded by the geometry, segments that must lie in the rock,
//! keys that are used or refused (never ignored), restarts of inputs that write defaults out, messages that name
//! the key, and exit codes 0, 2 or 3 only, with every output finite.
#include "blastsim/core/error.hpp"
#include "blastsim/fdem/mesh.hpp"
#include "blastsim/fdem/rock_solver.hpp"
#include "case.hpp"
#include "driver_runs.hpp"
#include "rock_outputs.hpp"

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <random>

namespace fs = std::filesystem;
using namespace blastsim;
using namespace blastsim::testing;

namespace {

//! A disc of rock with a hole (Gmsh), a pressure in the hole and a viscous outer circle, without contact.
std::string holed_disc(const fs::path& out, const std::string& more = "") {
  return "[rock]\npreset = \"paper_table2\"\ncontact = false\n"
         "[rock.mesh]\nshape = \"disc_with_hole\"\nradius = 0.1\nhole_radius = 0.02\nelement_size = 0.01\n"
         "[[rock.pressure]]\nboundary = \"hole\"\npressure = 1.0e6\n"
         "[[rock.viscous_boundary]]\nboundary = \"outer\"\n" + more +
         "[analysis]\nfragments = false\n[time]\nend = 1.0e-6\n"
         "[output]\ndirectory = \"" + out.string() + "\"\nvtk = false\nprogress_interval = 0.0\n";
}

app::Case read_text(const fs::path& dir, const std::string& name, const std::string& text,
                    const std::vector<std::string>& overrides = {}) {
  return app::read_case(app::load_input(write_input(dir, name, text).string(), overrides));
}

//! Every edge of `group` has both ends at distance r from c (to 1e-9 r).
bool group_on_circle(const fdem::NamedMesh& m, const std::string& group, double r) {
  if (!m.boundary_groups.count(group)) return false;
  for (const auto& e : m.boundary_groups.at(group))
    for (int v : {e[0], e[1]})
      if (std::fabs(std::hypot(m.mesh.vertices[v][0], m.mesh.vertices[v][1]) - r) > 1e-9 * r) return false;
  return true;
}

//! A mesh file (MSH 4.1 ASCII) of the unit square in n x n squares, two triangles each (structured_rectangle).
fs::path square_mesh_file(const fs::path& dir, int n) {
  const fdem::TriangleMesh m = fdem::structured_rectangle(n, n, 0.0, 1.0, 0.0, 1.0);
  fs::create_directories(dir);
  const fs::path p = dir / "square.msh";
  std::ofstream f(p);
  f.precision(17);
  f << "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n$Nodes\n1 " << m.vertices.size() << " 1 " << m.vertices.size() << "\n2 1 0 "
    << m.vertices.size() << "\n";
  for (std::size_t v = 0; v < m.vertices.size(); ++v) f << v + 1 << "\n";
  for (const auto& v : m.vertices) f << v[0] << " " << v[1] << " 0\n";
  f << "$EndNodes\n$Elements\n1 " << m.triangles.size() << " 1 " << m.triangles.size() << "\n2 1 2 "
    << m.triangles.size() << "\n";
  for (std::size_t t = 0; t < m.triangles.size(); ++t)
    f << t + 1 << " " << m.triangles[t][0] + 1 << " " << m.triangles[t][1] + 1 << " " << m.triangles[t][2] + 1 << "\n";
  f << "$EndElements\n";
  return p;
}

std::string file_rock(const fs::path& mesh, const fs::path& out, const std::string& more = "") {
  return "[rock]\npreset = \"paper_table2\"\ncontact = false\n[rock.mesh]\nshape = \"file\"\nfile = \"" + mesh.string() +
         "\"\n" + more + "[analysis]\nfragments = false\n[time]\nend = 1.0e-6\n[output]\ndirectory = \"" + out.string() +
         "\"\nvtk = false\nprogress_interval = 0.0\n";
}

}  // namespace

TEST_CASE("Rock mass: cracks, joints and joint sets that reach the outline leave every boundary group whole, so a "
          "hole's pressure stays on the hole", "[app][rockmass][groups]") {
  const fs::path dir = fresh_dir("rockmass_groups");
  const double R = 0.1, r = 0.02;
  // A joint set across the whole disc: every line splits the outer circle and the hole.
  const app::Case set = read_text(dir, "set.toml", holed_disc(dir / "out", "[[rock.joint_set]]\nangle = 90.0\nspacing = 0.05\n"));
  const fdem::RockModel with_set = app::make_rock_model(set);
  CHECK(group_on_circle(with_set.mesh, "outer", R));
  CHECK(group_on_circle(with_set.mesh, "hole", r));
  // A pre-cut crack from the hole to the outer circle, and an explicit joint from the outer circle inwards.
  const std::string cut = "[[rock.crack]]\nfrom = [0.0, 0.02]\nto = [0.0, 0.1]\n"
                          "[[rock.joint]]\nfrom = [-0.1, 0.0]\nto = [-0.05, 0.0]\n";
  const app::Case c = read_text(dir, "crack.toml", holed_disc(dir / "out", cut));
  const fdem::RockModel model = app::make_rock_model(c);
  CHECK(group_on_circle(model.mesh, "outer", R));
  CHECK(group_on_circle(model.mesh, "hole", r));
  // The physics that the wrong group gave away: the hole's pressure pushed on a quarter of the outer circle, which
  // moved at once. Before the P wave from the hole arrives (at (R - r) / c_p), the outer quarter beside the crack
  // stays at rest but for the scheme's precursor: below 1e-3 of the particle speed p / (rho c_p) the wave brings.
  fdem::RockSolver& rock = *model.solver;
  const double cp = rock.material().p_wave_speed(), arrival = (R - r) / cp;
  const double dt = rock.stable_dt();
  const int steps = static_cast<int>(0.4 * arrival / dt);
  for (int k = 0; k < steps; ++k) rock.step(dt);
  const fdem::RockSnapshot snap = rock.snapshot();
  double outer_speed = 0, wall_speed = 0;
  for (std::size_t n = 0; n < snap.x0.size(); ++n) {
    const double radius = std::hypot(snap.x0[n], snap.y0[n]), speed = std::hypot(snap.vx[n], snap.vy[n]);
    if (radius > 0.09 && snap.x0[n] > 0 && snap.y0[n] > 0) outer_speed = std::max(outer_speed, speed);
    if (radius < 0.021) wall_speed = std::max(wall_speed, speed);
  }
  const double wave_speed = 1e6 / (rock.material().density * cp);
  std::printf("rock mass groups: after %d steps (0.4 of the P wave's arrival at the outer circle, %.3g us), the outer "
              "quarter beside the crack moves at most %.3e m/s, the hole wall %.3e m/s (p / rho c_p = %.3e m/s)\n",
              steps, 1e6 * arrival, outer_speed, wall_speed, wave_speed);
  CHECK(wall_speed > 0.1 * wave_speed);
  CHECK(outer_speed < 1e-3 * wave_speed);
  // Several holes: a joint set keeps hole0, and a pressure on it is taken.
  const std::string holes =
      "[rock]\npreset = \"paper_table2\"\ncontact = false\n[rock.mesh]\nshape = \"rectangle_with_holes\"\n"
      "min = [0.0, 0.0]\nmax = [0.24, 0.12]\nelement_size = 0.01\n[[rock.mesh.hole]]\ncenter = [0.05, 0.06]\nradius = 0.01\n"
      "[[rock.joint_set]]\nangle = 0.0\nspacing = 0.03\n[[rock.pressure]]\nboundary = \"hole0\"\npressure = 1.0e6\n"
      "[time]\nend = 1.0e-6\n[output]\ndirectory = \"" + (dir / "out").string() + "\"\nvtk = false\n";
  const fdem::RockModel with_holes = app::make_rock_model(read_text(dir, "holes.toml", holes));
  REQUIRE(with_holes.mesh.boundary_groups.count("hole0") == 1);
  CHECK(with_holes.mesh.boundary_groups.count("hole") == 0);
}

TEST_CASE("Rock mass: the input's loops are bounded by the geometry: far offsets, endless traces and a tiny crack-gas "
          "Courant number end at once", "[app][rockmass][hang]") {
  const fs::path dir = fresh_dir("rockmass_hang");
  const fs::path input = write_input(dir, "set.toml", holed_disc(dir / "out", "[[rock.joint_set]]\nangle = 30.0\n"
                                                                              "spacing = 0.03\n"));
  // run_driver() reports a run past its 60 s limit as status -1: a hang fails here.
  for (const char* offset : {"1e17", "-3e250", "1e14"}) {
    const Run r = run_driver(input, {"--check", std::string("rock.joint_set.0.offset=") + offset}, "offset");
    INFO("offset " << offset << ": " << r.err);
    CHECK(r.status == 0);
  }
  // Two pre-cut cracks 50 um apart: refused before meshing (it took minutes and 3 GB), naming both.
  const std::string cracks = "[[rock.crack]]\nfrom = [-0.08, 0.05]\nto = [0.08, 0.05]\n"
                             "[[rock.crack]]\nfrom = [-0.08, 0.05005]\nto = [0.08, 0.05005]\n";
  Run r = run_driver(write_input(dir, "cracks.toml", holed_disc(dir / "out", cracks)), {"--check"}, "cracks");
  INFO(r.err);
  CHECK(r.status == 2);
  CHECK((r.err.find("rock.crack.1") != std::string::npos && r.err.find("rock.crack.0") != std::string::npos));
  r = run_driver(input, {"--check", "rock.joint_set.0.trace_length=1e308", "rock.joint_set.0.persistence=0.5"},
                 "trace");
  CHECK(r.status == 2);
  CHECK(r.err.find("rock.joint_set.0.trace_length") != std::string::npos);
  const fs::path coupled = write_input(dir, "coupled.toml", coupled_text(dir / "coupled", 2e-6));
  for (const char* courant : {"1e-12", "1e-8", "0.005"}) {
    r = run_driver(coupled, {"--check", "crack_gas.enabled=true", std::string("crack_gas.courant=") + courant}, "courant");
    INFO(r.err);
    CHECK(r.status == 2);
    CHECK(r.err.find("crack_gas.courant") != std::string::npos);
  }
}

TEST_CASE("Rock mass: segments lie in the rock, on a mesh file too, and a mesh file takes [[rock.joint]] and keeps its "
          "jittered vertices on the cracks", "[app][rockmass][segments]") {
  const fs::path dir = fresh_dir("rockmass_segments");
  const fs::path mesh = square_mesh_file(dir, 16);  // edges along x = 0.5 from y = 0 to 1, in 16 joints
  const fs::path out = dir / "out";
  // An explicit joint on a mesh file (documented; was always refused as outside the rock).
  const app::Case j = read_text(dir, "joint.toml", file_rock(mesh, out, "[[rock.joint]]\nfrom = [0.5, 0.0]\nto = [0.5, 1.0]\n"
                                                                     "cohesion = 2.0e6\n"));
  const fdem::RockModel jm = app::make_rock_model(j);
  REQUIRE(jm.set_joints.size() == 1);
  CHECK(jm.set_joints[0].size() == 16);
  // A crack that leaves the rock, or runs where the mesh file has no edges, is refused naming it.
  CHECK_THROWS_WITH(app::make_rock_model(read_text(dir, "out.toml", file_rock(mesh, out, "[[rock.crack]]\nfrom = [0.5, 0.0]\n"
                                                                                       "to = [0.5, 1.5]\n"))),
                    Catch::Contains("rock.crack.0") && Catch::Contains("outside the rock"));
  CHECK_THROWS_WITH(app::make_rock_model(read_text(dir, "off.toml", file_rock(mesh, out, "[[rock.crack]]\nfrom = [0.3, 0.0]\n"
                                                                                       "to = [0.3, 1.0]\n"))),
                    Catch::Contains("rock.crack.0"));
  // The mesh jitter keeps the vertices on a crack in place (it moved them off it, and the crack was refused).
  const app::Case jittered = read_text(dir, "jitter.toml", file_rock(mesh, out, "[[rock.crack]]\nfrom = [0.5, 0.0]\n"
                                                                               "to = [0.5, 1.0]\n"),
                                       {"rock.mesh.jitter=0.2", "rock.mesh.seed=3"});
  const fdem::RockModel jm2 = app::make_rock_model(jittered);
  REQUIRE(jm2.crack_joints.size() == 1);
  CHECK(jm2.crack_joints[0].size() == 16);
  // A crack with an end inside a hole of a built shape is refused naming the hole.
  const std::string holes =
      "[rock]\npreset = \"paper_table2\"\n[rock.mesh]\nshape = \"rectangle_with_holes\"\nmin = [0.0, 0.0]\n"
      "max = [0.24, 0.12]\nelement_size = 0.01\n[[rock.mesh.hole]]\ncenter = [0.05, 0.06]\nradius = 0.02\n"
      "[[rock.crack]]\nfrom = [0.05, 0.06]\nto = [0.15, 0.06]\n[time]\nend = 1.0e-6\n[output]\ndirectory = \"" +
      out.string() + "\"\n";
  CHECK_THROWS_WITH(read_text(dir, "inhole.toml", holes), Catch::Contains("rock.crack.0") && Catch::Contains("inside hole 0"));
  // initial_aperture is the crack gas's room: a rock-only case refuses it by name (it was accepted and ignored).
  CHECK_THROWS_WITH(read_text(dir, "aperture.toml", holed_disc(out, "[[rock.crack]]\nfrom = [0.0, 0.02]\nto = [0.0, 0.08]\n"
                                                                    "initial_aperture = 1e-4\n")),
                    Catch::Contains("rock.crack.0.initial_aperture"));
  // A charge on a mesh file needs a hole at its centre: here rock holds it (a mesh vertex), refused by name.
  std::string charged = coupled_text(out, 2e-6);
  const std::size_t at = charged.find("[rock.mesh]");
  charged.replace(at, charged.find("[time]") - at, "[rock.mesh]\nshape = \"file\"\nfile = \"" + mesh.string() + "\"\n");
  charged.replace(charged.find("[[gas.region]]"), charged.find("[rock]") - charged.find("[[gas.region]]"),
                  "[gas.explosive]\npreset = \"ANFO\"\n");
  charged.replace(0, charged.find("[gas.ambient]"),
                  "[domain]\nnx = 48\nny = 48\nx_min = -0.1\nx_max = 1.1\ny_min = -0.1\ny_max = 1.1\n");
  charged += "[[charge]]\ncenter = [0.5, 0.5]\nhole_radius = 0.05\n";
  const size_t mon = charged.find("[monitor.blasthole]");
  charged.erase(mon, charged.find("[[probe.point]]") - mon);
  const Run r = run_driver(write_input(dir, "charge.toml", charged), {}, "charge_file");
  INFO(r.err);
  CHECK(r.status == 2);
  CHECK(r.err.find("charge.0") != std::string::npos);
}

TEST_CASE("Rock mass: a restart takes an input that writes defaults out, and messages name the key the user gave",
          "[app][rockmass][restart]") {
  const fs::path dir = fresh_dir("rockmass_restart");
  const fs::path out = dir / "out";
  std::string text = coupled_text(out, 6e-6);
  text.replace(text.find("[rock.mesh]"), 11, "[rock.heterogeneity]\nmodulus = 5.0\n[rock.mesh]");
  const fs::path input = write_input(dir, "case.toml", text);
  Run r = run_driver(input, {}, "restart_first");
  REQUIRE(r.status == 0);
  // Keys read only when given, written out at the value their absence gives: the same case.
  r = run_driver(input, {"--restart", "time.end=1.2e-5", "rock.mesh.rotation=0", "rock.heterogeneity.correlation_length=0",
                         "output.times=[]"}, "restart_defaults");
  INFO(r.err);
  CHECK(r.status == 0);
  // A value that differs is still another case, named.
  r = run_driver(input, {"--restart", "time.end=1.8e-5", "rock.mesh.rotation=10"}, "restart_other");
  CHECK(r.status == 2);
  CHECK(r.err.find("rock.mesh.rotation") != std::string::npos);
  // Messages that name the key: a correlation length too short to mean anything, a joint set's strength the mesh
  // cannot take.
  r = run_driver(input, {"rock.heterogeneity.correlation_length=1e-308"}, "corr");
  CHECK(r.status == 2);
  CHECK(r.err.find("rock.heterogeneity.correlation_length") != std::string::npos);
  CHECK(r.err.find("nan") == std::string::npos);
  const fs::path set = write_input(dir, "set.toml", holed_disc(dir / "set", "[[rock.joint_set]]\nangle = 30.0\n"
                                                                           "spacing = 0.03\ntensile_strength = 1e10\n"));
  r = run_driver(set, {}, "set_strength");
  INFO(r.err);
  CHECK(r.status == 2);
  CHECK(r.err.find("rock.joint_set.0") != std::string::npos);
}

TEST_CASE("Command line: --version names the release, the commit and the backend, and a command line that cannot be read "
          "is bad input (exit 2)", "[app][rockmass][cli]") {
  const fs::path out = fs::temp_directory_path() / "blastsim_cli_version.txt";
  int raw = std::system((std::string(BLASTSIM_DRIVER) + " --version > '" + out.string() + "' 2>&1").c_str());
  CHECK(WIFEXITED(raw));
  CHECK(WEXITSTATUS(raw) == 0);
  const std::string text = file_bytes(out);
  CHECK(text.find("blastsim ") == 0);
  CHECK(text.find("commit ") != std::string::npos);
  CHECK(text.find("backend ") != std::string::npos);
  for (const char* args : {"", " --no-such-flag case.toml"}) {
    raw = std::system((std::string(BLASTSIM_DRIVER) + args + " > /dev/null 2>&1").c_str());
    INFO("blastsim" << args);
    CHECK(WEXITSTATUS(raw) == 2);
  }
}

TEST_CASE("Rock mass: a seeded fuzz over the rock-mass, crack and in-situ keys keeps the exit-code contract, every "
          "output finite, never a hang", "[app][rockmass][fuzz]") {
  // A coupled disc with a hole (Gmsh), a joint set, a pre-cut crack, in-situ stress and scattered strength; one to
  // three of these keys set to values drawn from the list. BLASTSIM_FUZZ_RUNS sets the number of runs (24 here).
  const fs::path dir = fresh_dir("rockmass_fuzz");
  const std::vector<std::string> keys{
      "rock.joint_set.0.angle", "rock.joint_set.0.spacing", "rock.joint_set.0.trace_length",
      "rock.joint_set.0.persistence", "rock.joint_set.0.offset", "rock.joint_set.0.open",
      "rock.joint_set.0.initial_aperture", "rock.joint_set.0.tensile_strength", "rock.crack.0.from",
      "rock.crack.0.to", "rock.crack.0.initial_aperture", "rock.in_situ_stress.sigma_xx",
      "rock.in_situ_stress.sigma_yy", "rock.in_situ_stress.tau_xy", "rock.in_situ_stress.boundaries",
      "rock.in_situ_stress.reference_y", "rock.in_situ_stress.max_steps", "rock.heterogeneity.modulus",
      "rock.heterogeneity.correlation_length", "rock.mesh.jitter", "rock.mesh.rotation", "rock.gravity",
      "crack_gas.courant", "crack_gas.enabled", "crack_gas.vacuum_fraction", "crack_gas.walls", "crack_gas.prandtl",
      "crack_gas.joint_closure_stiffness", "crack_gas.joint_max_closure"};
  const std::vector<std::string> values{
      "0", "-1", "1e308", "1e-300", "nan", "inf", "1e17", "true", "false", "0.5", "0.02", "3e-6", "-2.0e6", "45.0",
      "[0.0, 0.0]", "[0.0, 0.06]", "[0.05, 0.0]", "[0.0, -9.81]", "[\"outer\"]", "[\"hole\"]", "[]", "0.003", "1e-8",
      // plausible values, so that many draws run
      "30.0", "0.04", "0.8", "-1.0e6", "1e-4", "[0.025, 0.0]", "[0.045, 0.0]", "[\"outer\", \"hole\"]", "500",
      "\"isothermal\"", "\"adiabatic\"", "2e10", "5e-5"};
  const std::vector<std::string> plausible{
      "rock.joint_set.0.angle=20.0", "rock.joint_set.0.spacing=0.015", "rock.joint_set.0.trace_length=0.03",
      "rock.joint_set.0.persistence=0.6", "rock.joint_set.0.offset=0.004", "rock.joint_set.0.offset=1e17",
      "rock.joint_set.0.open=true", "rock.joint_set.0.tensile_strength=2e6", "rock.joint_set.0.seed=7",
      "rock.crack.0.initial_aperture=1e-4", "rock.crack.0.to=[-0.03464101615137755, 0.02]",
      "rock.in_situ_stress.sigma_xx=-8.0e6", "rock.in_situ_stress.tau_xy=1.0e6", "rock.in_situ_stress.sigma_yy=0.0",
      "rock.in_situ_stress.boundaries=[\"outer\", \"hole\"]", "rock.in_situ_stress.equilibrate=false",
      "rock.in_situ_stress.max_steps=50", "rock.in_situ_stress.reference_y=0.06", "rock.gravity=[0.0, -9.81]",
      "rock.gravity=[3.0, -9.81]", "rock.heterogeneity.modulus=2.0", "rock.heterogeneity.correlation_length=0.02",
      "rock.heterogeneity.seed=5", "rock.mesh.jitter=0.1", "rock.mesh.rotation=17.0", "rock.initial_velocity=[1.0, 0.0]",
      "crack_gas.enabled=true", "crack_gas.courant=0.05", "rock.pressure_ramp_time=1e-6",
      "crack_gas.walls=\"isothermal\"", "crack_gas.joint_closure_stiffness=2e10", "crack_gas.joint_max_closure=5e-5"};
  const char* env = std::getenv("BLASTSIM_FUZZ_RUNS");
  const int runs = env ? std::max(1, std::atoi(env)) : 24;
  std::mt19937_64 rng(20261207);
  int counts[4] = {0, 0, 0, 0};  // exit 0, 2, 3, other
  for (int k = 0; k < runs; ++k) {
    const fs::path out = dir / ("run" + std::to_string(k % 4));
    std::string text = coupled_text(out, 4e-6);
    text.replace(text.find("[rock]\n"), 7, "[rock]\ncontact = false\n");  // the fuzz is about the input, not contact
    const std::size_t mesh = text.find("[rock.mesh]");
    text.replace(mesh, text.find("[time]") - mesh,
                 "[rock.mesh]\nshape = \"disc_with_hole\"\ncenter = [0.0, 0.0]\nradius = 0.06\nhole_radius = 0.02\n"
                 "element_size = 0.008\n[[rock.viscous_boundary]]\nboundary = \"outer\"\n"
                 "[[rock.joint_set]]\nangle = 60.0\nspacing = 0.025\n"
                 // across the traces (normal to them, 150 deg) from the hole's rim to the third trace, which it ends on
                 "[[rock.crack]]\nfrom = [-0.017320508075688773, 0.01]\nto = [-0.04330127018922193, 0.025]\n"
                 // at most 20,000 relaxation steps: a rock that never settles (an open set slides) stops in seconds
                 "[rock.in_situ_stress]\nsigma_xx = -4.0e6\nsigma_yy = -2.0e6\ntolerance = 1e-4\nmax_steps = 20000\n"
                 "[rock.heterogeneity]\nmodulus = 5.0\n");
    fs::remove_all(out);
    const fs::path input = write_input(dir, "case.toml", text);
    // Half the draws take one to three values from the lists; the other half one to three plausible settings,
    // so that many runs get past the input and exercise the set-up and the first steps.
    auto [args, joined] = random_overrides(rng, keys, values);
    if (rng() % 2) {
      args.clear(), joined.clear();
      for (int m = 1 + static_cast<int>(rng() % 3); m > 0; --m) {
        args.push_back(plausible[rng() % plausible.size()]);
        joined += args.back() + " ";
      }
    }
    const Run r = run_driver(input, args, "rockmass_fuzz");
    INFO(joined << "-> exit " << r.status << ": " << r.err);
    std::printf("rock-mass fuzz %d: %s-> exit %d %s", k, joined.c_str(), r.status, r.err.empty() ? "\n" : r.err.c_str());
    CHECK((r.status == 0 || r.status == 2 || r.status == 3));
    if (r.status != 0) CHECK(!r.err.empty());
    if (r.status != 2 && fs::exists(out)) CHECK(csv_all_finite(out));
    ++counts[r.status == 0 ? 0 : r.status == 2 ? 1 : r.status == 3 ? 2 : 3];
  }
  std::printf("rock-mass fuzz: %d override sets over the rock-mass, crack and in-situ keys: %d ran (exit 0), %d refused "
              "(exit 2), %d unstable (exit 3), %d other (a hang or a crash); no CSV with a non-finite value\n", runs,
              counts[0], counts[1], counts[2], counts[3]);
  CHECK(counts[3] == 0);
}
