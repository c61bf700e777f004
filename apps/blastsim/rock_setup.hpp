//! \file rock_setup.hpp
//! \brief The rock of a case before its run: the model built from the case and checked against what the case
//! places in it, and the rock's time step.
#pragma once

#include "blastsim/fdem/rock_model.hpp"
#include "case.hpp"

#include <ostream>
#include <string>

namespace blastsim::app {

//! The rock model of a case (fdem::build_rock_model() with the case's rock probes), checked against the case
//! (check_against_mesh()).
//! A restart skips the equilibration under the in-situ stress (the checkpoint holds the state it reached); `log`,
//! when given, gets the equilibration's progress lines.
fdem::RockModel make_rock_model(const Case& c, bool restart = false, std::ostream* log = nullptr);
//! What --check adds for a case with rock: the rock model built and checked as the run would build it (mesh,
//! cracks and joints along it, strengths, boundary groups, probes, charges' holes), without the in-situ
//! relaxation; one line on `out` with its size.
void check_rock_model(const Case& c, std::ostream& out);
//! InputError when what the case places in the rock does not fit its mesh: an [[analysis.hole]] centre outside
//! the mesh's bounding box, damage rings wider than the rock, a [[charge]] without a hole of the mesh at its
//! centre (rock within half its hole's radius) or without rock around that hole (none within 1.5 radii).
void check_against_mesh(const Case& c, const fdem::TriangleMesh& mesh);

//! dt [s] of the rock: the fixed time.dt (refused above the stable step, naming it; a coupled run whose rock
//! subcycles divides the gas's step instead) or time.step_fraction x the stable step.
double rock_time_step(const Case& c, const fdem::RockSolver& solver);

//! One log line on the joint sets (each set's joints, open or its strength), or "" without sets.
std::string joint_sets_line(const Case& c, const fdem::RockModel& model);
//! The log line of the in-situ stress and its equilibration ("" without one).
std::string in_situ_line(const Case& c, const fdem::RockModel& model);

}  // namespace blastsim::app
