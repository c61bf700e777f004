//! \file bench_coupled.cpp
//! \brief Benchmark of the coupled gas-rock step of the single-hole blast, phase by phase, against a floor model.
//!
//! Case: the single-hole example (examples/single_hole): Table 1 gas in a 50 mm hole of a 0.93 m disc of the
//! Table 2 rock, in air, on an n x n grid over 2.24 m; the rock meshed in rings (fdem::ring_disc_with_hole,
//! no Gmsh, so it runs on machines without it). One dt for both solvers, as in the paper. After warm-up
//! steps (the hole gas has loaded the wall) every kernel is timed through KernelProfile (each launch
//! synchronised) and the labels are summed into the phases of the gas, rock and coupling steps. Floor model:
//! the bytes each phase must move at least (docs/performance.md, "Coupled step"), over the measured copy
//! bandwidth.
#include "bench_common.hpp"
#include "blastsim/cip/gas_solver.hpp"
#include "blastsim/fdem/mesh.hpp"
#include "blastsim/fdem/rock_solver.hpp"
#include "blastsim/ibm/coupler.hpp"

#include <chrono>
#include <cstdio>
#include <string>
#include <utility>
#include <vector>

namespace {

struct Phase {
  const char* name;
  std::vector<std::string> prefixes;  // kernel labels that start with one of these
  double seconds = 0;
  double floor_bytes = 0;  // per step
};

bool starts_with(const std::string& s, const std::string& p) { return s.compare(0, p.size(), p) == 0; }

}  // namespace

int main(int argc, char** argv) {
  using namespace blastsim;
  std::vector<std::pair<int, double>> cases{{280, 0.03}, {560, 0.015}};
  int steps = 20, warmup = 40;
  bool per_kernel = false;
  cip::KernelFusion fusion = cip::KernelFusion::backend_default;
  ibm::GasLoad load = ibm::GasLoad::edge_pressures;
  for (int a = 1; a < argc; ++a) {
    const std::string arg = argv[a];
    if (arg.rfind("--cases=", 0) == 0) {  // N:H,N:H,...
      cases.clear();
      for (const std::string& item : bench::split_list(arg.substr(8))) {
        const size_t colon = item.find(':');
        cases.push_back({std::stoi(item.substr(0, colon)), std::stod(item.substr(colon + 1))});
      }
    } else if (arg.rfind("--steps=", 0) == 0) {
      steps = std::stoi(arg.substr(8));
    } else if (arg.rfind("--warmup=", 0) == 0) {
      warmup = std::stoi(arg.substr(9));
    } else if (arg == "--kernels") {
      per_kernel = true;
    } else if (arg == "--fused") {
      fusion = cip::KernelFusion::fused;
    } else if (arg == "--separate") {
      fusion = cip::KernelFusion::separate;
    } else if (arg == "--gas-load=faces" || arg == "--gas-load=edges" || arg == "--gas-load=edges_paid") {
      load = arg == "--gas-load=faces"   ? ibm::GasLoad::face_forces
             : arg == "--gas-load=edges" ? ibm::GasLoad::edge_pressures
                                         : ibm::GasLoad::edge_pressures_paid;
    } else {
      std::fprintf(stderr, "usage: %s [--cases=N:H,...] [--steps=N] [--warmup=N] [--kernels] [--fused | --separate]\n"
                           "       [--gas-load=edges|faces|edges_paid]\n"
                           "  N: gas cells per side of the 2.24 m grid; H: triangle size [m] (paper: 5001:0.0095)\n"
                           "  --kernels: also every kernel's time and launches per step\n"
                           "  --fused, --separate: the gas step's kernel groups as one launch each, or one by one\n"
                           "    (default: fused on a GPU, separate on host threads)\n"
                           "  --gas-load: the gas's load on the rock, edge pressures (default) or face forces\n",
                   argv[0]);
      return 2;
    }
  }
  const double bw = bench::copy_bandwidth();
  std::printf("backend %s, threads %d, %d timed steps after %d warm-up steps; gas load %s; copy bandwidth (read + "
              "write) %.1f GB/s\n", backend_name(), bench::thread_count(), steps, warmup, ibm::gas_load_name(load), bw / 1e9);
  for (const auto& [n, h] : cases) {
    const double w = 1.12;
    const cip::GasPoint air{1.20, 2.09e5, 0, 0}, hole_gas{163.0, 4.29e5, 0, 0};
    cip::GasSolverOptions gas_options;
    gas_options.fusion = fusion;
    cip::GasSolver gas(cip::GasGrid::from_box(n, n, -w, w, -w, w), cip::EquationOfState::ideal(1.4), gas_options);
    const double r_fill = 0.05 + 1.5 * 2 * w / n;
    gas.initialise([&](double x, double y) { return x * x + y * y < r_fill * r_fill ? hole_gas : air; });
    const fdem::FdemTopology topo = fdem::build_topology(fdem::ring_disc_with_hole(0, 0, 0.93, 0.05, h).mesh);
    fdem::RockSolver rock(topo, fdem::RockMaterial::paper_table2(), fdem::RockOptions{});
    ibm::CouplerOptions coupling;
    coupling.gas_load = load;
    ibm::GasRockCoupler coupler(gas, rock, air, coupling);
    coupler.rock_to_gas();
    // After the first step the coupler has the signal rate (read with the rock's speed, one wait a step).
    auto one_step = [&] {
      const double rate = std::isfinite(coupler.signal_rate()) ? coupler.signal_rate() : gas.max_signal_rate();
      coupler.step(std::min(0.1 / rate, 0.9 * rock.stable_dt()));
    };
    for (int k = 0; k < warmup; ++k) one_step();
    KernelProfile& prof = KernelProfile::instance();
    prof.reset();
    prof.enable(true);
    const auto t0 = std::chrono::steady_clock::now();
    for (int k = 0; k < steps; ++k) one_step();
    bench::wait_for_device();
    const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    prof.enable(false);
    prof.reset();  // and once more without the per-launch synchronisation
    const LaunchCounts counts0 = LaunchCounts::instance();
    const auto t1 = std::chrono::steady_clock::now();
    for (int k = 0; k < steps; ++k) one_step();
    bench::wait_for_device();
    const LaunchCounts counts1 = LaunchCounts::instance();
    const double free_wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t1).count();
    prof.enable(true);
    for (int k = 0; k < steps; ++k) one_step();  // the profile of record
    prof.enable(false);

    // Floor bytes per step (docs/performance.md): cells, faces and rock items each touched once.
    const double cells = double(n) * n, tri = rock.triangle_count(), joints = rock.joint_count(), nodes = 3 * tri;
    std::vector<Phase> phases{
        {"gas non-advection", {"cip.pressure", "cip.face_velocity", "cip.cell_nonadvection"}, 0, cells * (8 + 8) * 8 + 3 * cells},
        {"gas derivatives", {"cip.derivatives"}, 0, cells * 24 * 8},
        {"gas advection", {"cip.transport", "cip.advection"}, 0, cells * 24 * 8},
        {"gas boundary", {"cip.ghosts", "cip.boundary_outflow"}, 0, 4.0 * n * 2 * 24 * 8},
        {"gas time step (signal rate)", {"cip.signal_rate", "ibm.step_scalars"}, 0, cells * 4 * 8},
        {"rock triangles", {"fdem.triangles"}, 0, tri * (35 * 8 + 3)},
        {"rock joints", {"fdem.joints"}, 0, joints * (30 * 8 + 16 + 12 * 8)},
        {"rock contact search", {"fdem.grid", "fdem.contact.count", "fdem.contact.fill"}, 0, 0},
        {"rock contact forces", {"fdem.contact"}, 0, tri * 12 * 8},
        {"rock integration", {"fdem.nodes", "fdem.vmax", "fdem.speed2_peak"}, 0, nodes * 33 * 8},
        {"coupling masks", {"ibm.cover", "ibm.cells", "ibm.clear_owner"}, 0, cells * (2 * 4 + 1) + tri * 6 * 8},
        {"coupling velocities", {"ibm.face_velocity"}, 0, cells * 2 * (8 + 1 + 4)},
        {"coupling pressures", {"ibm.edge_pressure"}, 0, 3 * tri * (8 + 8 + 1)},
        // face forces: per triangle its node loads, and the owners, pressures and masks of the faces it covers;
        // the work over the step: the face velocities kept (copied) and the nodes kept, then per cell its two
        // owners, face velocities kept and imposed, P, rho, e (read and written) and mask (the records of the
        // loaded faces, a band along the rock's surface, left out)
        // (with paid edge pressures only the face velocities and the nodes kept)
        {"coupling face forces", {"ibm.face_load", "ibm.face_work"}, 0,
         load == ibm::GasLoad::face_forces
             ? 3 * tri * 16 + cells * 2 * (4 + 8 + 1) + cells * 2 * 16 + nodes * 4 * 16 +
                   cells * (2 * 4 + 2 * 8 + 2 * 8 + 8 + 8 + 16 + 1)
             : (load == ibm::GasLoad::edge_pressures_paid ? cells * 2 * 16 + nodes * 4 * 16 : 0)},
        // paid edge pressures, what every cell and slot must touch: per cell its mask and two prescribed flags
        // (the velocities, P, rho and e only beside the rock, left out); per slot its source and exposure, the
        // key, record and work written and the key read back once sorted (the exposed slots' nodes, the sort and
        // the charged cells left out)
        {"coupling edge work", {"ibm.edge_work"}, 0,
         load == ibm::GasLoad::edge_pressures_paid ? cells * (1 + 2) + 3 * tri * (4 + 1 + 4 + 4 + 8 + 4) : 0},
    };
    double other = 0, total = 0;
    for (const auto& [label, e] : prof.entries()) {
      total += e.seconds;
      Phase* best = nullptr;
      size_t best_len = 0;
      for (Phase& p : phases)
        for (const std::string& pre : p.prefixes)
          if (starts_with(label, pre) && pre.size() > best_len) best = &p, best_len = pre.size();
      if (best) best->seconds += e.seconds;
      else other += e.seconds;
    }
    std::printf("\ncase: %d x %d cells of %.3f mm; rock %d triangles of %.1f mm, %d joints; %d inactive cells\n", n, n,
                2e3 * w / n, rock.triangle_count(), 1e3 * h, rock.joint_count(), static_cast<int>(coupler.inactive_cells()));
    std::printf("step: %.3f ms wall without profiling, %.3f ms with each launch synchronised\n", 1e3 * free_wall / steps,
                1e3 * wall / steps);
    std::printf("  %-28s %10s %7s %14s %12s\n", "phase", "ms/step", "share", "floor MB/step", "floor/bw");
    for (const Phase& p : phases) {
      const double t = p.seconds / steps;
      std::printf("  %-28s %10.4f %6.1f%% %14.2f %11.1f%%\n", p.name, 1e3 * t, 100 * p.seconds / total,
                  p.floor_bytes / 1e6, p.floor_bytes > 0 && t > 0 ? 100 * p.floor_bytes / t / bw : 0.0);
    }
    std::printf("  %-28s %10.4f %6.1f%%\n", "other kernels", 1e3 * other / steps, 100 * other / total);
    long launches = 0;
    for (const auto& [label, e] : prof.entries()) launches += e.launches;
    std::printf("  launches through the profiled launchers: %.1f per step\n", double(launches) / steps);
    std::printf("  LaunchCounts over the unprofiled steps: %.1f launches and %.1f host waits per step\n",
                double(counts1.launches - counts0.launches) / steps, double(counts1.host_waits - counts0.host_waits) / steps);
    if (per_kernel)
      for (const auto& [label, e] : prof.entries())
        std::printf("    %-34s %10.4f ms/step %6.2f launches/step\n", label.c_str(), 1e3 * e.seconds / steps,
                    double(e.launches) / steps);
  }
  return 0;
}
