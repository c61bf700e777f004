//! \file test_robustness.cpp
//! \brief The driver under careless and hostile use: damaged or forged checkpoints, restarts against missing
//! or changed outputs, schedules that could not advance, integers that do not fit, colliding output names,
//! output folders that cannot be made, and a seeded fuzz of override strings. Every run must end with exit 0
//! (outputs that read back), 2 (bad input, one line naming the key or file), 3 (unstable) or 4 (a write
//! failed), never hang and never crash.
#include "driver_runs.hpp"

#include <random>

namespace fs = std::filesystem;
using namespace blastsim::testing;

TEST_CASE("Robustness: damaged and forged checkpoints are refused with exit 2, naming the file or record",
          "[app][robust][checkpoint]") {
  const fs::path dir = fresh_dir("robust_ckpt");
  const fs::path out = dir / "out";
  const fs::path input = write_input(dir, "case.toml", coupled_text(out, 1.5e-5));
  REQUIRE(run_driver(input, {}, "ckpt_base").status == 0);
  const fs::path ckpt = out / "checkpoint.bin";
  const std::vector<char> good = read_bytes(ckpt);
  REQUIRE(good.size() > 1000);
  REQUIRE(run_driver(input, {"--restart"}, "ckpt_good").status == 0);  // the intact file restarts
  std::mt19937_64 rng(20261201);
  // Single-byte flips anywhere and truncations: the checksum or the structure refuses every one.
  int refused = 0;
  for (int k = 0; k < 16; ++k) {
    std::vector<char> bad = good;
    const std::size_t at = std::uniform_int_distribution<std::size_t>(0, bad.size() - 1)(rng);
    bad[at] = static_cast<char>(bad[at] ^ (1 + static_cast<int>(rng() % 255)));
    write_bytes(ckpt, bad);
    const Run r = run_driver(input, {"--restart"}, "ckpt_flip");
    INFO("flip at byte " << at << ": " << r.err);
    CHECK(r.status == 2);
    CHECK(r.err.find("checkpoint") != std::string::npos);
    refused += r.status == 2;
  }
  for (std::size_t keep : {std::size_t{0}, std::size_t{7}, good.size() / 3, good.size() - 21, good.size() - 1}) {
    write_bytes(ckpt, std::vector<char>(good.begin(), good.begin() + static_cast<std::ptrdiff_t>(keep)));
    const Run r = run_driver(input, {"--restart"}, "ckpt_cut");
    INFO("truncated to " << keep << " bytes: " << r.err);
    CHECK(r.status == 2);
  }
  // Forged files (checksum recomputed): every index, count and time is checked against what it addresses.
  struct Forgery {
    std::string record;
    std::size_t entry;   //!< element to overwrite
    std::int64_t value;  //!< written with the record's element size
    double real;         //!< for double records (element size 8 and value 0)
  };
  const std::vector<Forgery> forged{
      {"rock.grid.neighbour_list", 0, 0x7fffffff, 0}, {"rock.grid.neighbour_list", 0, -5, 0},
      {"rock.grid.sorted_triangles", 3, 1 << 30, 0},  {"rock.grid.cell_start", 0, -1, 0},
      {"rock.edges.exposed", 2, 7, 0},                 {"rock.joints.broken", 1, 3, 0},
      {"gas.cell_active", 100, 9, 0},                  {"ibm.masks_set", 0, 5, 0}};
  for (const Forgery& f : forged) {
    std::vector<char> bad = good;
    std::uint64_t element = 0;
    const std::size_t data = record_data(bad, f.record, &element);
    std::memcpy(&bad[data + f.entry * element], &f.value, element);
    reseal(bad);
    write_bytes(ckpt, bad);
    const Run r = run_driver(input, {"--restart"}, "ckpt_forged");
    INFO(f.record << "[" << f.entry << "] = " << f.value << ": " << r.err);
    CHECK(r.status == 2);
    CHECK(r.err.find(f.record) != std::string::npos);
  }
  {  // a negative time
    std::vector<char> bad = good;
    const double minus_one = -1.0;
    std::memcpy(&bad[record_data(bad, "gas.time")], &minus_one, 8);
    reseal(bad);
    write_bytes(ckpt, bad);
    const Run r = run_driver(input, {"--restart"}, "ckpt_time");
    CHECK(r.status == 2);
    CHECK(r.err.find("gas.time") != std::string::npos);
  }
  {  // a snapshot index of -7, and a CSV size beyond the file (which would pad it with NUL bytes)
    std::vector<char> bad = good;
    const int minus_seven = -7;
    std::memcpy(&bad[record_data(bad, "out.gas.snapshot_index")], &minus_seven, sizeof minus_seven);
    reseal(bad);
    write_bytes(ckpt, bad);
    Run r = run_driver(input, {"--restart"}, "ckpt_index");
    CHECK(r.status == 2);
    CHECK(r.err.find("out.gas.snapshot_index") != std::string::npos);
    bad = good;
    std::uint64_t size = 0;
    const std::size_t at = record_data(bad, "out.coupling.csv_size");
    std::memcpy(&size, &bad[at], 8);
    size += 1000;
    std::memcpy(&bad[at], &size, 8);
    reseal(bad);
    write_bytes(ckpt, bad);
    r = run_driver(input, {"--restart"}, "ckpt_size");
    CHECK(r.status == 2);
    CHECK(r.err.find("coupling_series.csv") != std::string::npos);
    CHECK(read_bytes(out / "coupling_series.csv").size() < size);  // not padded
  }
  {  // a record this version does not know, added with a valid checksum
    std::vector<char> bad(good.begin(), good.end() - 20);
    const std::string name = "extra.record";
    const std::uint64_t n = name.size(), e = 8, c = 1;
    const double v = 1.0;
    auto put = [&](const void* p, std::size_t s) { bad.insert(bad.end(), static_cast<const char*>(p), static_cast<const char*>(p) + s); };
    put(&n, 8), put(name.data(), n), put(&e, 8), put(&c, 8), put(&v, 8);
    std::vector<char> trailer(good.end() - 20, good.end());
    std::uint64_t records;
    std::memcpy(&records, &trailer[8], 8);
    ++records;
    std::memcpy(&trailer[8], &records, 8);
    bad.insert(bad.end(), trailer.begin(), trailer.end());
    reseal(bad);
    write_bytes(ckpt, bad);
    const Run r = run_driver(input, {"--restart"}, "ckpt_extra");
    CHECK(r.status == 2);
    CHECK(r.err.find("extra.record") != std::string::npos);
  }
  std::printf("robustness: %d of 16 byte flips, 5 truncations, %zu forged records, a negative time and an unknown "
              "record refused with exit 2\n", refused, forged.size());
}

TEST_CASE("Robustness: a restart refuses missing or shortened outputs and creates nothing before it accepts the "
          "checkpoint", "[app][robust][restart]") {
  const fs::path dir = fresh_dir("robust_restart");
  const fs::path out = dir / "out";
  const fs::path input = write_input(dir, "case.toml", coupled_text(out, 1.5e-5));
  REQUIRE(run_driver(input, {}, "rs_base").status == 0);
  // No checkpoint there: refused, and the output folder is not created.
  const fs::path elsewhere = dir / "never_made";
  Run r = run_driver(input, {"--restart", "output.directory=\"" + elsewhere.string() + "\""}, "rs_none");
  CHECK(r.status == 2);
  CHECK_FALSE(fs::exists(elsewhere));
  // A folder holding only the checkpoint: the outputs it continues are missing.
  const fs::path only = dir / "only_checkpoint";
  fs::create_directories(only);
  fs::copy_file(out / "checkpoint.bin", only / "checkpoint.bin");
  r = run_driver(input, {"--restart", "output.directory=\"" + only.string() + "\""}, "rs_only");
  CHECK(r.status == 2);
  CHECK(r.err.find(".csv") != std::string::npos);
  // A CSV shortened below what the checkpoint recorded.
  const std::vector<char> series = read_bytes(out / "coupling_series.csv");
  write_bytes(out / "coupling_series.csv", std::vector<char>(series.begin(), series.begin() + 100));
  r = run_driver(input, {"--restart"}, "rs_short");
  CHECK(r.status == 2);
  CHECK(r.err.find("coupling_series.csv") != std::string::npos);
  // A deleted CSV.
  write_bytes(out / "coupling_series.csv", series);
  fs::remove(out / "rock_series.csv");
  r = run_driver(input, {"--restart"}, "rs_deleted");
  CHECK(r.status == 2);
  CHECK(r.err.find("rock_series.csv") != std::string::npos);
  CHECK_FALSE(fs::exists(out / "rock_series.csv"));
}

TEST_CASE("Robustness: a restart with a later time.end continues exactly like a run made with that end time",
          "[app][robust][restart]") {
  // Run A to 10 us (a snapshot time), restarted with time.end = 20 us; run B to 20 us at once. Every CSV
  // must match byte for byte: the checkpoint at 10 us holds nothing that only the end of run A wrote.
  const fs::path dir = fresh_dir("robust_extend");
  const fs::path a = dir / "a", b = dir / "b";
  const fs::path input_a = write_input(dir, "a.toml", coupled_text(a, 1.0e-5));
  const fs::path input_b = write_input(dir, "b.toml", coupled_text(b, 2.0e-5));
  // Rows every 1000 steps: the end of run A (a few dozen steps) is no row step, so run A closes with rows that
  // run B does not write at that time.
  const std::string rows = "output.monitor_interval=1000";
  REQUIRE(run_driver(input_a, {rows}, "ext_a").status == 0);
  REQUIRE(run_driver(input_a, {rows, "--restart", "time.end=2.0e-5"}, "ext_a2").status == 0);
  REQUIRE(run_driver(input_b, {rows}, "ext_b").status == 0);
  int compared = 0;
  for (const char* f : {"coupling_series.csv", "rock_series.csv", "gas_totals.csv", "wall_series.csv", "point_hole.csv",
                        "summary.txt"}) {
    INFO(f);
    CHECK(same_file(a / f, b / f));
    ++compared;
  }
  std::printf("robustness: restart with a later end time: %d files identical to the run made with that end time\n",
              compared);
}

TEST_CASE("Robustness: schedules, integers, names and folders give exit 2 or 4 naming the key, never a hang",
          "[app][robust][input]") {
  const fs::path dir = fresh_dir("robust_input");
  const fs::path out = dir / "out";
  const fs::path input = write_input(dir, "gas.toml", gas_text(out));
  struct Case {
    std::vector<std::string> args;
    int status;
    std::string names;  //!< what the message must name
  };
  std::ofstream(dir / "a_file") << "x";
  const std::vector<Case> cases{
      {{"output.interval=1e-320"}, 2, "output.interval"},
      {{"probe.point.0.interval=1e-300"}, 2, "probe.point.0.interval"},
      {{"time.end=1e20", "time.max_steps=3"}, 2, "interval"},
      {{"domain.nx=4294967301"}, 2, "domain.nx"},
      {{"domain.nx=1000000", "domain.ny=1000000"}, 2, "domain.nx"},
      {{"gas.region.99999999999999999999999.radius=1"}, 2, "gas.region"},
      {{"time.dt=1e-320"}, 2, "time.dt"},
      {{"gas.courant=1e-320"}, 2, "gas.courant"},
      {{"output.directory=\"" + (dir / "a_file" / "sub").string() + "\""}, 4, "output.directory"},
  };
  for (const Case& c : cases) {
    std::string joined;
    for (const std::string& a : c.args) joined += a + " ";
    const Run r = run_driver(input, c.args, "input");
    INFO(joined << "-> exit " << r.status << ": " << r.err);
    CHECK(r.status == c.status);
    CHECK(r.err.find(c.names) != std::string::npos);
  }
  {  // two probes of one name would write one file
    std::string text = gas_text(out);
    text += "[[probe.point]]\nname = \"centre\"\nposition = [0.1, 0.0]\ninterval = 1.0e-6\n";
    const Run r = run_driver(write_input(dir, "twice.toml", text), {}, "input_twice");
    INFO(r.err);
    CHECK(r.status == 2);
    CHECK(r.err.find("probe.point.1.name") != std::string::npos);
  }
  {  // a rock mesh that would not fit in memory: refused before meshing
    const fs::path coupled = write_input(dir, "coupled.toml", coupled_text(out, 1e-5));
    const Run r = run_driver(coupled, {"rock.mesh.element_size=1e-6"}, "input_mesh");
    INFO(r.err);
    CHECK(r.status == 2);
    CHECK(r.err.find("rock.mesh.element_size") != std::string::npos);
  }
  {  // a line probe with more points than fit: refused, not wrapped
    std::string text = gas_text(out);
    text += "[[probe.line]]\nname = \"axis\"\nstart = [0.0, 0.0]\nend = [0.1, 0.0]\npoints = 11\ntimes = [5.0e-6]\n";
    const Run r = run_driver(write_input(dir, "line.toml", text), {"probe.line.0.points=4294967301"}, "input_points");
    INFO(r.err);
    CHECK(r.status == 2);
    CHECK(r.err.find("probe.line.0.points") != std::string::npos);
  }
  {  // an output folder path longer than the system allows
    const Run r = run_driver(input, {"output.directory=\"" + (dir / std::string(5000, 'a')).string() + "\""}, "input_long");
    CHECK(r.status == 4);
    CHECK(r.err.find("output.directory") != std::string::npos);
  }
  const Run d = run_driver(dir, {}, "input_dir");  // the input path is a folder
  CHECK(d.status == 2);
  CHECK(d.err.find("directory") != std::string::npos);
}

TEST_CASE("Robustness: a seeded fuzz of override strings ends with exit 0, 2 or 3, and exit 0 leaves outputs that "
          "read back", "[app][robust][fuzz]") {
  const fs::path dir = fresh_dir("robust_fuzz");
  const std::vector<std::string> keys{"domain.nx",        "domain.ny",           "domain.x_max",     "gas.gamma",
                                      "gas.courant",      "gas.ambient.density", "gas.region.0.radius",
                                      "gas.region.0.density", "time.end",        "time.dt",          "time.max_steps",
                                      "output.interval",  "output.monitor_interval", "probe.point.0.interval",
                                      "probe.point.0.position", "gas.viscosity_linear", "gas.boundary.left"};
  const std::vector<std::string> values{"0", "-1", "1e308", "-1e308", "nan", "inf", "1e-320", "3", "7", "0.5",
                                        "2.0e-6", "\"wall\"", "\"text\"", "true", "[1.0, 2.0]", "[]", "4294967301",
                                        "99999999999999999999", "1e-9", "0.1"};
  std::mt19937_64 rng(42);
  int counts[5] = {0, 0, 0, 0, 0};  // exit 0, 2, 3, 4, other
  for (int k = 0; k < 40; ++k) {
    const fs::path out = dir / ("run" + std::to_string(k));
    const fs::path input = write_input(dir, "case" + std::to_string(k) + ".toml", gas_text(out));
    const auto [args, joined] = random_overrides(rng, keys, values);
    const Run r = run_driver(input, args, "fuzz");
    INFO(joined << "-> exit " << r.status << ": " << r.err);
    CHECK((r.status == 0 || r.status == 2 || r.status == 3));
    if (r.status != 0) CHECK(!r.err.empty());
    if (r.status == 0) {
      CHECK(csv_reads_back(out / "gas_totals.csv"));
      CHECK(csv_reads_back(out / "point_centre.csv"));
    }
    ++counts[r.status == 0 ? 0 : r.status == 2 ? 1 : r.status == 3 ? 2 : r.status == 4 ? 3 : 4];
  }
  std::printf("robustness fuzz: 40 override sets: %d ran (exit 0), %d refused (exit 2), %d unstable (exit 3), "
              "%d other\n", counts[0], counts[1], counts[2], counts[3] + counts[4]);
}

TEST_CASE("Robustness: a write that fails stops the run with exit 4 naming the file, and nothing half-written "
          "stands under its final name", "[app][robust][write]") {
  // /dev/full accepts the open and fails every write (ENOSPC): a full disk. The files a run writes through a
  // temporary name are pointed there by a link of that temporary name.
  REQUIRE(fs::exists("/dev/full"));
  const fs::path dir = fresh_dir("robust_write");
  const fs::path out = dir / "out";
  const fs::path input = write_input(dir, "gas.toml", gas_text(out));
  fs::create_directories(out);
  fs::create_symlink("/dev/full", out / "gas_totals.csv");  // an appended CSV on a full disk
  Run r = run_driver(input, {}, "write_csv");
  INFO(r.err);
  CHECK(r.status == 4);
  CHECK(r.err.find("gas_totals.csv") != std::string::npos);
  fs::remove(out / "gas_totals.csv");
  fs::create_symlink("/dev/full", out / "line_axis_000.csv.tmp");
  std::string text = gas_text(out);
  text += "[[probe.line]]\nname = \"axis\"\nstart = [0.0, 0.0]\nend = [0.1, 0.0]\npoints = 11\ntimes = [5.0e-6]\n";
  r = run_driver(write_input(dir, "line.toml", text), {}, "write_line");
  INFO(r.err);
  CHECK(r.status == 4);
  CHECK(r.err.find("line_axis_000.csv") != std::string::npos);
  CHECK_FALSE(fs::exists(out / "line_axis_000.csv"));
}
