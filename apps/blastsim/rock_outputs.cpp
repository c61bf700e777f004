//! \file rock_outputs.cpp
//! \brief The rock's output files (VTU series, energy series, the analysis of every snapshot).
#include "rock_outputs.hpp"

#include "blastsim/core/error.hpp"
#include "blastsim/fdem/rock_analysis.hpp"
#include "blastsim/fdem/vtk_writer.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace blastsim::app {

RockOutputs::RockOutputs(const Case& c, const fdem::RockModel& model, bool resume)
    : c_(c), solver_(*model.solver), velocity_nodes_(model.velocity_nodes),
      joint_set_of_(model.joint_set_of), dir_(make_output_dir(c.output.directory)),
      rock_pvd_((dir_ / "rock.pvd").string()), joints_pvd_((dir_ / "joints.pvd").string()),
      series_((dir_ / "rock_series.csv").string(),
              csv_text(CsvRecord::Mode::header, [&](CsvRecord& o) {
                series_columns(o, {}, 0, std::vector<std::array<double, 2>>(model.velocity_nodes.size()));
              }),
              resume),
      e0_(solver_.energies()) {
  if (c.analysis.fragments)
    fragmentation_.emplace((dir_ / "fragmentation_series.csv").string(),
                           csv_text(CsvRecord::Mode::header, [&](CsvRecord& o) { fragmentation_columns(o); }), resume);
  if (!c.probes.rock_points.empty())
    probes_.emplace((dir_ / "rock_probes.csv").string(),
                    csv_text(CsvRecord::Mode::header, [&](CsvRecord& o) { probe_columns(o); }), resume);
  // Damage rings: twice the mean joint length unless given (a ring then holds joints of every orientation).
  const double joint = fdem::mean_joint_length(model.topology);
  ring_width_ = c.analysis.ring_width > 0 ? c.analysis.ring_width : (joint > 0 ? 2 * joint : 1.0);
}

void RockOutputs::write_checkpoint(CheckpointWriter& w) {
  w.value("out.rock.index", index_);
  w.value("out.rock.initial", e0_);
  series_.write_checkpoint(w, "out.rock.csv_size");
  if (fragmentation_) fragmentation_->write_checkpoint(w, "out.rock.fragmentation_size");
  if (probes_) probes_->write_checkpoint(w, "out.rock.probes_size");
  rock_pvd_.write_checkpoint(w, "out.rock.pvd");
  joints_pvd_.write_checkpoint(w, "out.joints.pvd");
}

void RockOutputs::read_checkpoint(CheckpointReader& r) {
  index_ = r.value<int>("out.rock.index");
  if (index_ < 0 || index_ > 999999) r.fail("out.rock.index", "out of range (0 to 999999 snapshots)");
  e0_ = r.value<fdem::RockEnergies>("out.rock.initial");
  for (double v : {e0_.kinetic, e0_.strain, e0_.joint_work, e0_.joint_stored, e0_.external_work, e0_.pressure_work})
    if (!std::isfinite(v)) r.fail("out.rock.initial", "holds an energy that is not finite");
  series_.read_checkpoint(r, "out.rock.csv_size");
  if (fragmentation_) fragmentation_->read_checkpoint(r, "out.rock.fragmentation_size");
  if (probes_) probes_->read_checkpoint(r, "out.rock.probes_size");
  rock_pvd_.read_checkpoint(r, "out.rock.pvd");
  joints_pvd_.read_checkpoint(r, "out.joints.pvd");
}

void RockOutputs::snapshot() {
  if (!c_.output.vtk && !c_.analysis.fragments && c_.probes.rock_points.empty()) return;
  const fdem::RockSnapshot s = solver_.snapshot();
  fdem::RockCellFields cells;
  const auto t0 = std::chrono::steady_clock::now();
  if (c_.analysis.fragments) cells.fragment_id = fdem::fragment_labels(solver_.view());
  if (c_.output.vtk) cells.damage = fdem::triangle_damage(s);  // for the VTU only
  analyse(s, cells.fragment_id);
  analysis_seconds_ += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  ++analyses_;
  const int index = index_++;
  if (!c_.output.vtk) return;
  const std::string rock_name = fmt::format("rock_{:06d}.vtu", index);
  const std::string joints_name = fmt::format("joints_{:06d}.vtu", index);
  fdem::write_rock_vtu((dir_ / rock_name).string(), s, cells);
  std::vector<fdem::JointField> fields;
  if (crack_) {
    ibm::CrackSegmentFields f = crack_->segment_fields();
    fields = {{"aperture", std::move(f.aperture)},
           {"gas_pressure", std::move(f.gas_pressure)},
           {"gas_mass", std::move(f.gas_mass)},
           {"blast_gas_fraction", std::move(f.blast_gas_fraction)}};
  }
  if (!joint_set_of_.empty())  // the natural joints' set (-1: rock); runs without sets leave it out
    fields.push_back({"joint_set", std::vector<double>(joint_set_of_.begin(), joint_set_of_.end())});
  if (c_.rock.model.heterogeneity || !joint_set_of_.empty()) {  // each joint's strength (uniform rock: left out)
    const std::vector<fdem::JointStrength> js = solver_.joint_strengths();
    std::vector<double> ft(js.size()), coh(js.size());
    for (std::size_t j = 0; j < js.size(); ++j) ft[j] = js[j].tensile_strength, coh[j] = js[j].cohesion;
    fields.push_back({"tensile_strength", std::move(ft)});
    fields.push_back({"cohesion", std::move(coh)});
  }
  fdem::write_joints_vtu((dir_ / joints_name).string(), s, fields);
  rock_pvd_.add(solver_.time(), rock_name);
  joints_pvd_.add(solver_.time(), joints_name);
}

void RockOutputs::analyse(const fdem::RockSnapshot& s, const std::vector<int>& labels) {
  const AnalysisSettings& a = c_.analysis;
  analysed_at_ = solver_.time();
  zones_.clear();
  for (const AnalysisSettings::Hole& h : a.holes)
    zones_.push_back(fdem::damage_zone(s, h.center, h.radius, ring_width_, a.crushed_fraction, h.behind));
  if (!zones_.empty())  // crack_rose.csv: each hole's broken length by direction, at the latest snapshot
    write_atomically((dir_ / "crack_rose.csv").string(), [&](std::ostream& out) {
      out << "time_s,hole,sector_start_deg,sector_end_deg,crack_length_m\n";
      for (size_t k = 0; k < zones_.size(); ++k)
        for (int q = 0; q < fdem::kRoseSectors; ++q)
          out << fmt::format("{:.9e},{},{},{},{:.9e}\n", analysed_at_, k, q * 360 / fdem::kRoseSectors,
                             (q + 1) * 360 / fdem::kRoseSectors, zones_[k].crack_rose[q]);
    });
  if (!zones_.empty())  // damage_profile_NNNNNN.csv: each hole's rings, their broken length and fracture intensity
    write_atomically((dir_ / fmt::format("damage_profile_{:06d}.csv", index_)).string(), [&](std::ostream& out) {
      out << "time_s,hole,inner_radius_m,outer_radius_m,joint_length_m,broken_length_m,broken_fraction,rock_area_m2,"
             "p21_per_m\n";
      for (size_t k = 0; k < zones_.size(); ++k)
        for (const fdem::DamageRing& r : zones_[k].rings)  // a ring without joints or rock: empty ratio fields
          out << fmt::format("{:.9e},{},{:.9e},{:.9e},{:.9e},{:.9e},{},{:.9e},{}\n", analysed_at_, k, r.inner_radius,
                             r.outer_radius, r.joint_length, r.broken_length,
                             r.joint_length > 0 ? fmt::format("{:.9e}", r.broken_length / r.joint_length) : "",
                             r.rock_area, r.rock_area > 0 ? fmt::format("{:.9e}", r.broken_length / r.rock_area) : "");
    });
  if (probes_) {  // ppv.csv: the peak so far at each probe, with its distance from the first hole
    const std::vector<fdem::ProbeSample> p = solver_.probe_samples();
    write_atomically((dir_ / "ppv.csv").string(), [&](std::ostream& out) {
      out << "name,x_m,y_m,distance_from_hole0_m,ppv_m_per_s,peak_time_s,peak_vx_m_per_s,peak_vy_m_per_s\n";
      for (size_t k = 0; k < p.size(); ++k) {  // without an analysis hole the distance is an empty field
        const auto& q = c_.probes.rock_points[k].position;
        const double d = a.holes.empty() ? 0.0 : std::hypot(q[0] - a.holes[0].center[0], q[1] - a.holes[0].center[1]);
        out << c_.probes.rock_points[k].name << ","
            << csv_text(CsvRecord::Mode::row, [&](CsvRecord& o) {
                 o.real("x_m", q[0]).real("y_m", q[1]).real_if(!a.holes.empty(), "distance_from_hole0_m", d);
                 o.real("ppv_m_per_s", p[k].peak_speed).real("peak_time_s", p[k].peak_time);
                 o.real("peak_vx_m_per_s", p[k].peak_vx).real("peak_vy_m_per_s", p[k].peak_vy);
               })
            << "\n";
      }
    });
  }
  if (!a.fragments) return;
  const std::vector<fdem::Fragment> f =
      fdem::measure_fragments(s, labels, c_.rock.model.material.density, a.min_fragment_triangles);
  sizes_ = fdem::size_distribution(f, a.oversize);
  double largest = 0;
  for (const fdem::Fragment& g : f) largest = std::max(largest, g.mass);
  largest_fraction_ = sizes_.total_mass > 0 ? largest / sizes_.total_mass : 0;
  write_atomically((dir_ / fmt::format("fragments_{:06d}.csv", index_)).string(), [&](std::ostream& out) {
    out << "label,triangles,fines,area_m2,mass_kg_per_m,equivalent_diameter_m,sieve_size_m,centroid_x_m,centroid_y_m,"
           "velocity_x_m_per_s,velocity_y_m_per_s\n";
    for (const fdem::Fragment& g : f)
      out << fmt::format("{},{},{},{:.9e},{:.9e},{:.9e},{:.9e},{:.9e},{:.9e},{:.9e},{:.9e}\n", g.label, g.triangles,
                         g.fines ? 1 : 0, g.area, g.mass, g.equivalent_diameter, g.sieve_size, g.centroid[0],
                         g.centroid[1], g.velocity[0], g.velocity[1]);
  });
  const fdem::SizeDistribution& d = sizes_;
  auto size_columns = [&](CsvRecord& o, size_t i) {  // a fit that cannot be made: empty fields
    const fdem::SwebrecFit& sw = d.swebrec;
    const fdem::RosinRammlerFit& rr = d.rosin_rammler;
    const double x = o.header() ? 0.0 : d.size[i];
    o.real("sieve_size_m", x).real("passing", o.header() ? 0.0 : d.passing[i]);
    o.real_if(sw.valid, "swebrec_fit", sw.valid ? fdem::swebrec_passing(x, sw.x50, sw.xmax, sw.b) : 0.0);
    o.real_if(rr.valid, "rosin_rammler_fit", rr.valid ? fdem::rosin_rammler_passing(x, rr.x50, rr.n) : 0.0);
  };
  write_atomically((dir_ / "size_distribution.csv").string(), [&](std::ostream& out) {
    out << csv_text(CsvRecord::Mode::header, [&](CsvRecord& o) { size_columns(o, 0); }) << "\n";
    for (size_t i = 0; i < d.size.size(); ++i)
      out << csv_text(CsvRecord::Mode::row, [&](CsvRecord& o) { size_columns(o, i); }) << "\n";
  });
  fragmentation_->row_of([&](CsvRecord& o) { fragmentation_columns(o); });
}

void RockOutputs::fragmentation_columns(CsvRecord& o) const {
  const fdem::SizeDistribution& d = sizes_;
  o.integer("step", solver_.steps()).real("time_s", solver_.time()).integer("fragments", d.fragments);
  o.integer("sized", d.sized).real("fines_mass_fraction", d.total_mass > 0 ? d.fines_mass / d.total_mass : 0.0, 6);
  o.real("largest_mass_fraction", largest_fraction_, 6).real("x20_m", d.x20, 6).real("x50_m", d.x50, 6);
  o.real("x80_m", d.x80, 6).real("oversize_fraction", d.oversize_fraction, 6);
  const bool sw = d.swebrec.valid, rr = d.rosin_rammler.valid;  // a fit that cannot be made: empty fields
  o.real_if(sw, "swebrec_x50_m", d.swebrec.x50, 6).real_if(sw, "swebrec_xmax_m", d.swebrec.xmax, 6);
  o.real_if(sw, "swebrec_b", d.swebrec.b, 6).real_if(sw, "swebrec_r2", d.swebrec.r_squared, 6);
  o.real_if(rr, "rosin_rammler_x50_m", d.rosin_rammler.x50, 6).real_if(rr, "rosin_rammler_n", d.rosin_rammler.n, 6);
  o.real_if(rr, "rosin_rammler_r2", d.rosin_rammler.r_squared, 6);
  for (size_t k = 0; k < c_.analysis.holes.size(); ++k) {
    const fdem::DamageZone z = o.header() ? fdem::DamageZone{} : zones_[k];
    o.real(fmt::format("hole{}_crushed_radius_m", k), z.crushed_radius, 6);
    o.real(fmt::format("hole{}_cracked_radius_m", k), z.cracked_radius, 6);
  }
}

std::string RockOutputs::summary() const {
  if (analysed_at_ < 0) return {};
  const AnalysisSettings& a = c_.analysis;
  std::string out = fmt::format("\nanalysis of the rock at t = {:.4e} s (docs/analysis.md defines each figure)\n", analysed_at_);
  if (a.fragments) {
    const fdem::SizeDistribution& d = sizes_;
    auto size = [](double x) { return x > 0 ? fmt::format("{:.4f} m", x) : std::string("in the fines"); };
    out += fmt::format("fragments: {} pieces, {} sized (at least {} triangles), fines {:.2f} % of the mass; the largest "
                       "piece holds {:.2f} % of the mass\n", d.fragments, d.sized, a.min_fragment_triangles,
                       d.total_mass > 0 ? 100 * d.fines_mass / d.total_mass : 0.0, 100 * largest_fraction_);
    out += fmt::format("  X20 {}, X50 {}, X80 {} (sieve size: minimum Feret width); oversize (> {:g} m) {:.2f} % of the mass\n",
                       size(d.x20), size(d.x50), size(d.x80), a.oversize, 100 * d.oversize_fraction);
    out += d.swebrec.valid ? fmt::format("  Swebrec fit: x50 {:.4f} m, xmax {:.4f} m{}, b {:.3f}; R^2 {:.4f}\n", d.swebrec.x50,
                                         d.swebrec.xmax,
                                         d.swebrec.xmax_at_bound ? " (at its bound 100 x50: not determined by these pieces)" : "",
                                         d.swebrec.b, d.swebrec.r_squared)
                           : std::string("  Swebrec fit: too few sized fragments (needs 4 points with 0 < P < 1)\n");
    out += d.rosin_rammler.valid
               ? fmt::format("  Rosin-Rammler fit: x50 {:.4f} m, n {:.3f}; R^2 {:.4f}\n", d.rosin_rammler.x50,
                             d.rosin_rammler.n, d.rosin_rammler.r_squared)
               : std::string("  Rosin-Rammler fit: too few sized fragments (needs 3 points with 0 < P < 1)\n");
  }
  for (size_t k = 0; k < zones_.size(); ++k) {
    const fdem::DamageZone& z = zones_[k];
    const std::array<double, 2>& b = a.holes[k].behind;
    out += fmt::format("damage zone around hole {} at ({:g}, {:g}) m, radius {:g} m{} (rings of {:.4f} m): crushed to {:.4f} m "
                       "({:.1f} hole radii), cracked to {:.4f} m ({:.1f} hole radii)\n",
                       k, z.center[0], z.center[1], z.hole_radius,
                       b[0] == 0 && b[1] == 0 ? std::string() : fmt::format(", behind it along ({:g}, {:g})", b[0], b[1]),
                       ring_width_, z.crushed_radius, z.crushed_radius / z.hole_radius, z.cracked_radius,
                       z.cracked_radius / z.hole_radius);
  }
  const std::vector<ProbeSettings::RockPoint>& probes = c_.probes.rock_points;
  if (!probes.empty()) {
    out += "peak particle velocity (largest |v| at each rock probe, updated every step):\n";
    const std::vector<fdem::ProbeSample> p = solver_.probe_samples();
    for (size_t k = 0; k < p.size(); ++k) {
      const auto& q = probes[k].position;
      const std::string dist = a.holes.empty() ? std::string()
                                               : fmt::format(", {:.4f} m from hole 0",
                                                             std::hypot(q[0] - a.holes[0].center[0], q[1] - a.holes[0].center[1]));
      const double until = probes[k].until;
      out += fmt::format("  {} at ({:g}, {:g}) m{}: PPV {:.4g} m/s at {:.4f} ms{}\n", probes[k].name, q[0], q[1], dist,
                         p[k].peak_speed, 1e3 * p[k].peak_time,
                         until < 1e300 ? fmt::format(" (window to {:.4f} ms)", 1e3 * until) : std::string());
    }
  }
  return out;
}

std::string RockOutputs::cost_note() const {
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - started_).count();
  return fmt::format("rock analysis: {:.3f} s over {} snapshots ({:.2f} % of the {:.1f} s wall time since the outputs "
                     "opened)\n", analysis_seconds_, analyses_, wall > 0 ? 100 * analysis_seconds_ / wall : 0.0, wall);
}

void RockOutputs::write_summary() const {
  const std::string text = summary();
  if (text.empty()) return;
  write_atomically((dir_ / "summary.txt").string(), [&](std::ostream& out) {
    out << fmt::format("blastsim rock summary at t = {:.4e} s (step {})\n", solver_.time(), solver_.steps()) << text;
  });
}

fdem::RockEnergies RockOutputs::monitor() {
  const fdem::RockEnergies e = solver_.energies();
  const double balance = fdem::energy_residual(e, e0_);
  // the support reactions on the loaded nodes: the platen force, with the sign of the axes
  const std::vector<std::array<double, 2>> reactions = solver_.support_reactions(velocity_nodes_);
  if (probes_) probes_->row_of([&](CsvRecord& o) { probe_columns(o); });
  series_.row_of([&](CsvRecord& o) { series_columns(o, e, balance, reactions); });
  return e;
}

void RockOutputs::series_columns(CsvRecord& o, const fdem::RockEnergies& e, double balance,
                                 const std::vector<std::array<double, 2>>& reactions) const {
  o.integer("step", solver_.steps()).real("time_s", solver_.time()).real("kinetic_J_per_m", e.kinetic);
  o.real("strain_J_per_m", e.strain).real("joint_work_J_per_m", e.joint_work);
  o.real("fracture_dissipated_J_per_m", e.fracture_dissipated).real("contact_work_J_per_m", e.contact_work);
  o.real("friction_dissipated_J_per_m", e.friction_dissipated).real("damping_dissipated_J_per_m", e.damping_dissipated);
  o.real("external_work_J_per_m", e.external_work).real("energy_balance_J_per_m", balance, 6);
  o.integer("broken_joints", e.broken_joints).real("crack_length_m", e.crack_length, 6);
  o.real("radiated_J_per_m", -e.boundary_work);
  for (size_t k = 0; k < reactions.size(); ++k)
    o.real(fmt::format("velocity{}_reaction_x_N_per_m", k), reactions[k][0])
        .real(fmt::format("velocity{}_reaction_y_N_per_m", k), reactions[k][1]);
}

void RockOutputs::probe_columns(CsvRecord& o) const {
  o.integer("step", solver_.steps()).real("time_s", solver_.time());
  const std::vector<fdem::ProbeSample> p = o.header() ? std::vector<fdem::ProbeSample>(c_.probes.rock_points.size())
                                                      : solver_.probe_samples();
  for (size_t k = 0; k < p.size(); ++k) {
    const std::string& name = c_.probes.rock_points[k].name;
    o.real(name + "_vx_m_per_s", p[k].vx, 6).real(name + "_vy_m_per_s", p[k].vy, 6);
    o.real(name + "_speed_m_per_s", std::hypot(p[k].vx, p[k].vy), 6);
  }
}

}  // namespace blastsim::app
