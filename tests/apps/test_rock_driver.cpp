//! \file test_rock_driver.cpp
//! \brief Driver on rock-only cases: the bundled Brazilian disc runs and writes .vtu that VTK reads back; the bundled
//! uniaxial compression reaches the Mohr-Coulomb strength (F8 through the driver); bad rock input.
#include "blastsim/core/error.hpp"
#include "case.hpp"
#include "catch.hpp"
#include "temp_files.hpp"
#include "run_loop.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>

#if defined(BLASTSIM_HAVE_VTK)
#include <vtkCellData.h>
#include <vtkDataArray.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkUnstructuredGrid.h>
#include <vtkXMLUnstructuredGridReader.h>
#endif

namespace fs = std::filesystem;
using namespace blastsim;
using blastsim::testing::fresh_dir;
using blastsim::testing::first_line;

namespace {
const std::string brazilian_toml = std::string(BLASTSIM_EXAMPLES_DIR) + "/brazilian_disc/brazilian_disc.toml";
const std::string uniaxial = std::string(BLASTSIM_EXAMPLES_DIR) + "/uniaxial_compression/uniaxial_compression.toml";

//! Column `name` of a CSV file with a header row.
std::vector<double> csv_column(const fs::path& file, const std::string& name) {
  std::ifstream in(file);
  std::string line, cell;
  std::getline(in, line);
  std::istringstream header(line);
  int column = -1;
  for (int k = 0; std::getline(header, cell, ','); ++k)
    if (cell == name) column = k;
  REQUIRE(column >= 0);
  std::vector<double> values;
  while (std::getline(in, line)) {
    std::istringstream row(line);
    for (int k = 0; std::getline(row, cell, ','); ++k)
      if (k == column) values.push_back(std::stod(cell));
  }
  return values;
}
}  // namespace

TEST_CASE("Driver runs the bundled uniaxial compression: the platen force peaks at the Mohr-Coulomb strength",
          "[app][rock][F8][heavy]") {
  const fs::path out = fresh_dir("uniaxial");
  const app::Case c = app::read_case(
      app::load_input(uniaxial, {"output.vtk=false", "output.directory=\"" + out.string() + "\""}));
  REQUIRE(c.rock.model.mesh.joint_lines.size() == 1);
  std::ostringstream log;
  app::run_rock_case(c, log);
  INFO(log.str());
  // The bottom platen's reaction over the width is the axial stress; the analytic strength of a plane at
  // 45 - phi/2 is 2 c cos(phi) / (1 - sin(phi)); docs/validation.md F8 bound 20 %.
  const std::vector<double> bottom = csv_column(out / "rock_series.csv", "velocity1_reaction_y_N_per_m");
  const std::vector<double> top = csv_column(out / "rock_series.csv", "velocity0_reaction_y_N_per_m");
  REQUIRE(bottom.size() > 100);
  const double width = c.rock.model.mesh.max[0] - c.rock.model.mesh.min[0];
  const double peak = *std::max_element(bottom.begin(), bottom.end()) / width;
  const double phi = c.rock.model.material.friction_angle;
  const double expected = 2 * c.rock.model.material.cohesion * std::cos(phi) / (1 - std::sin(phi));
  std::printf("Uniaxial brazilian_toml: peak platen stress %.2f MPa vs %.2f MPa (%+.1f %%)\n", peak / 1e6, expected / 1e6,
              100 * (peak / expected - 1));
  CHECK(std::fabs(peak / expected - 1) < 0.20);
  const size_t at = std::max_element(bottom.begin(), bottom.end()) - bottom.begin();
  CHECK(top[at] < 0);  // the top platen pushes down, the bottom one up
  CHECK(std::fabs(top[at] + bottom[at]) < 0.05 * bottom[at]);  // quasi-static: nearly balanced at the peak
  CHECK(bottom.back() < 0.2 * bottom[at]);  // and the specimen has failed by the end
}

#if defined(BLASTSIM_HAVE_VTK)
TEST_CASE("Driver runs the bundled Brazilian disc (coarse) and its .vtu read back", "[app][rock][vtk]") {
  const fs::path out = fresh_dir("brazilian");
  // The bundled file with a coarser mesh, run past the peak load (about 0.5 ms).
  const app::Case c = app::read_case(app::load_input(
      brazilian_toml, {"rock.mesh.element_size=0.008", "time.end=7e-4", "output.interval=3.5e-4",
                "output.directory=\"" + out.string() + "\""}));
  std::ostringstream log;
  app::run_rock_case(c, log);
  INFO(log.str());
  CHECK(first_line(out / "rock_series.csv").rfind("step,time_s,kinetic_J_per_m,strain_J_per_m", 0) == 0);
  CHECK(fs::exists(out / "rock.pvd"));
  CHECK(fs::exists(out / "joints.pvd"));
  vtkNew<vtkXMLUnstructuredGridReader> reader;
  reader->SetFileName((out / "rock_000002.vtu").string().c_str());
  reader->Update();
  vtkUnstructuredGrid* grid = reader->GetOutput();
  REQUIRE(grid->GetNumberOfCells() > 100);
  CHECK(grid->GetNumberOfPoints() == 3 * grid->GetNumberOfCells());  // FDEM: three own nodes per triangle
  REQUIRE(grid->GetCellData()->GetArray("stress") != nullptr);
  CHECK(grid->GetCellData()->GetArray("stress")->GetNumberOfComponents() == 3);
  vtkDataArray* ps3 = grid->GetCellData()->GetArray("principal_min");
  REQUIRE(ps3 != nullptr);
  double range[2];
  ps3->GetRange(range);
  CHECK(range[0] < -1e6);  // the loading arcs compress the disc: MPa-level compressive principal stress
  REQUIRE(grid->GetPointData()->GetArray("displacement") != nullptr);
  vtkNew<vtkXMLUnstructuredGridReader> joints;
  joints->SetFileName((out / "joints_000002.vtu").string().c_str());
  joints->Update();
  vtkDataArray* broken = joints->GetOutput()->GetCellData()->GetArray("broken");
  REQUIRE(broken != nullptr);
  broken->GetRange(range);
  CHECK(range[1] == 1.0);  // the disc has split: broken joints drawn as cracks
  CHECK(log.str().find("joints broken") != std::string::npos);
}
#endif

TEST_CASE("Bad rock input gives one clear error naming the key", "[app][rock][bad]") {
  auto read = [](const std::vector<std::string>& overrides) {
    return app::read_case(app::load_input(brazilian_toml, overrides));
  };
  CHECK_THROWS_WITH(read({"rock.youngs_modulus=-1.0"}), Catch::Contains("rock.youngs_modulus"));
  CHECK_THROWS_WITH(read({"rock.mesh.shape=\"hexagon\""}), Catch::Contains("rock.mesh.shape"));
  CHECK_THROWS_WITH(read({"rock.mesh.elements=3"}), Catch::Contains("rock.mesh.elements"));
  CHECK_THROWS_WITH(read({"rock.damping_ratio=1.5"}), Catch::Contains("rock.damping_ratio"));
  CHECK_THROWS_WITH(read({"rock.velocity.0.components=\"z\""}), Catch::Contains("rock.velocity.0.components"));
  // Joint lines: ends inside the rock, longer than half an element, on a Gmsh shape that takes them.
  auto read_uniaxial = [](const std::vector<std::string>& overrides) {
    return app::read_case(app::load_input(uniaxial, overrides));
  };
  CHECK_THROWS_WITH(read_uniaxial({"rock.mesh.joint_line.0.to=[0.06, 0.09]"}),
                    Catch::Contains("rock.mesh.joint_line.0") && Catch::Contains("outside the rock"));
  CHECK_THROWS_WITH(read_uniaxial({"rock.mesh.joint_line.0.to=[0.001, 0.007]"}),
                    Catch::Contains("rock.mesh.joint_line.0") && Catch::Contains("shorter than half an element"));
  CHECK_THROWS_WITH(read_uniaxial({"rock.mesh.joint_line.0.along=1.0"}), Catch::Contains("rock.mesh.joint_line.0.along"));
  CHECK_THROWS_WITH(read_uniaxial({"rock.mesh.shape=\"rectangle_with_hole\"", "rock.mesh.center=[0.025, 0.05]",
                                   "rock.mesh.hole_radius=0.005"}),
                    Catch::Contains("joint lines are made by Gmsh"));
  // Heterogeneous strength: a modulus in [1, 1000], a known distribution, each distribution's own parameter,
  // at least one property scattered.
  CHECK_THROWS_WITH(read({"rock.heterogeneity.modulus=0.5"}), Catch::Contains("rock.heterogeneity.modulus"));
  CHECK_THROWS_WITH(read({"rock.heterogeneity.distribution=\"gauss\"", "rock.heterogeneity.modulus=4"}),
                    Catch::Contains("rock.heterogeneity.distribution"));
  CHECK_THROWS_WITH(read({"rock.heterogeneity.distribution=\"lognormal\"", "rock.heterogeneity.cov=0.3",
                          "rock.heterogeneity.modulus=4"}),
                    Catch::Contains("rock.heterogeneity.modulus"));
  CHECK_THROWS_WITH(read({"rock.heterogeneity.distribution=\"lognormal\""}), Catch::Contains("rock.heterogeneity.cov"));
  CHECK_THROWS_WITH(read({"rock.heterogeneity.modulus=4", "rock.heterogeneity.tensile_strength=false",
                          "rock.heterogeneity.cohesion=false", "rock.heterogeneity.fracture_energy=false"}),
                    Catch::Contains("rock.heterogeneity"));
  CHECK_THROWS_WITH(read({"rock.heterogeneity.modulus=4", "rock.heterogeneity.seed=-1"}),
                    Catch::Contains("rock.heterogeneity.seed"));
  const app::Case het = read({"rock.heterogeneity.modulus=4", "rock.heterogeneity.seed=9"});
  REQUIRE(het.rock.model.heterogeneity.has_value());
  CHECK(het.rock.model.heterogeneity->weibull_modulus == 4.0);
  CHECK(het.rock.model.heterogeneity->seed == 9u);
  CHECK(het.rock.model.heterogeneity->correlation_length == 0.0);  // default: independent joints
  CHECK_THROWS_WITH(read({"rock.heterogeneity.modulus=4", "rock.heterogeneity.correlation_length=-0.01"}),
                    Catch::Contains("rock.heterogeneity.correlation_length"));
  CHECK(read({"rock.heterogeneity.modulus=4", "rock.heterogeneity.correlation_length=0.02"})
            .rock.model.heterogeneity->correlation_length == 0.02);
  CHECK_FALSE(read({}).rock.model.heterogeneity.has_value());
  // A case with both gas and rock is a coupled case.
  toml::table both = app::load_input(brazilian_toml, {});
  CHECK(app::case_kind(both) == app::CaseKind::rock);
  both.insert("gas", toml::table{});
  CHECK(app::case_kind(both) == app::CaseKind::coupled);
  // Run-time checks: unknown boundary group, a fixed dt above the stable step.
  std::ostringstream log;
  app::Case c = read({"time.end=1e-6", "output.vtk=false", "output.directory=\"" + fresh_dir("bad_rock").string() + "\""});
  c.rock.model.pressures.push_back({"rock.pressure.0", "nowhere", 1e6});
  CHECK_THROWS_WITH(app::run_rock_case(c, log), Catch::Contains("no such boundary group"));
  c.rock.model.pressures.clear();
  c.time.dt = 1e-3;
  CHECK_THROWS_WITH(app::run_rock_case(c, log), Catch::Contains("time.dt"));
}

TEST_CASE("Driver: a bar pushed at one end radiates rho c_p v0^2 H through a viscous far end (F9 through the input)",
          "[app][rock][F9]") {
  // A bar 0.5 x 0.05 m on rollers (1-D strain), its left end pushed at v0 from t = 0, its right end viscous.
  // Once the front has crossed it, the bar moves at v0 throughout and the dashpots take rho c_p v0 per metre of
  // edge: the radiated power is rho c_p v0^2 H [W/m] (Lysmer and Kuhlemeyer 1969). Joint penalty 100 E: the
  // lattice's impedance is then within 2 % of rho c_p (F1); at 10 E it is 11 % lower, and until the wave
  // reflected by that mismatch has come back (2 L / c) the end moves at 2 Z / (Z + rho c_p) = 0.94 v0.
  const double L = 0.5, H = 0.05, v0 = 0.1;
  const fs::path dir = fresh_dir("viscous_bar");
  fs::create_directories(dir);
  const fs::path input = dir / "bar.toml";
  std::ofstream(input) << "[rock]\npreset = \"paper_table2\"\ncontact = false\njoint_penalty_factor = 100.0\n"
                          "[rock.mesh]\nshape = \"rectangle\"\nmin = [0.0, 0.0]\nmax = [0.5, 0.05]\nelement_size = 0.01\n"
                          "[[rock.velocity]]\nmin = [-0.001, -0.001]\nmax = [0.501, 0.0001]\nvelocity = [0.0, 0.0]\n"
                          "components = \"y\"\n"
                          "[[rock.velocity]]\nmin = [-0.001, 0.0499]\nmax = [0.501, 0.051]\nvelocity = [0.0, 0.0]\n"
                          "components = \"y\"\n"
                          "[[rock.velocity]]\nmin = [-0.001, -0.001]\nmax = [0.0001, 0.051]\nvelocity = [0.1, 0.0]\n"
                          "components = \"x\"\n"
                          "[[rock.viscous_boundary]]\nboundary = \"right\"\n"
                          "[analysis]\nfragments = false\n"
                          "[time]\nend = 3.0e-4\n"
                          "[output]\nvtk = false\nmonitor_interval = 5\n";
  const fs::path out = dir / "out";
  app::Case c = app::read_case(app::load_input(input.string(), {"output.directory=\"" + out.string() + "\""}));
  REQUIRE(c.rock.model.viscous_boundaries.size() == 1);
  REQUIRE(c.rock.model.viscous_boundaries[0].boundary == "right");
  std::ostringstream log;
  app::run_rock_case(c, log);
  const std::vector<double> t = csv_column(out / "rock_series.csv", "time_s");
  const std::vector<double> radiated = csv_column(out / "rock_series.csv", "radiated_J_per_m");
  const double cp = c.rock.model.material.p_wave_speed();
  // Mean power over [1.5 L / c_p, the end], from the rows nearest those times.
  auto row_at = [&](double time) {
    size_t k = 0;
    while (k + 1 < t.size() && t[k] < time) ++k;
    return k;
  };
  const size_t a = row_at(1.5 * L / cp), b = t.size() - 1;
  REQUIRE(b > a);
  const double power = (radiated[b] - radiated[a]) / (t[b] - t[a]);
  const double expected = c.rock.model.material.density * cp * v0 * v0 * H;
  std::printf("F9 through the driver: radiated power %.4e W/m vs rho c_p v0^2 H = %.4e W/m (%+.2f %%)\n", power,
              expected, 100 * (power / expected - 1));
  CHECK(std::fabs(power / expected - 1) < 0.05);
  // An unknown group is refused naming the table.
  c.rock.model.viscous_boundaries[0].boundary = "back";
  CHECK_THROWS_WITH(app::run_rock_case(c, log),
                    Catch::Contains("rock.viscous_boundary.0.boundary") && Catch::Contains("no such boundary group"));
}

TEST_CASE("Driver: in-situ stress on a holed disc, held and relaxed, explicit joints, and their bad input", "[app][rock][S2]") {
  // A graded ring mesh around a hole, sigma_xx = -12, sigma_yy = -6 MPa held on the outer circle (taken from its
  // viscous boundary): the run starts relaxed (log line) and stays at rest (the figures: S3, tests/fdem).
  const fs::path dir = fresh_dir("in_situ");
  fs::create_directories(dir);
  const fs::path input = dir / "in_situ.toml";
  std::ofstream(input) << "[rock]\npreset = \"paper_table2\"\n"
                          "[rock.mesh]\nshape = \"disc_with_hole\"\nmesher = \"rings\"\ngrowth = 1.25\nradius = 0.3\n"
                          "hole_radius = 0.05\nelement_size = 0.012\n"
                          "[[rock.viscous_boundary]]\nboundary = \"outer\"\n"
                          "[rock.in_situ_stress]\nsigma_xx = -12.0e6\nsigma_yy = -6.0e6\n"
                          "[analysis]\nfragments = false\n"
                          "[time]\nend = 1.0e-4\n"
                          "[output]\nvtk = false\nmonitor_interval = 20\n";
  const fs::path out = dir / "out";
  auto read = [&](const std::vector<std::string>& overrides) {
    std::vector<std::string> o = overrides;
    o.push_back("output.directory=\"" + out.string() + "\"");
    return app::read_case(app::load_input(input.string(), o));
  };
  const app::Case c = read({});
  REQUIRE(c.rock.model.in_situ.has_value());
  CHECK(c.rock.model.in_situ->held_boundaries == std::vector<std::string>{"outer"});
  CHECK(c.rock.model.in_situ->stress.gradient[1] == 0.0);
  std::ostringstream log;
  app::run_rock_case(c, log);
  INFO(log.str());
  CHECK(log.str().find("in-situ stress: sigma_xx -1.2e+07, sigma_yy -6e+06, tau_xy 0 Pa at y = 0 m (per metre up: 0, 0, "
                       "0 Pa/m), held on outer; at rest after") != std::string::npos);
  const std::vector<double> kinetic = csv_column(out / "rock_series.csv", "kinetic_J_per_m");
  const std::vector<double> strain = csv_column(out / "rock_series.csv", "strain_J_per_m");
  REQUIRE(!kinetic.empty());
  const double ke_max = *std::max_element(kinetic.begin(), kinetic.end());
  std::printf("S2 driver: strain energy %.5g J/m at the start, largest kinetic energy over 0.1 ms %.3e of it\n",
              strain.front(), ke_max / strain.front());
  CHECK(ke_max <= 1e-6 * strain.front());
  // Gravity sets the gradients of sigma_yy and tau_xy (equilibrium).
  const app::Case g = read({"rock.gravity=[1.0, -9.81]"});
  CHECK(g.rock.model.in_situ->stress.gradient[1] == Approx(9.81 * 2600.0));
  CHECK(g.rock.model.in_situ->stress.gradient[2] == Approx(-2600.0));
  // Bad input: one clear line naming the key.
  CHECK_THROWS_WITH(read({"rock.in_situ_stress.tolerance=0.1"}), Catch::Contains("rock.in_situ_stress.tolerance"));
  CHECK_THROWS_WITH(read({"rock.in_situ_stress.max_steps=0"}), Catch::Contains("rock.in_situ_stress.max_steps"));
  CHECK_THROWS_WITH(read({"rock.in_situ_stress.sigma_xx=0.0", "rock.in_situ_stress.sigma_yy=0.0"}),
                    Catch::Contains("rock.in_situ_stress") && Catch::Contains("zero"));
  CHECK_THROWS_WITH(read({"rock.in_situ_stress.boundaries=[]"}), Catch::Contains("rock.in_situ_stress.boundaries"));
  CHECK_THROWS_WITH(read({"rock.in_situ_stress.boundaries=[1]"}), Catch::Contains("rock.in_situ_stress.boundaries"));
  CHECK_THROWS_WITH(read({"rock.in_situ_stress.sigma_yy=\"high\""}), Catch::Contains("rock.in_situ_stress.sigma_yy"));
  CHECK_THROWS_WITH(read({"rock.mesh.growth=3.0"}), Catch::Contains("rock.mesh.growth"));
  CHECK_THROWS_WITH(read({"rock.mesh.mesher=\"gmsh\"", "rock.mesh.growth=1.1"}), Catch::Contains("rock.mesh.growth"));
  // Gmsh's algorithm is for Gmsh meshes only (the ring mesher has none).
  CHECK_THROWS_WITH(read({"rock.mesh.algorithm=\"frontal\""}), Catch::Contains("rock.mesh.algorithm"));
  // So is a mesh realisation.
  CHECK_THROWS_WITH(read({"rock.mesh.realisation=2"}), Catch::Contains("rock.mesh.realisation") && Catch::Contains("gmsh"));
  {
    app::Case bad = read({"rock.in_situ_stress.boundaries=[\"rim\"]", "time.end=1e-6"});
    std::ostringstream l;
    CHECK_THROWS_WITH(app::run_rock_case(bad, l), Catch::Contains("rock.in_situ_stress.boundaries = \"rim\"") &&
                                                    Catch::Contains("outer"));
  }
  {  // a joint that cannot carry its in-situ traction is named: tension above f_t
    app::Case bad = read({"rock.in_situ_stress.sigma_xx=8e6", "time.end=1e-6"});
    std::ostringstream l;
    CHECK_THROWS_WITH(app::run_rock_case(bad, l), Catch::Contains("rock.in_situ_stress: joint") &&
                                                    Catch::Contains("tensile strength"));
  }
  // Explicit joints (on the uniaxial specimen, a Gmsh rectangle): a closed one with its own strength, an open one.
  auto read_uniaxial = [](const std::vector<std::string>& overrides) {
    return app::read_case(app::load_input(uniaxial, overrides));
  };
  const app::Case j = read_uniaxial({"rock.joint=[{from=[0.0, 0.03], to=[0.05, 0.05], cohesion=2e6, friction_angle=20.0}, "
                                     "{from=[0.01, 0.08], to=[0.04, 0.08], open=true}]"});
  REQUIRE(j.rock.model.joint_sets.size() == 2);
  CHECK(j.rock.model.joint_sets[0].segments.size() == 1);
  CHECK(j.rock.model.joint_sets[0].properties.cohesion == 2e6);
  CHECK(j.rock.model.joint_sets[0].properties.friction_angle == Approx(20 * M_PI / 180));
  CHECK(j.rock.model.joint_sets[1].open);
  CHECK_THROWS_WITH(read_uniaxial({"rock.joint=[{from=[0.0, 0.03], to=[0.08, 0.05]}]"}),
                    Catch::Contains("rock.joint.0") && Catch::Contains("outside the rock"));
  CHECK_THROWS_WITH(read_uniaxial({"rock.joint=[{from=[0.0, 0.03], to=[0.05, 0.05], open=true, cohesion=1e6}]"}),
                    Catch::Contains("rock.joint.0.cohesion"));
  CHECK_THROWS_WITH(read_uniaxial({"rock.joint=[{from=[0.0, 0.03], to=[0.05, 0.05], initial_aperture=1e-4}]"}),
                    Catch::Contains("rock.joint.0.initial_aperture"));
}
