//! \file main.cpp
//! \brief The blastsim driver: reads one TOML case (plus key=value overrides), echoes it, runs it.
#include "blastsim/core/error.hpp"
#include "blastsim/core/kernel_profile.hpp"
#include "blastsim/core/macros.hpp"
#include "blastsim_build_info.hpp"
#include "case.hpp"
#include "rock_outputs.hpp"
#include "run_loop.hpp"

#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include <iostream>
#include <optional>
#include <string>
#include <vector>


int main(int argc, char** argv) {
  using namespace blastsim;
  // What a user quotes with a result: the release, the commit of the source tree and the backend.
  const std::string version = fmt::format("blastsim {} (commit {}), backend {}", BLASTSIM_VERSION, BLASTSIM_COMMIT,
                                          backend_name());
  CLI::App cli{"blastsim: 2-D rock-blasting simulator (CIP gas, FDEM rock, or both coupled by immersed boundaries)"};
  std::string input;
  std::vector<std::string> overrides;
  bool quiet = false, check_only = false, restart = false, profile = false;
  cli.add_option("input", input, "case file (TOML); docs/input.md lists every key")->required();
  cli.add_option("overrides", overrides, "section.key=value settings that replace the file's");
  cli.add_flag("-q,--quiet", quiet, "no progress lines");
  cli.add_flag("--check", check_only,
               "read and validate the input (the rock model built and checked too, not relaxed), print the resolved "
               "configuration, run nothing");
  cli.add_flag("--restart", restart,
               "coupled cases: continue from output.directory/checkpoint.bin (same input; time.end may grow)");
  cli.add_flag("--profile", profile,
               "time every kernel (each launch synchronised, so the run is slower) and print the table at the end");
  cli.set_version_flag("--version", version, "print the release, the commit and the backend, and exit");
  try {
    cli.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    // --help and --version print and exit 0; a command line that cannot be read is bad input (exit 2, as for
    // the case file), with CLI11's message and the usage.
    return cli.exit(e) == 0 ? 0 : 2;
  }

  std::optional<app::CaseKind> kind;  // known once the input is read: the memory message names its keys
  try {
    const app::Case c = app::read_case(app::load_input(input, overrides));
    kind = c.kind;
    if (restart && c.kind != app::CaseKind::coupled)
      throw InputError("--restart: checkpoints are written by coupled gas-rock cases only; this input is a " +
                       std::string(c.kind == app::CaseKind::rock ? "rock-only" : "gas-only") + " case");
    std::cout << fmt::format("{}\nresolved configuration of {}:\n", version, input);
    for (const app::EchoLine& line : c.echo) std::cout << "  " << line.text << "\n";
    if (check_only) {
      if (c.kind != app::CaseKind::gas) app::check_rock_model(c, std::cout);
      return 0;
    }
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
    const std::string gas = "fewer cells (domain.nx, domain.ny)";
    const std::string rock = "larger elements (rock.mesh.element_size), and no cracks or joints closer than half an "
                             "element to each other or to the rock's boundary";
    std::cerr << "input error: the case needs more memory than this machine could give (" << what << "); use "
              << (!kind                              ? gas + " or " + rock
                  : *kind == app::CaseKind::gas      ? gas
                  : *kind == app::CaseKind::rock     ? rock
                                                     : gas + " or " + rock)
              << "\n";
    return 2;
  } catch (const std::exception& e) {
    std::cerr << "error: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
