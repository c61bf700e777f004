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
  std::vector<cip::Transport> transports{cip::Transport::conservative, cip::Transport::paper};
  for (int a = 1; a < argc; ++a) {
    const std::string arg = argv[a];
    if (arg.rfind("--sizes=", 0) == 0) {
      sizes = bench::parse_int_list(arg.substr(8));
    } else if (arg == "--transport=conservative") {
      transports = {cip::Transport::conservative};
    } else if (arg == "--transport=paper") {
      transports = {cip::Transport::paper};
    } else if (arg.rfind("--steps=", 0) == 0) {
      steps = std::stoi(arg.substr(8));
    } else {
      std::fprintf(stderr, "usage: %s [--sizes=256,512,...] [--steps=N] [--transport=conservative|paper]\n", argv[0]);
      return 2;
    }
  }
  const int threads = bench::thread_count();
  const double floor_bytes_per_cell = 24 * sizeof(double);
  std::printf("backend %s, threads %d, %d timed steps after 3 warm-up steps\n", backend_name(), threads, steps);
  const double bandwidth = bench::copy_bandwidth();
  std::printf("measured copy bandwidth (read + write): %.2f GB/s\n", bandwidth / 1e9);
  std::printf("%13s %10s %12s %16s %14s %18s\n", "transport", "cells", "ms/step", "cell-updates/s", "floor GB/s",
              "floor/bandwidth");
  for (cip::Transport transport : transports)
  for (int n : sizes) {
    const cip::EquationOfState eos = cip::EquationOfState::ideal(1.4);
    cip::GasSolverOptions options;
    options.transport = transport;
    options.viscosity = cip::recommended_viscosity(transport);
    cip::GasSolver s(cip::GasGrid::from_box(n, n, -1.25, 1.25, -1.25, 1.25), eos, options);
    // The paper's blasthole: 28 MPa gas in a 50 mm circle, ambient air elsewhere (Table 1).
    s.initialise([](double x, double y) {
      const bool hole = x * x + y * y < 0.05 * 0.05;
      return hole ? cip::GasPoint{163.0, 4.29e5, 0, 0} : cip::GasPoint{1.20, 2.09e5, 0, 0};
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
                transport == cip::Transport::paper ? "paper" : "conservative", cells, 1e3 * sec, cells / sec,
                floor_rate / 1e9, 100 * floor_rate / bandwidth);
  }
  return 0;
}
