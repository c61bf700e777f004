//! \file case.hpp
//! \brief The driver's case: the settings of each input section, held once, in one Case for gas, rock and
//! coupled runs alike (plain data). Each section is read, checked and echoed by the input_<section>.cpp file of
//! its name; docs/input.md lists every key.
#pragma once

#include "blastsim/cip/eos.hpp"
#include "blastsim/cip/gas_types.hpp"
#include "blastsim/cip/grid.hpp"
#include "blastsim/fdem/fragments.hpp"
#include "blastsim/fdem/rock_model.hpp"
#include "blastsim/ibm/charge_types.hpp"
#include "blastsim/ibm/coupling_options.hpp"
#include "input_reader.hpp"

#include <array>
#include <optional>
#include <string>
#include <vector>

namespace blastsim::app {

//! What an input describes: [gas] alone, [rock] alone, or both (a coupled gas-rock case).
enum class CaseKind { gas, rock, coupled };

//! [domain] and [gas]: the grid and the gas, its initial state and how it is solved.
struct GasSettings {
  cip::GasGrid grid;                              //!< [domain]
  cip::EquationOfState eos;                       //!< the air (and the only gas without an explosive)
  std::optional<cip::EquationOfState> explosive;  //!< [gas.explosive]: JWL detonation products
  //! [gas.explosive]: the explosive itself (for [[charge]]): detonation velocity [m/s] and energy [J/kg], given
  //! or derived from the Chapman-Jouguet state of the JWL set (cip::chapman_jouguet()).
  double detonation_velocity = 0, detonation_energy = 0;
  bool charges = false;  //!< the case has [[charge]] tables (their products need the second material)
  cip::GasSolverOptions solver;
  //! [-] dt = courant / max signal rate, or the limit a fixed dt must respect; unset in the input: the
  //! recommended number of the run's transport and gas load (read_case(), ibm::recommended_courant())
  double courant = cip::kPaperCourant;
  bool courant_given = false;  //!< gas.courant is in the input
  cip::GasPoint ambient{};
  //! [[gas.region]]: initial states (later regions overwrite earlier ones); products_fraction 1 for products;
  //! tracer 1 for the blast gas of a one-gas run (blast_gas, default true)
  struct Region {
    cip::CellRegion where;
    cip::GasPoint state;
    bool blast_gas_given = false;  //!< the input set blast_gas (refused in a run with detonation products)
  };
  std::vector<Region> regions;

  //! Initial state at a point: the last region containing it, else the ambient state.
  cip::GasPoint initial_state(double x, double y) const;
  //! The gas's materials: the air, and the explosive's products when a region or a charge holds them.
  cip::GasMaterials materials() const;
  double ambient_pressure() const;  //!< [Pa]
};

//! [rock]: the rock model (mesh, material, options, loads) and the ramp of its boundary pressures.
struct RockSettings {
  fdem::RockModelSpec model;       //!< probes filled from [[probe.rock_point]] when the model is built
  double pressure_ramp_time = 0;   //!< [s] pressures rise as a half cosine over this time (0: at once)
};

//! [analysis]: what the run reports about fragments and damage at every snapshot.
struct AnalysisSettings {
  bool fragments = true;
  int min_fragment_triangles = fdem::kDefaultMinFragmentTriangles;
  double oversize = 0.5;          //!< [m] sieve size above which a fragment is oversize
  double ring_width = 0;          //!< [m] of the damage-zone rings (0: twice the mean joint length)
  double crushed_fraction = 0.5;  //!< broken share of a ring's joint length that makes it crushed
  //! [[analysis.hole]]: a hole around which the damage zone is measured (default: the mesh's holes)
  struct Hole {
    std::array<double, 2> center{};  //!< [m]
    double radius = 0;               //!< [m]
    std::array<double, 2> behind{};  //!< away from the free face: only the half plane behind counts ([0, 0]: all)
  };
  std::vector<Hole> holes;
  bool holes_given = false;  //!< [[analysis.hole]] tables were given
};

//! [probe]: gas values along lines and at points, and rock velocity probes.
struct ProbeSettings {
  //! [[probe.line]]: values along a segment at chosen times (line_NAME_NNN.csv)
  struct Line {
    std::string name;
    std::array<double, 2> start{}, end{};  //!< [m]
    int points = 0;
    std::vector<double> times;  //!< [s]
  };
  //! [[probe.point]]: a time series at a point (point_NAME.csv)
  struct Point {
    std::string name;
    std::array<double, 2> position{};  //!< [m]
    double interval = 0.0;             //!< [s] between samples
  };
  //! [[probe.rock_point]]: follows the material point at `position` (rock_probes.csv, ppv.csv)
  struct RockPoint {
    std::string name;
    std::array<double, 2> position{};  //!< [m] in the initial mesh
    double until = 1e308;              //!< [s] end of the window in which the peak counts
  };
  std::vector<Line> lines;
  std::vector<Point> points;
  std::vector<RockPoint> rock_points;
};

//! [time]
struct TimeSettings {
  double end = 0;                //!< [s]
  std::optional<double> dt;      //!< [s] a fixed step
  long long max_steps = 0;       //!< 0: no limit
  double step_fraction = 0.9;    //!< [-] of the rock's stable step (cases with rock)
  bool rock_subcycling = false;  //!< coupled: the rock fills each gas step with steps of its own
};

//! [output]
struct OutputSettings {
  std::string directory;
  double interval = 0;          //!< [s] between snapshots (0: start and end only)
  std::vector<double> times;    //!< [s] extra snapshots, ascending
  bool vtk = true;
  double progress_interval = 2;     //!< [s of wall time] between progress lines
  long long monitor_interval = 1;   //!< steps between rows of the CSV series
  double drift_warning = 0.01;      //!< relative balance drift that triggers a warning (gas and coupled)
  bool checkpoint = true;           //!< coupled: checkpoint.bin with every snapshot
};

//! [monitor] (coupled cases): the blasthole monitor and the regions whose gas is tracked.
struct MonitorSettings {
  //! [monitor.blasthole]: wall_series.csv and summary.txt
  struct Blasthole {
    ibm::BlastholeGeometry geometry;
    double interval = 1e-6;  //!< [s] between samples
  };
  std::optional<Blasthole> blasthole;
  //! [[monitor.region]]: a region whose gas mass and energy coupling_series.csv carries
  struct Region {
    std::string name;
    cip::CellRegion where;
  };
  std::vector<Region> regions;
};

//! [coupling], [crack_gas] and [[charge]] (coupled cases).
struct CouplingSettings {
  ibm::GasLoad gas_load = ibm::GasLoad::edge_pressures_paid;  //!< coupling.gas_load: "edges_paid", "edges" or "faces"
  bool crack_gas = false;                                //!< crack_gas.enabled
  ibm::CrackGasOptions crack_gas_options;
  std::vector<ibm::Charge> charges;  //!< [[charge]], their holes first among the mesh's holes
  ibm::ChargeProducts charge_products;  //!< the state the products start from ([gas.explosive])
};

//! One case: every section's settings once, and the resolved configuration.
struct Case {
  CaseKind kind = CaseKind::gas;
  GasSettings gas;            //!< gas and coupled cases
  RockSettings rock;          //!< rock and coupled cases
  AnalysisSettings analysis;  //!< rock and coupled cases
  ProbeSettings probes;
  TimeSettings time;
  OutputSettings output;
  MonitorSettings monitor;    //!< coupled cases
  CouplingSettings coupling;  //!< coupled cases
  std::vector<EchoLine> echo;  //!< every key read, in reading order
};

//! What a parsed input describes.
CaseKind case_kind(const toml::table& input);
//! Reads and checks a case from a parsed input (any kind); InputError (one line naming the key, the value and
//! what is allowed) on any bad input.
Case read_case(const toml::table& input);
//! The same from a file, with "section.key=value" overrides applied first.
Case load_case(const std::string& input_path, const std::vector<std::string>& overrides);

// The section readers (input_<section>.cpp), in the order read_case() calls them.
void read_domain(TableReader& root, Case& c);
void read_gas(TableReader& root, Case& c);
void read_probe(TableReader& root, Case& c);
void read_rock(TableReader& root, Case& c);
void read_analysis(TableReader& root, Case& c);  //!< after [rock]: its mesh sets the default holes
void read_charges(TableReader& root, Case& c);   //!< after [gas] and [rock]: the charges' holes join the mesh's
void read_time(TableReader& root, Case& c);
void read_output(TableReader& root, Case& c);
void read_monitor(TableReader& root, Case& c);
void read_coupling(TableReader& root, Case& c);  //!< [coupling] and [crack_gas]

// Checks shared by the readers.
//! InputError unless `name` (used in file names) is letters, digits, '_' and '-'; `kind` is its table.
void check_output_name(const std::string& kind, const std::string& name);
//! InputError when the output names of one kind repeat (two probes would write one file): `kind` is the
//! table ("probe.point"), `names` in input order.
void check_unique_names(const std::string& kind, const std::vector<std::string>& names);
//! InputError when a sampling interval [s] would give more than 1e9 samples in the run (or could not advance
//! the time): `key` = `interval` must be 0 (when `zero_allowed`) or at least 1e-9 x time.end.
void check_interval(const std::string& key, double interval, double end_time, bool zero_allowed);
//! InputError when `bytes`, the memory a case needs for what `what` names, exceeds the machine's memory.
void check_memory_need(const std::string& what, double bytes);
//! A region shape ("box" with min and max, or "circle" with center and radius) of table t.
cip::CellRegion read_region_shape(TableReader& t);

}  // namespace blastsim::app
