//! \file bench_fdem.cpp
//! \brief Benchmark of the FDEM rock step: (triangle + joint) updates per second, per-phase times, contact cost.
//!
//! Case: an intact square block of n x n squares (2 n^2 triangles, about 3 n^2 joints) of the paper's rock,
//! set vibrating by a random initial velocity so that every kernel does real work. Floor model
//! (docs/performance.md): bytes each phase must move at least, over the measured copy bandwidth.
#include "bench_common.hpp"
#include "blastsim/fdem/rock_solver.hpp"

#include <chrono>
#include <cstdio>
#include <random>
#include <sstream>
#include <string>
#include <vector>


namespace {
using Clock = std::chrono::steady_clock;
}  // namespace

int main(int argc, char** argv) {
  using namespace blastsim;
  std::vector<int> sizes{64, 128, 256};
  int steps = 50;
  for (int a = 1; a < argc; ++a) {
    const std::string arg = argv[a];
    if (arg.rfind("--sizes=", 0) == 0) {
      sizes = bench::parse_int_list(arg.substr(8));
    } else if (arg.rfind("--steps=", 0) == 0) {
      steps = std::stoi(arg.substr(8));
    } else {
      std::fprintf(stderr, "usage: %s [--sizes=64,128,...] [--steps=N]\n", argv[0]);
      return 2;
    }
  }
  const int threads = bench::thread_count();
  const double bw = bench::copy_bandwidth();
  std::printf("backend %s, threads %d, %d timed steps; copy bandwidth (read + write) %.1f GB/s\n", backend_name(),
              threads, steps, bw / 1e9);
  // Floor bytes per item (each array read or written once): triangle 6 positions + 6 velocities + 4 inv F0
  // + eta + 3 edge pressures in (+3 exposed flags), 6 forces + 6 pressure loads + 3 stresses out =
  // 35 doubles + 3 B; joint 4 indices + 8 strengths + 8 positions + 3 damage in, 3 damage + 4 x 2 slot forces
  // out (+12 doubles of opening/traction history) = 30 doubles + 16 B + 12 doubles; node: position,
  // velocity, mass, 3 per-node forces x 2, 2 slots x 2, work x 4 in; position, velocity, work x 4,
  // support x 2 out = 33 doubles.
  const double tri_bytes = 35 * 8 + 3, joint_bytes = 30 * 8 + 16 + 12 * 8, node_bytes = 33 * 8;
  std::printf("%8s %8s %9s | %9s %9s %9s %9s %9s | %12s %11s | %s\n", "tri", "joints", "contact", "tri ms",
              "joint ms", "contact ms", "node ms", "step ms", "(t+j) upd/s", "rebuild ms", "floor/bw per phase (t, j, n)");
  for (int n : sizes)
    for (bool contact : {false, true}) {
      const fdem::FdemTopology topo = fdem::build_topology(fdem::structured_rectangle(n, n, 0, n * 0.0095, 0, n * 0.0095));
      fdem::RockOptions opt;
      opt.contact = contact;
      fdem::RockSolver s(topo, fdem::RockMaterial::paper_table2(), opt);
      std::mt19937 rng(7);
      std::uniform_real_distribution<double> u(-0.01, 0.01);
      std::vector<double> v(2 * s.node_count());
      for (double& x : v) x = u(rng);
      s.set_velocities(v);
      const double dt = 0.5 * s.stable_dt();
      for (int k = 0; k < 3; ++k) s.step(dt);
      double t_tri = 0, t_joint = 0, t_contact = 0, t_node = 0;
      auto timed = [](auto&& f) {
        const auto t0 = Clock::now();
        f();
        bench::wait_for_device();
        return std::chrono::duration<double>(Clock::now() - t0).count();
      };
      bench::wait_for_device();
      for (int k = 0; k < steps; ++k) {
        t_tri += timed([&] { s.triangle_forces(dt); });
        t_joint += timed([&] { s.joint_forces(); });
        t_contact += timed([&] { s.contact_forces(dt); });
        t_node += timed([&] { s.update_nodes(dt); });
      }
      bench::wait_for_device();
      const auto t0 = Clock::now();
      for (int k = 0; k < steps; ++k) s.step(dt);
      bench::wait_for_device();
      const double step = std::chrono::duration<double>(Clock::now() - t0).count() / steps;
      const double rebuild = contact ? timed([&] { s.rebuild_contact_grid(); }) : 0.0;
      const double T = s.triangle_count(), J = s.joint_count();
      t_tri /= steps, t_joint /= steps, t_contact /= steps, t_node /= steps;
      std::printf("%8.0f %8.0f %9s | %9.3f %9.3f %9.3f %9.3f %9.3f | %12.3e %11.3f | %.1f%% %.1f%% %.1f%%\n", T, J,
                  contact ? "on" : "off", 1e3 * t_tri, 1e3 * t_joint, 1e3 * t_contact, 1e3 * t_node, 1e3 * step,
                  (T + J) / step, 1e3 * rebuild, 100 * T * tri_bytes / t_tri / bw, 100 * J * joint_bytes / t_joint / bw,
                  100 * 3 * T * node_bytes / t_node / bw);
    }
  return 0;
}
