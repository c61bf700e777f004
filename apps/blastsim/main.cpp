//! \file main.cpp
//! \brief The blastsim driver: reads one TOML case (plus key=value overrides), echoes it, runs it.
#include "blastsim/core/backend.hpp"
#include "blastsim/core/error.hpp"
#include "blastsim/core/macros.hpp"
#include "case_input.hpp"
#include "coupled_run.hpp"
#include "gas_run.hpp"
#include "rock_run.hpp"

#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include <algorithm>
#include <iostream>
#include <map>
#include <vector>

namespace {
const std::string& config_directory(const blastsim::app::CoupledCaseConfig& c) { return c.gas.output_directory; }
template <class Config>
const std::string& config_directory(const Config& c) { return c.output_directory; }
//! The kernel profile (--profile): each label's wall time, launches and share, then per library.
void print_profile(std::ostream& out) {
  const auto& entries = blastsim::KernelProfile::instance().entries();
  double total = 0;
  std::map<std::string, double> group;
  for (const auto& [label, e] : entries) {
    total += e.seconds;
    group[label.substr(0, label.find('.'))] += e.seconds;
  }
  std::vector<std::pair<std::string, blastsim::KernelProfile::Entry>> sorted(entries.begin(), entries.end());
  std::sort(sorted.begin(), sorted.end(), [](const auto& a, const auto& b) { return a.second.seconds > b.second.seconds; });
  out << fmt::format("kernel profile (each launch synchronised; {:.3f} s in kernels):\n", total);
  out << fmt::format("  {:<32} {:>10} {:>12} {:>12} {:>7}\n", "kernel", "launches", "total s", "ms/launch", "share");
  for (const auto& [label, e] : sorted)
    out << fmt::format("  {:<32} {:>10} {:>12.4f} {:>12.4f} {:>6.1f}%\n", label, e.launches, e.seconds,
                       1e3 * e.seconds / e.launches, 100 * e.seconds / total);
  for (const auto& [name, seconds] : group)
    out << fmt::format("  {:<32} {:>36.4f} {:>6.1f}%\n", name + ".*", seconds, 100 * seconds / total);
}

}  // namespace

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
    const toml::table table = app::load_input(input, overrides);
    auto echo = [&](const std::vector<std::string>& lines) {
      std::cout << fmt::format("blastsim {}, backend {}\nresolved configuration of {}:\n", BLASTSIM_VERSION,
                               backend_name(), input);
      for (const std::string& line : lines) std::cout << "  " << line << "\n";
    };
    auto run = [&](const auto& config, auto runner) {
      echo(config.echo);
      if (check_only) return;
      KernelProfile::instance().enable(profile);
      runner(config, std::cout, app::RunOptions{quiet, restart});
      if (profile) print_profile(std::cout);
      std::cout << "done; results in " << config_directory(config) << "\n";
    };
    if (restart && app::case_kind(table) != app::CaseKind::coupled)
      throw InputError("--restart: checkpoints are written by coupled gas-rock cases only; this input is a " +
                       std::string(app::case_kind(table) == app::CaseKind::rock ? "rock-only" : "gas-only") + " case");
    switch (app::case_kind(table)) {
      case app::CaseKind::rock: run(app::read_rock_case(table), app::run_rock_case); break;
      case app::CaseKind::coupled: run(app::read_coupled_case(table), app::run_coupled_case); break;
      case app::CaseKind::gas: run(app::read_case(table), app::run_gas_case); break;
    }
  } catch (const InputError& e) {
    std::cerr << "input error: " << e.what() << "\n";
    return 2;
  } catch (const OutputError& e) {
    std::cerr << "output error: " << e.what() << "\n";
    return 4;
  } catch (const InstabilityError& e) {
    std::cerr << "unstable: " << e.what() << "\n";
    return 3;
  } catch (const std::bad_alloc&) {
    std::cerr << "input error: the case needs more memory than this machine could give (std::bad_alloc); use "
                 "fewer cells (domain.nx, domain.ny) or larger elements (rock.mesh.element_size)\n";
    return 2;
  } catch (const std::exception& e) {
    std::cerr << "error: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
