//! \file kernel_profile.hpp
//! \brief Host-side counters of the kernel launchers: wall time per kernel label, launches and host waits; no
//! Thrust and no CUDA runtime, so the driver and the benchmarks' host code read them without the backend.
#pragma once

#include <algorithm>
#include <cstdio>
#include <map>
#include <string>
#include <utility>
#include <vector>

namespace blastsim {

//! Wall time per kernel label, for benchmarks and profiles (`blastsim --profile`, blastsim-bench-coupled).
//! Off by default; when on, every launch through the backend's launchers is bracketed by synchronize(), so the
//! times are each kernel's own (and the run is slower). Host threads only read or change it between steps.
class KernelProfile {
 public:
  struct Entry {
    double seconds = 0;
    long launches = 0;
  };
  static KernelProfile& instance() {
    static KernelProfile p;
    return p;
  }
  bool enabled() const { return enabled_; }
  void enable(bool on) { enabled_ = on; }
  void reset() { entries_.clear(); }
  const std::map<std::string, Entry>& entries() const { return entries_; }
  //! The table of the labels' wall times, launches and shares, largest first, then the sum per library (the
  //! label's prefix before its first '.').
  std::string report() const {
    double total = 0;
    std::map<std::string, double> group;
    for (const auto& [label, e] : entries_) total += e.seconds, group[label.substr(0, label.find('.'))] += e.seconds;
    std::vector<std::pair<std::string, Entry>> sorted(entries_.begin(), entries_.end());
    std::sort(sorted.begin(), sorted.end(), [](const auto& a, const auto& b) { return a.second.seconds > b.second.seconds; });
    char line[256];
    std::snprintf(line, sizeof line, "kernel profile (each launch synchronised; %.3f s in kernels):\n", total);
    std::string out = line;
    std::snprintf(line, sizeof line, "  %-32s %10s %12s %12s %7s\n", "kernel", "launches", "total s", "ms/launch", "share");
    out += line;
    for (const auto& [label, e] : sorted) {
      std::snprintf(line, sizeof line, "  %-32s %10ld %12.4f %12.4f %6.1f%%\n", label.c_str(), e.launches, e.seconds,
                    1e3 * e.seconds / e.launches, 100 * e.seconds / total);
      out += line;
    }
    for (const auto& [name, seconds] : group) {
      std::snprintf(line, sizeof line, "  %-32s %36.4f %6.1f%%\n", (name + ".*").c_str(), seconds, 100 * seconds / total);
      out += line;
    }
    return out;
  }
  //! Adds one launch of `seconds` [s] to `label` (the launchers, when enabled: backend.hpp).
  void add(const char* label, double seconds) {
    Entry& e = entries_[label];
    e.seconds += seconds;
    ++e.launches;
  }

 private:
  bool enabled_ = false;
  std::map<std::string, Entry> entries_;
};

//! How many kernels the launchers below started and how many times the host waited for the device
//! (a reduction's result, a copy to the host, a blocking sort or scan), counted on every backend alike
//! so that a test on the CPU shows what a GPU step does: the step loop's goal is one wait a step, for
//! the value that sets dt. Host threads only; never reset while a step runs.
struct LaunchCounts {
  long launches = 0;
  long host_waits = 0;
  static LaunchCounts& instance() {
    static LaunchCounts c;
    return c;
  }
};
//! Records a blocking call made outside the launchers (a Thrust sort or scan on the device policy).
inline void count_host_wait() { ++LaunchCounts::instance().host_waits; }

}  // namespace blastsim
