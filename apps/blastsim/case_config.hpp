//! \file case_config.hpp
//! \brief The driver's case description (domain, gas states, time, output, probes); plain data, no backend
//! or TOML headers (case_input.hpp reads it from a file).
#pragma once

#include "blastsim/cip/eos.hpp"
#include "blastsim/cip/gas_types.hpp"
#include "blastsim/cip/grid.hpp"

#include <array>
#include <optional>
#include <string>
#include <vector>

namespace blastsim::app {

//! A region of the initial gas state (later regions overwrite earlier ones).
struct GasRegion {
  enum class Shape { box, circle } shape = Shape::box;
  std::array<double, 2> min{}, max{};  //!< [m] box corners
  std::array<double, 2> center{};      //!< [m] circle centre
  double radius = 0.0;                 //!< [m] circle radius
  cip::GasPoint state{};  //!< products_fraction 1 for a products region
  bool contains(double x, double y) const;
};

//! Values along a segment at chosen times, written as CSV (x,y,rho,u,v,p,e).
struct LineProbe {
  std::string name;
  std::array<double, 2> start{}, end{};  //!< [m]
  int points = 0;
  std::vector<double> times;  //!< [s]
};

//! Time series at a point, written as CSV (t,x,y,rho,u,v,p,e).
struct PointProbe {
  std::string name;
  std::array<double, 2> position{};  //!< [m]
  double interval = 0.0;             //!< [s] between samples
};

struct CaseConfig {
  // [domain]
  cip::GasGrid grid;
  // [gas]
  cip::EquationOfState eos;                     //!< the air (and the only gas without an explosive)
  std::optional<cip::EquationOfState> explosive;  //!< [gas.explosive]: JWL detonation products
  //! [gas.explosive]: the explosive itself (for [[charge]]): detonation velocity [m/s] and energy [J/kg], given
  //! or derived from the Chapman-Jouguet state of the JWL set (cip::chapman_jouguet()).
  double detonation_velocity = 0, detonation_energy = 0;
  bool charges = false;  //!< the case has [[charge]] tables (their products need the second material)
  cip::GasSolverOptions solver;
  double courant = 0.1;  //!< [-] dt = courant / max signal rate, or the limit a fixed dt must respect
  cip::GasPoint ambient{};
  std::vector<GasRegion> regions;
  // [time]
  double end_time = 0.0;                //!< [s]
  std::optional<double> fixed_dt;       //!< [s]
  long long max_steps = 0;              //!< 0: no limit
  // [output]
  std::string output_directory;
  double output_interval = 0.0;         //!< [s] between field snapshots; 0: start and end only
  std::vector<double> output_times;     //!< [s] extra snapshots (output.times), ascending
  bool vtk = true;
  double progress_interval = 2.0;       //!< [s of wall time] between progress lines
  long long monitor_interval = 1;       //!< steps between rows of the conservation monitor
  double drift_warning = 0.01;          //!< relative mass/energy balance drift that triggers a warning
  std::vector<LineProbe> line_probes;
  std::vector<PointProbe> point_probes;
  //! The resolved configuration, one "key = value unit" line per key (defaults marked).
  std::vector<std::string> echo;

  //! Initial state at a point: the last region containing it, else the ambient state.
  cip::GasPoint initial_state(double x, double y) const;
  //! The gas's materials: the air, and the explosive's products when a region holds them.
  cip::GasMaterials materials() const;
};

}  // namespace blastsim::app
