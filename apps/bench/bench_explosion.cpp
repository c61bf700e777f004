//! \file bench_explosion.cpp
//! \brief Cost against accuracy of the gas solver on Toro's 2-D cylindrical explosion (docs/validation.md G2):
//! wall time and density L1 error against a fine radial reference, per grid; also the L1 error of another
//! code's density field on the same grid (an OpenFOAM ASCII volScalarField), for comparisons at equal accuracy
//! (scripts/compare-openfoam.sh, docs/performance.md "The gas against rhoCentralFoam").
//!
//! Case (Toro 2009, Riemann Solvers and Numerical Methods for Fluid Dynamics, 3rd ed., sec. 17.1): [-1, 1]^2,
//! rho = 1, p = 1 for r < 0.4 (cell centres), rho = 0.125, p = 0.1 outside, at rest, gamma = 1.4, to t = 0.25.
//! Reference: the cylindrically symmetric 1-D problem on 6,000 cells over [0, 1.5] (the same as test G2).
#include "bench_common.hpp"
#include "blastsim/cip/gas_solver.hpp"
#include "gas_cases.hpp"
#include "radial_reference.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace {

using namespace blastsim;
using Clock = std::chrono::steady_clock;

test::RadialProfile reference() {
  return test::solve_radial(6000, 1.5, 1.4, 0.25, [](double r) { return r < 0.4 ? 1.0 : 0.125; },
                            [](double r) { return r < 0.4 ? 1.0 : 0.1; });
}

//! f(r, rho - rho_ref(r)) for each of the n x n cells of [-1, 1]^2 (rho[j n + i] at cell (i, j), i along x; r the
//! cell centre's radius), in row order.
template <class F>
void for_each_cell_error(const std::vector<double>& rho, int n, const test::RadialProfile& ref, F f) {
  const double h = 2.0 / n;
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const double r = std::hypot(-1 + (i + 0.5) * h, -1 + (j + 0.5) * h);
      f(r, rho[static_cast<size_t>(j) * n + i] - ref.density_at(r));
    }
}

//! Mean |rho - rho_ref| over the n x n cells of [-1, 1]^2.
double density_l1(const std::vector<double>& rho, int n, const test::RadialProfile& ref) {
  double sum = 0;
  for_each_cell_error(rho, n, ref, [&](double, double e) { sum += std::fabs(e); });
  return sum / (static_cast<double>(n) * n);
}

//! The density L1 split over rings of the given width in r (each ring's share of the whole domain's L1), printed
//! with the ring's signed mean error: where along the radius the error lies (shock, contact, rarefaction).
void print_l1_rings(const std::vector<double>& rho, int n, const test::RadialProfile& ref, double width) {
  const int rings = static_cast<int>(std::ceil(std::sqrt(2.0) / width));
  std::vector<double> abs_sum(rings, 0.0), signed_sum(rings, 0.0), cells(rings, 0.0);
  for_each_cell_error(rho, n, ref, [&](double r, double e) {
    const int k = std::min(rings - 1, static_cast<int>(r / width));
    abs_sum[k] += std::fabs(e);
    signed_sum[k] += e;
    cells[k] += 1;
  });
  std::printf("  ring [m]       L1 share  mean error  exact density at mid-ring\n");
  for (int k = 0; k < rings; ++k)
    if (cells[k] > 0)
      std::printf("  %.2f-%.2f  %10.3e  %+10.3e  %8.4f\n", k * width, (k + 1) * width,
                  abs_sum[k] / (static_cast<double>(n) * n), signed_sum[k] / cells[k], ref.density_at((k + 0.5) * width));
}

//! The internalField of an OpenFOAM ASCII volScalarField ("nonuniform List<scalar> N ( v0 v1 ... )").
std::vector<double> read_openfoam_field(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error("cannot open " + path);
  std::string word;
  while (in >> word && word != "internalField") {
  }
  std::string kind, list;
  size_t count = 0;
  char open = 0;
  if (!(in >> kind >> list >> count >> open) || kind != "nonuniform" || open != '(')
    throw std::runtime_error(path + ": internalField is not an ASCII nonuniform List<scalar>");
  std::vector<double> v(count);
  for (double& x : v)
    if (!(in >> x)) throw std::runtime_error(path + ": fewer values than the list's length");
  return v;
}

}  // namespace

int main(int argc, char** argv) {
  std::vector<int> sizes{100, 200, 400};
  double courant = 0;  // 0: the solver's recommended number for its transport
  std::string field_path;
  int field_n = 0;
  double ring_width = 0;  // 0: no split
  bool profile = false;   // each kernel's synchronised wall time (KernelProfile), printed after each grid
  cip::GasSolverOptions options;  // the solver's defaults unless --predictor= / --viscosity= say otherwise
  for (int a = 1; a < argc; ++a) {
    const std::string arg = argv[a];
    if (arg.rfind("--sizes=", 0) == 0) {
      sizes = bench::parse_int_list(arg.substr(8));
    } else if (arg.rfind("--courant=", 0) == 0) {
      courant = std::stod(arg.substr(10));
    } else if (arg.rfind("--openfoam-rho=", 0) == 0) {
      field_path = arg.substr(15);
    } else if (arg == "--rings") {
      ring_width = 0.05;
    } else if (arg.rfind("--rings=", 0) == 0) {
      ring_width = std::stod(arg.substr(8));
      if (!(ring_width > 0)) {
        std::fprintf(stderr, "--rings=%s: the ring width must be positive\n", arg.substr(8).c_str());
        return 2;
      }
    } else if (arg == "--profile") {
      profile = true;
    } else if (arg == "--fused" || arg == "--separate") {
      options.fusion = arg == "--fused" ? cip::KernelFusion::fused : cip::KernelFusion::separate;
    } else if (arg == "--predictor=on" || arg == "--predictor=off") {
      options.pressure_predictor = arg == "--predictor=on";
    } else if (arg.rfind("--viscosity=", 0) == 0) {
      const std::vector<double> c = bench::parse_double_list(arg.substr(12));
      if (c.size() != 2 || !(c[0] >= 0) || !(c[1] >= 0)) {
        std::fprintf(stderr, "--viscosity=%s: two coefficients c1,c2 >= 0 are allowed\n", arg.substr(12).c_str());
        return 2;
      }
      options.viscosity = cip::ArtificialViscosity{c[0], c[1]};
    } else if (arg.rfind("--n=", 0) == 0) {
      field_n = std::stoi(arg.substr(4));
    } else {
      std::fprintf(stderr,
                   "usage: %s [--sizes=100,200,...] [--courant=C] [--rings[=W]] [--predictor=on|off] [--viscosity=C1,C2]\n"
                   "          [--profile] [--fused|--separate]\n"
                   "       %s --openfoam-rho=CASE/TIME/rho --n=N [--rings[=W]]   (L1 of an N x N field over [-1, 1]^2)\n"
                   "--rings[=W]: the L1 split over rings of width W in radius (default 0.05)\n"
                   "--profile: each kernel's wall time (launches synchronised) after each grid's line\n"
                   "--fused|--separate: kernel groups as one launch or one launch a kernel (default: the backend's)\n"
                   "--predictor=on|off: gas.pressure_predictor; --viscosity=C1,C2: the artificial viscosity's linear and\n"
                   "  quadratic coefficients (default: the solver's: on, 0.25,0.5)\n",
                   argv[0], argv[0]);
      return 2;
    }
  }
  const test::RadialProfile ref = reference();
  if (!field_path.empty()) {
    const std::vector<double> rho = read_openfoam_field(field_path);
    if (field_n <= 0 || rho.size() != static_cast<size_t>(field_n) * field_n) {
      std::fprintf(stderr, "--n=%d: the field holds %zu values, not n^2 with n > 0\n", field_n, rho.size());
      return 2;
    }
    std::printf("field %s, %d x %d cells: density L1 %.4e\n", field_path.c_str(), field_n, field_n,
                density_l1(rho, field_n, ref));
    if (ring_width > 0) print_l1_rings(rho, field_n, ref, ring_width);
    return 0;
  }
  const cip::EquationOfState eos = cip::EquationOfState::ideal(1.4);
  std::printf("backend %s, threads %d; Toro's cylindrical explosion to t = 0.25; viscosity c1 %g c2 %g, pressure "
              "predictor %s\n",
              backend_name(), bench::thread_count(), options.viscosity.linear, options.viscosity.quadratic,
              options.pressure_predictor ? "on" : "off");
  std::printf("%6s %8s %7s %10s %14s %12s\n", "n", "courant", "steps", "seconds", "cell upd./s", "density L1");
  for (const int n : sizes) {
    cip::GasSolver s(cip::GasGrid::from_box(n, n, -1, 1, -1, 1), eos, options);
    const double c = courant > 0 ? courant : cip::recommended_courant(s.options().transport);
    s.initialise([&](double x, double y) {
      const bool in = x * x + y * y < 0.16;
      const double rho = in ? 1.0 : 0.125, p = in ? 1.0 : 0.1;
      return cip::GasPoint{rho, eos.internal_energy(rho, p), 0.0, 0.0};
    });
    KernelProfile::instance().reset();
    KernelProfile::instance().enable(profile);
    const auto t0 = Clock::now();
    test::run_to(s, 0.25, c);  // as test G2
    bench::wait_for_device();
    const long long steps = s.steps();
    const double seconds = std::chrono::duration<double>(Clock::now() - t0).count();
    KernelProfile::instance().enable(false);
    const cip::HostGasFields h = s.to_host();
    std::printf("%6d %8.3f %7lld %10.3f %14.4e %12.4e\n", n, c, steps, seconds,
                static_cast<double>(n) * n * steps / seconds, density_l1(h.rho, n, ref));
    if (ring_width > 0) print_l1_rings(h.rho, n, ref, ring_width);
    if (profile) std::printf("%s", KernelProfile::instance().report().c_str());
    std::fflush(stdout);
  }
  return 0;
}
