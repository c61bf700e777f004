//! \file main.cpp
//! \brief The blastsim driver: reads one TOML case (plus key=value overrides), echoes it, runs it.
#include "blastsim/core/backend.hpp"
#include "blastsim/core/error.hpp"
#include "blastsim/core/macros.hpp"
#include "case.hpp"
#include "run_loop.hpp"

#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include <iostream>
#include <string>
#include <vector>


int main(int argc, char** argv) {
  CLI::App cli{"blastsim: 2-D rock-blasting simulator (CIP gas, FDEM rock, or both coupled by immersed boundaries)"};
  std::string input;
  std::vector<std::string> overrides;
  bool quiet = false, check_only = false, restart = false, profile = false;
  cli.add_option("input", input, "case file (TOML); docs/input.md lists every key")->required();
  cli.add_option("overrides", overrides, "section.key=value settings that replace the file's");
  cli.add_flag("-q,--quiet", quiet, "no progress lines");
  cli.add_flag("--check", check_only, "read and validate the input, print the resolved configuration, run nothing");
  cli.add_flag("--restart", restart,
               "coupled cases: continue from output.directory/checkpoint.bin (same input; time.end may grow)");
  cli.add_flag("--profile", profile,
               "time every kernel (each launch synchronised, so the run is slower) and print the table at the end");
  CLI11_PARSE(cli, argc, argv);

  using namespace blastsim;
  try {
    const app::Case c = app::read_case(app::load_input(input, overrides));
    if (restart && c.kind != app::CaseKind::coupled)
      throw InputError("--restart: checkpoints are written by coupled gas-rock cases only; this input is a " +
                       std::string(c.kind == app::CaseKind::rock ? "rock-only" : "gas-only") + " case");
    std::cout << fmt::format("blastsim {}, backend {}\nresolved configuration of {}:\n", BLASTSIM_VERSION, backend_name(),
                             input);
    for (const app::EchoLine& line : c.echo) std::cout << "  " << line.text << "\n";
    if (check_only) return 0;
    KernelProfile::instance().enable(profile);
    const app::RunOptions options{quiet, restart};
    switch (c.kind) {
      case app::CaseKind::rock: app::run_rock_case(c, std::cout, options); break;
      case app::CaseKind::coupled: app::run_coupled_case(c, std::cout, options); break;
      case app::CaseKind::gas: app::run_gas_case(c, std::cout, options); break;
    }
    if (profile) std::cout << KernelProfile::instance().report();
    std::cout << "done; results in " << c.output.directory << "\n";
  } catch (const InputError& e) {
    std::cerr << "input error: " << e.what() << "\n";
    return 2;
  } catch (const OutputError& e) {
    std::cerr << "output error: " << e.what() << "\n";
    return 4;
  } catch (const InstabilityError& e) {
    std::cerr << "unstable: " << e.what() << "\n";
    return 3;
  } catch (const std::bad_alloc& e) {
    // Thrust reports every failed device allocation as a bad_alloc, with the CUDA error in its message: only an
    // allocation that ran out of memory is the case's size; any other CUDA error means the GPU cannot be used.
    const std::string what = e.what();
    if (what.find("cudaError") != std::string::npos && what.find("cudaErrorMemoryAllocation") == std::string::npos) {
      std::cerr << "error: the GPU cannot be used (" << what << "); a CUDA build of blastsim needs an NVIDIA GPU and "
                   "a driver for its CUDA version (the CPU build runs without one)\n";
      return 1;
    }
    std::cerr << "input error: the case needs more memory than this machine could give (" << what << "); use "
                 "fewer cells (domain.nx, domain.ny) or larger elements (rock.mesh.element_size)\n";
    return 2;
  } catch (const std::exception& e) {
    std::cerr << "error: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
