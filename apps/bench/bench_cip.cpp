//! \file bench_cip.cpp
//! \brief Benchmark of the CIP gas step: cell updates per second and bytes per second against the floor.
//!
//! Floor model (docs/performance.md): a step must at least read and write the 12 double arrays of the
//! state (rho, e, u, v, each with d/dx and d/dy): 24 x 8 = 192 bytes per cell. "floor GB/s" is those bytes
//! divided by the step time; its ratio to the measured copy bandwidth is how close the step is to the floor.
#include "bench_common.hpp"
#include "blastsim/cip/gas_solver.hpp"

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <sstream>
#include <string>
#include <vector>


int main(int argc, char** argv) {
  using namespace blastsim;
  std::vector<int> sizes{256, 512, 1024};
  int steps = 20;
  double hole_radius = 0.05;  // [m]
  // Modes: the conservative and the paper's transport with one gas, and the conservative transport with two
  // materials (ANFO products in the hole, air around: eos.hpp GasMaterials).
  enum class Mode { conservative, paper, two_materials };
  std::vector<Mode> modes{Mode::conservative, Mode::paper, Mode::two_materials};
  for (int a = 1; a < argc; ++a) {
    const std::string arg = argv[a];
    if (arg.rfind("--sizes=", 0) == 0) {
      sizes = bench::parse_int_list(arg.substr(8));
    } else if (arg == "--transport=conservative") {
      modes = {Mode::conservative};
    } else if (arg == "--transport=paper") {
      modes = {Mode::paper};
    } else if (arg == "--transport=two-materials") {
      modes = {Mode::two_materials};
    } else if (arg.rfind("--hole-radius=", 0) == 0) {
      hole_radius = std::stod(arg.substr(14));
    } else if (arg.rfind("--steps=", 0) == 0) {
      steps = std::stoi(arg.substr(8));
    } else {
      std::fprintf(stderr, "usage: %s [--sizes=256,512,...] [--steps=N] [--transport=conservative|paper|two-materials] [--hole-radius=0.05]\n", argv[0]);
      return 2;
    }
  }
  const int threads = bench::thread_count();
  const double floor_bytes_per_cell = 24 * sizeof(double);
  std::printf("backend %s, threads %d, %d timed steps after 3 warm-up steps, hole radius %g m\n", backend_name(),
              threads, steps, hole_radius);
  const double bandwidth = bench::copy_bandwidth();
  std::printf("measured copy bandwidth (read + write): %.2f GB/s\n", bandwidth / 1e9);
  std::printf("%13s %10s %12s %16s %14s %18s\n", "mode", "cells", "ms/step", "cell-updates/s", "floor GB/s",
              "floor/bandwidth");
  for (Mode mode : modes)
  for (int n : sizes) {
    const cip::Transport transport = mode == Mode::paper ? cip::Transport::paper : cip::Transport::conservative;
    cip::GasMaterials mat;
    mat.air = cip::EquationOfState::ideal(1.4);
    mat.products = cip::EquationOfState::jwl_products(cip::EquationOfState::jwl_preset("ANFO").p);
    mat.two = mode == Mode::two_materials;
    cip::GasSolverOptions options;
    options.transport = transport;
    options.viscosity = cip::recommended_viscosity(transport);
    cip::GasSolver s(cip::GasGrid::from_box(n, n, -1.25, 1.25, -1.25, 1.25), mat, options);
    // The paper's blasthole: 28 MPa gas in a 50 mm circle, ambient air elsewhere (Table 1); with two materials
    // the hole holds ANFO products at the same density and pressure.
    const cip::GasPoint hole_gas = mat.two ? cip::GasPoint{163.0, mat.products.internal_energy(163.0, 2.8e7), 0, 0, 1.0}
                                           : cip::GasPoint{163.0, 4.29e5, 0, 0};
    s.initialise([&](double x, double y) {
      const bool hole = x * x + y * y < hole_radius * hole_radius;
      return hole ? hole_gas : cip::GasPoint{1.20, 2.09e5, 0, 0};
    });
    const double dt = s.courant_dt(0.1);
    for (int k = 0; k < 3; ++k) s.step(dt);
    (void)s.max_signal_rate();  // synchronises the device
    const auto t0 = std::chrono::steady_clock::now();
    for (int k = 0; k < steps; ++k) s.step(dt);
    (void)s.max_signal_rate();
    const double sec = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count() / steps;
    const double cells = static_cast<double>(n) * n;
    const double floor_rate = cells * floor_bytes_per_cell / sec;  // [B/s] the floor bytes over the step time
    std::printf("%13s %10.0f %12.3f %16.3e %14.2f %17.1f%%\n",
                mode == Mode::paper ? "paper" : (mode == Mode::two_materials ? "two-materials" : "conservative"), cells,
                1e3 * sec, cells / sec,
                floor_rate / 1e9, 100 * floor_rate / bandwidth);
  }
  return 0;
}
