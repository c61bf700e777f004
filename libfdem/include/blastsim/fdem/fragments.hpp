//! \file fragments.hpp
//! \brief What a blast engineer reads off a rock state: fragments and their sizes, the size distribution with
//! Swebrec and Rosin-Rammler fits, per-triangle damage and the damage zone around a hole. Host functions on a
//! RockSnapshot and the labels of fragment_labels(); docs/analysis.md defines every quantity.
#pragma once

#include "blastsim/fdem/rock_fields.hpp"
#include "blastsim/fdem/rock_types.hpp"

#include <array>
#include <vector>

namespace blastsim::fdem {

//! Default smallest fragment that is sized: a piece needs at least one triangle whose three edges are all
//! inside it (a triangle and its three neighbours, 4 triangles) before its shape comes from fracture rather
//! than from single mesh cells; smaller pieces are reported as fines (docs/analysis.md, "Fines").
inline constexpr int kDefaultMinFragmentTriangles = 4;

//! One fragment: the triangles that share a label.
struct Fragment {
  int label = 0;              //!< the smallest triangle index it holds
  int triangles = 0;
  double area = 0;            //!< current area [m2 per m of thickness]
  double mass = 0;            //!< [kg/m]: density x initial area (conserved)
  double equivalent_diameter = 0;  //!< sqrt(4 A / pi) [m]
  double sieve_size = 0;      //!< minimum Feret width of the convex hull of its nodes [m] (the sieve proxy)
  std::array<double, 2> centroid{};  //!< mass centre [m]
  std::array<double, 2> velocity{};  //!< mass-weighted mean velocity [m/s] (the throw)
  bool fines = false;         //!< fewer triangles than the sizing minimum: counted as fines, not sized
};

//! Fragment label of every triangle: triangles joined through joints that have not broken share a label, the
//! smallest triangle index of their fragment (label propagation with pointer jumping on the device; the same
//! labels on every backend and thread count). Costs a few sweeps over the triangles and a host wait a sweep.
std::vector<int> fragment_labels(const RockReadView& rock);

//! Measures the fragments of a snapshot from per-triangle labels (fragment_labels()); density
//! [kg/m3]; pieces of fewer than `min_triangles` triangles are marked fines. Ordered by label.
std::vector<Fragment> measure_fragments(const RockSnapshot& s, const std::vector<int>& labels, double density,
                                        int min_triangles = kDefaultMinFragmentTriangles);

//! Minimum Feret width [m] of a point set: the smallest distance between two parallel lines that enclose it,
//! found over the edges of its convex hull (the minimum is attained with one line along a hull edge). 0 for
//! fewer than three points or collinear points.
double minimum_feret_width(const std::vector<std::array<double, 2>>& points);

//! Swebrec function of mass passing (Ouchterlony 2005, Fragblast 9(1), eq. 1):
//! P(x) = 1 / (1 + [ln(xmax / x) / ln(xmax / x50)]^b) for 0 < x < xmax, 1 from xmax on.
double swebrec_passing(double x, double x50, double xmax, double b);
//! Rosin-Rammler function in the Kuz-Ram form (Cunningham 1987): P(x) = 1 - exp(-ln 2 (x / x50)^n).
double rosin_rammler_passing(double x, double x50, double n);

//! A least-squares fit of a passing function to (size, passing) points: its parameters, R^2 and the RMS
//! residual of the passing fraction.
//! Largest xmax / x50 a Swebrec fit may reach (measured muck piles: 2 to 20).
inline constexpr double kSwebrecMaxRatio = 100;
struct SwebrecFit {
  bool valid = false;
  double x50 = 0, xmax = 0, b = 0;  //!< [m], [m], [-]
  double r_squared = 0, rms = 0;
  bool xmax_at_bound = false;  //!< xmax reached kSwebrecMaxRatio x x50: the data do not determine it
};
struct RosinRammlerFit {
  bool valid = false;
  double x50 = 0, n = 0;  //!< [m], [-] (uniformity index)
  double r_squared = 0, rms = 0;
};
//! Fits minimise the sum of squared passing residuals over the points with 0 < P < 1 (Levenberg-Marquardt from
//! the linearised estimates); they need at least 3 (Rosin-Rammler) or 4 (Swebrec) such points. The Swebrec
//! fit keeps xmax / x50 below kSwebrecMaxRatio.
SwebrecFit fit_swebrec(const std::vector<double>& size, const std::vector<double>& passing);
RosinRammlerFit fit_rosin_rammler(const std::vector<double>& size, const std::vector<double>& passing);

//! Cumulative mass passing by sieve size, the characteristic sizes and both fits.
struct SizeDistribution {
  int fragments = 0;        //!< all pieces, fines included
  int sized = 0;            //!< pieces sized (not fines)
  double total_mass = 0;    //!< [kg/m]
  double fines_mass = 0;    //!< [kg/m] of the fines; they pass every sieve
  std::vector<double> size;     //!< sieve sizes of the sized fragments, ascending [m]
  std::vector<double> passing;  //!< mass fraction passing at each size (fines + every fragment up to it)
  double x20 = 0, x50 = 0, x80 = 0;  //!< [m] sizes that 20, 50, 80 % of the mass pass (0: within the fines)
  double oversize_size = 0;          //!< [m] the size asked for
  double oversize_fraction = 0;      //!< mass fraction of fragments larger than it
  SwebrecFit swebrec;
  RosinRammlerFit rosin_rammler;
};
//! The distribution of `fragments` (measure_fragments()); `oversize_size` [m] > 0. Sizes between two
//! fragments are interpolated linearly in log(size) along the passing curve.
SizeDistribution size_distribution(const std::vector<Fragment>& fragments, double oversize_size);

//! Size [m] that the fraction p in (0, 1) of the mass passes: 0 when the fines alone pass p; the smallest
//! fragment's size when p lies between the fines and its point; else interpolated linearly in log(size)
//! between the two points of the passing curve around p.
double passing_size(const SizeDistribution& d, double p);

//! Per triangle the largest damage (in [0, 1]) of the joints on its edges; 1 next to a broken joint.
std::vector<double> triangle_damage(const RockSnapshot& s);

//! The damage zone around a hole centre, measured in rings of width `ring_width` [m] from the hole wall
//! (joints sorted by the initial distance of their midpoints): the crushed zone reaches to the outer radius
//! of the last ring, counted from the wall, in which every ring has at least `crushed_fraction` of its joint
//! length broken; the cracked zone to the outer radius of the last ring in which every ring from the wall has
//! some broken joint (cracks connected to the hole, not spalls far from it). Radii from the centre [m]; equal
//! to the hole radius when the zone is empty. With a nonzero `behind` direction only the joints in the half
//! plane (m - centre) . behind >= 0 count: in a bench, the rock behind a hole (away from the free face), whose
//! damage is the depth of the back break.
//! Its crack rose: the broken joint length [m] within the cracked zone by the direction of each joint's middle
//! from the centre, in kRoseSectors sectors of 30 deg counter-clockwise from +x (sector k: [30 k, 30 k + 30)
//! deg); radial cracks that run along the major principal stress fill the sectors on its axis.
//! Its damage profile: every ring from the wall out to the farthest joint or triangle, with the joint length it holds, the
//! broken part of it and the rock's area there (the initial areas of the triangles whose centroids lie in the
//! ring, in the same half plane). broken_length / rock_area is the ring's fracture intensity P21 [m/m2], the
//! trace length of fractures per unit area of a section (Dershowitz & Herda 1992, 33rd US Rock Mechanics
//! Symposium); joint_length / rock_area is the mesh's own, the most a ring can break.
inline constexpr int kRoseSectors = 12;
struct DamageRing {
  double inner_radius = 0, outer_radius = 0;  //!< [m] from the centre
  double joint_length = 0;                    //!< [m] joints whose initial midpoints lie in the ring
  double broken_length = 0;                   //!< [m] the broken ones among them
  double rock_area = 0;                       //!< [m2] initial area of the triangles centred in the ring
};
struct DamageZone {
  std::array<double, 2> center{};
  double hole_radius = 0;
  double crushed_radius = 0;
  double cracked_radius = 0;
  std::array<double, kRoseSectors> crack_rose{};
  std::vector<DamageRing> rings;  //!< ring k spans hole_radius + [k, k + 1) ring_width
};
DamageZone damage_zone(const RockSnapshot& s, const std::array<double, 2>& center, double hole_radius, double ring_width,
                       double crushed_fraction = 0.5, const std::array<double, 2>& behind = {0.0, 0.0});

}  // namespace blastsim::fdem
