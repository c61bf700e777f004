//! \file test_driver.cpp
//! \brief The driver end to end: a gas case writes VTK image data that VTK reads back, probe CSVs with the
//! documented columns, and a clear non-zero exit with no output for bad input.
#include "blastsim/core/error.hpp"
#include "case.hpp"
#include "catch.hpp"
#include "temp_files.hpp"
#include "run_loop.hpp"

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

#if defined(BLASTSIM_HAVE_VTK)
#include <vtkCellData.h>
#include <vtkDataArray.h>
#include <vtkImageData.h>
#include <vtkNew.h>
#include <vtkXMLImageDataReader.h>
#endif

namespace fs = std::filesystem;
using namespace blastsim;
using blastsim::testing::fresh_dir;
using blastsim::testing::first_line;

namespace {


std::string case_text(const fs::path& out, bool vtk) {
  std::ostringstream s;
  s << "[domain]\nnx = 40\nny = 30\nx_min = -0.2\nx_max = 0.2\ny_min = -0.15\ny_max = 0.15\n"
    << "[gas]\n[gas.ambient]\ndensity = 1.20\ninternal_energy = 2.09e5\n"
    << "[[gas.region]]\nshape = \"circle\"\ncenter = [0.0, 0.0]\nradius = 0.03\ndensity = 163.0\n"
    << "internal_energy = 4.29e5\n[time]\nend = 2.0e-5\n"
    << "[output]\ndirectory = \"" << out.string() << "\"\ninterval = 1.0e-5\nvtk = " << (vtk ? "true" : "false")
    << "\nprogress_interval = 0.0\n"
    << "[[probe.line]]\nname = \"axis\"\nstart = [0.0, 0.0]\nend = [0.2, 0.0]\npoints = 11\ntimes = [1.0e-5]\n"
    << "[[probe.point]]\nname = \"centre\"\nposition = [0.0, 0.0]\ninterval = 1.0e-6\n";
  return s.str();
}


}  // namespace

TEST_CASE("Driver runs a gas case: probes with the documented columns, VTK that reads back", "[app][driver]") {
  const fs::path out = fresh_dir("driver");
  const app::Case c = app::read_case(toml::parse(case_text(out, false)));
  std::ostringstream log;
  app::run_gas_case(c, log);
  CHECK(first_line(out / "line_axis_000.csv") == "x,y,rho,u,v,p,e");
  CHECK(first_line(out / "point_centre.csv") == "t,x,y,rho,u,v,p,e");
  // 11 points along the axis; at 10 us the blast has not reached x = 0.2 m: ambient pressure there.
  std::ifstream line(out / "line_axis_000.csv");
  std::string row;
  std::vector<std::string> rows;
  while (std::getline(line, row)) rows.push_back(row);
  REQUIRE(rows.size() == 12);
  double x, y, rho, u, v, p, e;
  REQUIRE(std::sscanf(rows.back().c_str(), "%lf,%lf,%lf,%lf,%lf,%lf,%lf", &x, &y, &rho, &u, &v, &p, &e) == 7);
  CHECK_THAT(x, WithinAbs(0.2, 1e-12));
  CHECK_THAT(p, WithinRel(0.4 * 1.20 * 2.09e5, 1e-6));
  CHECK(log.str().find("step ") != std::string::npos);  // progress lines (progress_interval = 0)
}


#if defined(BLASTSIM_HAVE_VTK)
TEST_CASE("Driver VTK output opens as image data with the gas fields", "[app][driver][vtk]") {
  const fs::path out = fresh_dir("vtk");
  const app::Case c = app::read_case(toml::parse(case_text(out, true)));
  std::ostringstream log;
  app::run_gas_case(c, log);
  CHECK(fs::exists(out / "gas.pvd"));
  vtkNew<vtkXMLImageDataReader> reader;
  reader->SetFileName((out / "gas_000000.vti").string().c_str());
  reader->Update();
  vtkImageData* image = reader->GetOutput();
  int dims[3];
  image->GetDimensions(dims);
  CHECK(dims[0] == 41);
  CHECK(dims[1] == 31);
  CHECK(image->GetNumberOfCells() == 40 * 30);
  vtkDataArray* p = image->GetCellData()->GetArray("pressure");
  REQUIRE(p != nullptr);
  double range[2];
  p->GetRange(range);
  // Initial state: Table 1 pressures (0.4 * 1.2 * 2.09e5 and 0.4 * 163 * 4.29e5).
  CHECK_THAT(range[0], WithinRel(0.4 * 1.20 * 2.09e5, 1e-12));
  CHECK_THAT(range[1], WithinRel(0.4 * 163.0 * 4.29e5, 1e-12));
  REQUIRE(image->GetCellData()->GetArray("velocity") != nullptr);
  CHECK(image->GetCellData()->GetArray("velocity")->GetNumberOfComponents() == 3);
  // Later snapshots exist and the series lists them.
  CHECK(fs::exists(out / "gas_000002.vti"));
  std::ifstream pvd(out / "gas.pvd");
  std::stringstream all;
  all << pvd.rdbuf();
  CHECK(all.str().find("gas_000002.vti") != std::string::npos);
}
#endif

TEST_CASE("Driver executable: bad input exits non-zero with one line and writes nothing", "[app][driver][bad]") {
  const fs::path out = fresh_dir("bad");
  fs::create_directories(out.parent_path());
  const fs::path input = fs::temp_directory_path() / "blastsim_test_bad.toml";
  {
    std::ofstream f(input);
    f << case_text(out, false);
  }
  const std::string cmd = std::string(BLASTSIM_DRIVER) + " " + input.string() + " gas.gamma=0.9 > " +
                          (fs::temp_directory_path() / "blastsim_test_bad.log").string() + " 2>&1";
  const int status = std::system(cmd.c_str());
  CHECK(status != 0);
  CHECK(WEXITSTATUS(status) == 2);
  std::ifstream log(fs::temp_directory_path() / "blastsim_test_bad.log");
  std::string all((std::istreambuf_iterator<char>(log)), std::istreambuf_iterator<char>());
  CHECK(all == "input error: gas.gamma = 0.9: must be > 1\n");
  CHECK(!fs::exists(out));
}

TEST_CASE("A fixed dt above the Courant limit stops with a clear message", "[app][driver][bad]") {
  const fs::path out = fresh_dir("cfl");
  toml::table t = toml::parse(case_text(out, false));
  app::apply_override(t, "time.dt=1e-5");
  const app::Case c = app::read_case(t);
  std::ostringstream log;
  try {
    app::run_gas_case(c, log);
    FAIL("no error for dt above the Courant limit");
  } catch (const InputError& e) {
    const std::string m = e.what();
    CHECK(m.find("time.dt = 1e-05 s violates the Courant limit at step 1") != std::string::npos);
    CHECK(m.find("largest stable dt") != std::string::npos);
  }
}

TEST_CASE("An unstable run stops with the quantity, step and place, and its written output stays finite",
          "[app][driver][unstable]") {
  // The paper's 277:1 jump with the plain scheme (paper's transport, no limiter, c1 = 0.5, c2 = 1): the
  // cubic's undershoot drives the density negative within a few dozen steps (docs/gas-solver.md).
  const fs::path out = fresh_dir("unstable");
  std::ostringstream s;
  s << "[domain]\nnx = 800\nny = 3\nx_min = 0.0\nx_max = 1.0\ny_min = 0.0\ny_max = 0.00375\n"
    << "[gas]\ntransport = \"paper\"\nlimiter = \"none\"\nviscosity_linear = 0.5\nviscosity_quadratic = 1.0\n"
    << "[gas.boundary]\nbottom = \"wall\"\ntop = \"wall\"\n"
    << "[gas.ambient]\ndensity = 1.20\ninternal_energy = 2.09e5\n"
    << "[[gas.region]]\nshape = \"box\"\nmin = [0.0, 0.0]\nmax = [0.2, 0.00375]\ndensity = 163.0\n"
    << "internal_energy = 4.29e5\n[time]\nend = 5.0e-4\n"
    << "[output]\ndirectory = \"" << out.string() << "\"\nvtk = false\n";
  const app::Case c = app::read_case(toml::parse(s.str()));
  std::ostringstream log;
  std::string message;
  try {
    app::run_gas_case(c, log);
  } catch (const InstabilityError& e) {
    message = e.what();
  }
  INFO(message);
  REQUIRE(!message.empty());
  CHECK(message.find("gas state invalid after step") != std::string::npos);
  CHECK((message.find("density = ") != std::string::npos || message.find("internal energy = ") != std::string::npos));
  CHECK(message.find(" in cell (") != std::string::npos);
  CHECK(message.find(" m, y = ") != std::string::npos);
  // Every row the monitor wrote is finite: the bad state never reached the files.
  std::ifstream totals(out / "gas_totals.csv");
  std::string row;
  std::getline(totals, row);
  int rows = 0;
  while (std::getline(totals, row)) {
    ++rows;
    CHECK(row.find("nan") == std::string::npos);
    CHECK(row.find("inf") == std::string::npos);
  }
  CHECK(rows > 1);
}
