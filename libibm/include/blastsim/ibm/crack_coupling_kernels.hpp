//! \file crack_coupling_kernels.hpp
//! \brief The kernels that join the crack gas to the rock and the grid (docs/coupling.md "Gas in the cracks"):
//! the channels' geometry from the rock, the hand-over of wide cracks to the grid, the mouths into the grid
//! gas, the deposits of what the cracks gave the cells, and the crack gas's pressure on the crack faces.
//! CrackGasCoupling (crack_gas_coupling.hpp) launches them. Plain header: no backend dependency.
#pragma once

#include "blastsim/cip/deposit_kernels.hpp"
#include "blastsim/cip/eos.hpp"
#include "blastsim/cip/gas_state.hpp"
#include "blastsim/cip/grid.hpp"
#include "blastsim/core/access.hpp"
#include "blastsim/core/field2d.hpp"
#include "blastsim/fdem/contact_kernels.hpp"
#include "blastsim/fdem/rock_fields.hpp"
#include "blastsim/ibm/coupling_kernels.hpp"
#include "blastsim/ibm/crack_gas_kernels.hpp"
#include "blastsim/ibm/immersed_boundary_kernels.hpp"

#include <cmath>
#include <cstdint>

namespace blastsim::ibm {

//! The coupling's own arrays beside the network's, as field lists X(element type, name, comment) (storage in
//! crack_gas_coupling.cpp): per junction its place on the mesh outline (fixed) and its mouth's cell; per
//! segment its initial aperture (fixed) and the gas it hands to the grid; per deposit record (the mouths, then
//! the segments) the sort by cell that makes the deposits' sums independent of the thread order.
#define BLASTSIM_CRACK_JUNCTION_PLACES(X) X(std::uint8_t, outline, "1: the junction's vertex lies on the mesh outline")
#define BLASTSIM_CRACK_SEGMENT_PARAMS(X)                                                                    \
  X(double, initial_aperture, "opening [m] of a pre-cut crack whose faces touch")                           \
  X(double, closure_stiffness, "Barton-Bandis initial normal stiffness K_ni [Pa/m] of an open joint")       \
  X(double, max_closure, "Barton-Bandis maximum closure V_m [m] of an open joint (0: its aperture does not close)")
//! A mouth draws from (and gives to) the grid cells at kMouthSamples points across its opening, so that an opening
//! wider than a cell is not fed through one cell.
inline constexpr int kMouthSamples = 3;
#define BLASTSIM_CRACK_MOUTH_CELLS(X)                                                                        \
  X(int, cell, "per junction kMouthSamples cells i + nx j its mouth opens into (-1: none), junction-major")   \
  X(int, sharers, "how many mouth samples (of all junctions) open into that cell")                            \
  X(ChannelConserved, share, "the sample's share of its junction's deposit, per quantity (q unused)")
#define BLASTSIM_CRACK_HANDOVERS(X)                                                                  \
  X(std::uint8_t, pending, "1: the segment handed its gas over; it goes to its gap's cells in after_rock") \
  X(ChannelConserved, gas, "the gas it hands over")                                                  \
  X(int, samples, "how many of its kHandoverSamples points found a cell in this step (0: none)")            \
  X(std::uint8_t, reverted, "1: the grid gave the segment back to its channel since the last after_cells")
//! A segment hands its gas to the grid at kHandoverSamples points of its gap (four along it, two across), in
//! equal shares, so that a gap several cells long and wide does not receive it in one cell.
inline constexpr int kHandoverAlong = 4, kHandoverAcross = 2, kHandoverSamples = kHandoverAlong * kHandoverAcross;
#define BLASTSIM_CRACK_HANDOVER_CELLS(X) \
  X(int, cell, "per segment kHandoverSamples cells i + nx j its handed gas goes to in this step (-1: none), segment-major")
//! Where a crack's faces stood when its cushion last set their load (CrackCushionKernel): the four nodes at the
//! ledger positions x - v dt / 2 [m], and each face's outward normal scaled by its length [m] at the positions x
//! the rock's step computes the load from.
struct CushionFaces {
  double ax0, ay0, ax1, ay1, bx0, by0, bx1, by1;
  double nax, nay, nbx, nby;
};
}  // namespace blastsim::ibm
BLASTSIM_CHECKPOINT_REALS(blastsim::ibm::CushionFaces)
namespace blastsim::ibm {
//! Per segment, the gas as a cushion between its faces over one rock substep (set before every substep from the
//! gas the channel solver just advanced, paid for before the next: CrackGeometryKernel): the load its faces
//! carry and where they stood.
#define BLASTSIM_CRACK_CUSHION(X)                                                                   \
  X(std::uint8_t, on, "1: the faces carry this cushion's load since the last geometry update")     \
  X(double, applied, "the pressure [Pa] the faces carry now (the gas's times dw / do)")           \
  X(CushionFaces, faces, "where the faces stood when that load was set")
//! Cumulative ledgers (checkpointed): per deposit record what it gave the grid's cells, per segment the work its
//! gas did on the crack's walls (docs/coupling.md "Energy budget with crack gas").
#define BLASTSIM_CRACK_EXCHANGE_LEDGER(X)                                                                      \
  X(ChannelConserved, to_grid, "per record: gas given to the cells since the start (q unused)")                 \
  X(double, momentum_x, "per record: x momentum [kg/s] of the gas given to the cells since the start")         \
  X(double, momentum_y, "per record: y momentum [kg/s] of the gas given to the cells since the start")         \
  X(double, refused_x, "per record: x momentum [kg/s] its cell had no free face to take (on the walls)")        \
  X(double, refused_y, "per record: y momentum [kg/s] its cell had no free face to take (on the walls)")
#define BLASTSIM_CRACK_WALL_LEDGER(X)                                                                   \
  X(double, wall_work, "per segment: work [J/m] of its gas on the walls since the start")              \
  X(double, unpaid_work, "per segment: work [J/m] its loads did on the rock beyond what its gas paid")          \
  X(double, taken_mass, "per segment: gas [kg/m] it took from covered cells of its gap (reverse hand-over)")     \
  X(double, taken_energy, "per segment: energy [J/m] it took with that gas")
#define BLASTSIM_CRACK_DEPOSIT_ORDER(X)                            \
  X(int, key, "cell key of each record (INT_MAX: none), sorted")   \
  X(int, record, "the record at each sorted position")

BLASTSIM_CONST_GROUP(CrackJunctionPlaces, BLASTSIM_CRACK_JUNCTION_PLACES)
BLASTSIM_CONST_GROUP(CrackSegmentParams, BLASTSIM_CRACK_SEGMENT_PARAMS)
BLASTSIM_VIEW_GROUP(CrackMouthCells, BLASTSIM_CRACK_MOUTH_CELLS)
BLASTSIM_VIEW_GROUP(CrackHandovers, BLASTSIM_CRACK_HANDOVERS)
BLASTSIM_VIEW_GROUP(CrackHandoverCells, BLASTSIM_CRACK_HANDOVER_CELLS)
BLASTSIM_VIEW_GROUP(CrackCushion, BLASTSIM_CRACK_CUSHION)
BLASTSIM_VIEW_GROUP(CrackDepositOrder, BLASTSIM_CRACK_DEPOSIT_ORDER)
BLASTSIM_VIEW_GROUP(CrackExchangeLedger, BLASTSIM_CRACK_EXCHANGE_LEDGER)
BLASTSIM_VIEW_GROUP(CrackWallLedger, BLASTSIM_CRACK_WALL_LEDGER)

//! Hydraulic aperture of a crack from the normal opening o of its faces [m] and the residual aperture w_r [m]:
//! w = w_r + o while open (o >= 0). Pressed together (o < 0), the asperities that keep a closed crack's void
//! close hyperbolically, as a rock joint does under normal stress (Bandis, Lumsden & Barton 1983, Int. J. Rock
//! Mech. Min. Sci. 20:249: bounded closure), towards w_r / 2: w = w_r / 2 + (w_r / 2) / (1 - 2 o / w_r), which
//! joins w_r + o with the same value and slope at o = 0. So a crack squeezed shut compresses its gas by at most
//! the ratio of its volume to that floor (docs/coupling.md "Closing cracks"). dw_dopening scales the gas's
//! pressure on the faces, so that their work p L dw_dopening do is the gas's p dV exactly: a closed crack's gas
//! loads its faces less the more they are pressed together.
struct CrackWidth {
  double w, dw_dopening;
};
BLAST_HD inline CrackWidth crack_width(double opening, double residual) {
  if (opening >= 0) return {residual + opening, 1.0};
  const double f = 1.0 / (1.0 - 2.0 * opening / residual);
  return {0.5 * residual * (1.0 + f), f * f};
}

//! Mean pressure [Pa] of a gas (pressure p [Pa], internal energy U [J/m] in volume V0 [m2 per m]) over an
//! isentropic change of its volume to V1: its work U (1 - (V0 / V1)^G) over V1 - V0, at the gas's effective
//! Gruneisen coefficient G = p V0 / U (exact for an ideal gas; JWL products and mixtures take the local G).
//! Below p when it expands, above when it is compressed; p itself for V1 = V0.
BLAST_HD inline double isentropic_mean_pressure(double p, double U, double V0, double V1) {
  if (!(p > 0.0) || !(U > 0.0) || !(V0 > 0.0) || !(V1 > 0.0) || fabs(V1 / V0 - 1.0) < 1e-9) return p;
  return U * (1.0 - pow(V0 / V1, p * V0 / U)) / (V1 - V0);
}

//! The work [J/m] a segment's gas (conserved c, pressure p [Pa] in volume V0 [m2 per m]) pays for its walls'
//! motion to V1, when its loads did the work W [J/m] on the rock: W, unless W would take more than half of its
//! internal energy U (a segment whose faces flew apart much faster than its loads followed); then the
//! isentropic expansion's work, which keeps U positive.
BLAST_HD inline double expansion_work(const ChannelConserved& c, double W, double p, double V0, double V1) {
  const double U = c.E - 0.5 * c.q * c.q / c.m;
  if (!(W > 0.5 * U) || !(U > 0.0)) return W;
  return isentropic_mean_pressure(p, U, V0, V1) * (V1 - V0);
}

using fdem::segment_distance2;  // fdem/triangle_kernels.hpp

//! Smallest distance [m] between the segments p0 - p1 and q0 - q1: 0 where they cross.
BLAST_HD inline double segments_distance(const fdem::Vec2& p0, const fdem::Vec2& p1, const fdem::Vec2& q0,
                                         const fdem::Vec2& q1) {
  using fdem::cross3;
  const double s0 = cross3(p0, p1, q0), s1 = cross3(p0, p1, q1), t0 = cross3(q0, q1, p0), t1 = cross3(q0, q1, p1);
  if (((s0 > 0 && s1 < 0) || (s0 < 0 && s1 > 0)) && ((t0 > 0 && t1 < 0) || (t0 < 0 && t1 > 0))) return 0.0;
  const double d2 = fmin(fmin(segment_distance2(p0, p1, q0.x, q0.y), segment_distance2(p0, p1, q1.x, q1.y)),
                         fmin(segment_distance2(q0, q1, p0.x, p0.y), segment_distance2(q0, q1, p1.x, p1.y)));
  return sqrt(d2);
}

//! The mean opening [m] of a crack whose face A runs a0 -> a1 and face B b0 -> b1 (a0 faces b1, a1 faces b0;
//! lengths la, lb > 0), positive when the faces stand apart, negative when pressed into each other. For faces
//! that face each other (parallel, hinged, slid along each other, pressed) it is the area a between them (the
//! quadrilateral a0 a1 b0 b1, by the shoelace formula) over their mean length L, the mean of the two ends'
//! normal openings; there the faces' nearest points stand no farther apart than |a|. A fragment thrown off
//! breaks this: faces that turned away from each other can enclose no area however far apart they are (the
//! quadrilateral folds into a bow tie), faces that passed each other enclose a negative one (it turns inside
//! out), and faces slid past each other's ends keep the area of their old overlap. So:
//! - a negative area beyond a tenth of L is a fold, not a pressed crack: contact keeps real overlaps to about
//!   stress / penalty x L (a few thousandths of L at a GPa and the default penalty 10 E); its magnitude is
//!   taken instead, blended in linearly between 0.1 and 0.2 L so that the opening stays continuous;
//! - where the faces' nearest points stand farther apart than that magnitude, the opening grows by the
//!   difference: it is their distance.
//! Pressed faces keep their negative opening (the closure law's), and faces apart read at least their distance.
BLAST_HD inline double faces_opening(const fdem::Vec2& a0, const fdem::Vec2& a1, const fdem::Vec2& b0,
                                     const fdem::Vec2& b1, double la, double lb) {
  // Shoelace over a0 -> a1 -> b0 -> b1: the gap lies to the right of a0 -> a1, so an open crack turns clockwise.
  const double twice = (a0.x * a1.y - a1.x * a0.y) + (a1.x * b0.y - b0.x * a1.y) + (b0.x * b1.y - b1.x * b0.y) +
                       (b1.x * a0.y - a0.x * b1.y);
  const double L = 0.5 * (la + lb), area = -twice / (la + lb);
  const double fold = fmin(1.0, fmax(0.0, (-area / L - 0.1) / 0.1));  // 0: pressed or open; 1: a fold
  const double a = area + fold * (fabs(area) - area);
  return a + fmax(0.0, segments_distance(a0, a1, b0, b1) - fabs(a));
}

//! Closure [m] of an open joint's asperities under the effective normal stress sigma [Pa] (compression
//! positive), by the hyperbola of Bandis, Lumsden & Barton (1983, Int. J. Rock Mech. Min. Sci. 20:249; Barton,
//! Bandis & Bakhtar 1985, Int. J. Rock Mech. Min. Sci. 22:121): dV = sigma V_m / (K_ni V_m + sigma), with the
//! initial normal stiffness K_ni [Pa/m] and the maximum closure V_m [m]; its slope at sigma = 0 is 1 / K_ni and
//! it tends to V_m. 0 for sigma <= 0 or V_m = 0 (no closure law).
BLAST_HD inline double joint_closure(double sigma, double stiffness, double max_closure) {
  if (!(sigma > 0.0) || !(max_closure > 0.0)) return 0.0;
  return sigma * max_closure / (stiffness * max_closure + sigma);
}

//! The effective normal stress [Pa] (compression positive) on the asperities of joint s: the mean of its two
//! triangles' normal stress n . T n across the joint (T of their last step, RockReadView::triangles), less the
//! pressure p [Pa] of the gas in it, which carries that part of the load.
BLAST_HD inline double joint_asperity_stress(const fdem::RockView& rock, int s, double p) {
  const fdem::JointNodes jn = rock.joint.nodes[s];
  const fdem::NodeMotion<Access::read>& x = rock.nodes;
  const fdem::Vec2 n = fdem::edge_outward_normal(x.position(jn.a0), x.position(jn.a1));
  const double len2 = n.x * n.x + n.y * n.y;
  if (!(len2 > 0.0)) return 0.0;
  auto normal_stress = [&](int slot) {
    const fdem::TriangleStress T = rock.triangles.stress[slot / 3];
    return (T.xx * n.x * n.x + 2.0 * T.xy * n.x * n.y + T.yy * n.y * n.y) / len2;
  };
  return -0.5 * (normal_stress(jn.a0) + normal_stress(jn.b0)) - p;
}

//! The faces of joint s in the rock's current state: their nodes' positions (a0 -> a1 is face A, b0 -> b1 face B;
//! a0 faces b1, a1 faces b0), the lengths, and the crack's mean opening [m] (faces_opening()).
//! `lag` [s] > 0 takes the positions x - lag v instead: with half the rock's last step (RockSolver::last_step()),
//! the positions along which the rock's work ledger pays the loads.
struct JointFaces {
  fdem::Vec2 a0, a1, b0, b1;
  double la, lb, opening;
};
BLAST_HD inline JointFaces joint_faces(const fdem::RockView& rock, int s, double lag = 0.0) {
  const fdem::JointNodes jn = rock.joint.nodes[s];
  const fdem::NodeMotion<Access::read>& x = rock.nodes;
  auto at = [&](int n) { return fdem::Vec2{x.x[n] - lag * x.vx[n], x.y[n] - lag * x.vy[n]}; };
  JointFaces f{at(jn.a0), at(jn.a1), at(jn.b0), at(jn.b1), 0.0, 0.0, 0.0};
  f.la = sqrt((f.a1.x - f.a0.x) * (f.a1.x - f.a0.x) + (f.a1.y - f.a0.y) * (f.a1.y - f.a0.y));
  f.lb = sqrt((f.b1.x - f.b0.x) * (f.b1.x - f.b0.x) + (f.b1.y - f.b0.y) * (f.b1.y - f.b0.y));
  f.opening = faces_opening(f.a0, f.a1, f.b0, f.b1, f.la, f.lb);
  return f;
}

//! Hydraulic aperture of segment s (crack_width()) from its faces f, its initial aperture and, for an open joint
//! with a closure law whose faces touch (f.opening <= 0: the asperities carry the load only in contact), the
//! Barton-Bandis closure of its asperities under the effective normal stress with its gas at pressure p [Pa]
//! (joint_closure(), joint_asperity_stress()): the opening w_r + o + a_0 - dV.
BLAST_HD inline CrackWidth segment_width(const fdem::RockView& rock, const CrackSegmentParams& params, int s,
                                         const JointFaces& f, double p, double residual_aperture) {
  const double closure =
      params.max_closure[s] > 0.0 && f.opening <= 0.0
          ? joint_closure(joint_asperity_stress(rock, s, p), params.closure_stiffness[s], params.max_closure[s])
          : 0.0;
  return crack_width(f.opening + params.initial_aperture[s] - closure, residual_aperture);
}

//! The area [m2 per m] the two faces swept away from each other since they stood at `was`, as the rock's work
//! ledger measures a uniform unit pressure's work on them: -1/2 n . (the move of each of the face's two nodes),
//! n the face's outward normal times its length where the load was computed.
BLAST_HD inline double swept_area(const CushionFaces& was, const JointFaces& now) {
  return -0.5 * (was.nax * (now.a0.x - was.ax0 + now.a1.x - was.ax1) + was.nay * (now.a0.y - was.ay0 + now.a1.y - was.ay1) +
                 was.nbx * (now.b0.x - was.bx0 + now.b1.x - was.bx1) + was.nby * (now.b0.y - was.by0 + now.b1.y - was.by1));
}

//! The crack widths [m] at which a segment's gas goes to the grid and back (docs/coupling.md "Hand-over"): its
//! faces at least `handover` apart (CrackGasOptions::handover_width cells), back below half of that.
struct HandoverGaps {
  double handover, back;
};

//! Every joint's channel from the rock (one thread per joint = segment), in the immersed boundary's cover stage,
//! before the cells' masks are made: length L (mean of its two faces), aperture w from their mean opening plus
//! its initial aperture (crack_width()), volume L w. A joint that just broke becomes a gas segment holding
//! nothing (a crack born inside the rock is empty: its gas can only come from its neighbours, so the total is
//! kept exactly), or a grid segment if it is already wide; a gas segment whose volume changes does the work p dV on its walls
//! (E -= p dV: the rock's edge pressures do the same work on the rock). Hand-over: a gas segment whose faces
//! are at least gaps.handover apart gives its gas to the grid (held in `handovers` until after_gas puts it in
//! a cell of the crack) and the grid carries the crack from then on; a grid segment whose faces come back
//! within gaps.back takes its own gas again (`reverted`): it starts empty, and when its gap's cells are covered
//! their gas goes to their stable neighbours or, with none, to the segment (CrackClaimedGasKernel). So the two
//! gases never share a crack.
struct CrackGeometryKernel {
  fdem::RockView rock;
  cip::GasMaterials mat;
  CrackSegmentParams params;
  CrackGeometry<Access::read_write> geo;
  CrackSegments<Access::read_write> seg;
  CrackHandovers<Access::read_write> handovers;
  CrackCushion<Access::read_write> cushion;
  CrackWallLedger<Access::read_write> ledger;
  double residual_aperture;
  HandoverGaps gaps;
  double lag;             //!< [s] half the rock's last step (joint_faces())
  double vacuum_density;  //!< [kg/m3] CrackGas::vacuum_density()
  BLAST_HD void operator()(index_t ji) const {
    const int s = static_cast<int>(ji);
    if (!rock.joints.broken[s]) {
      seg.kind[s] = kSegmentNone;
      return;
    }
    const JointFaces f = joint_faces(rock, s, lag);
    const CrackWidth cw = segment_width(rock, params, s, f, seg.prim[s].p, residual_aperture);
    const double L = 0.5 * (f.la + f.lb), w = cw.w, V = L * w;
    geo.length[s] = L, geo.aperture[s] = w;
    // the axis from end 0 (nodes a0, b1) to end 1 (a1, b0): the direction of the segment's momentum
    const double ax = f.a1.x + f.b0.x - f.a0.x - f.b1.x, ay = f.a1.y + f.b0.y - f.a0.y - f.b1.y;
    const double alen = sqrt(ax * ax + ay * ay);
    geo.axis_x[s] = alen > 0.0 ? ax / alen : 0.0, geo.axis_y[s] = alen > 0.0 ? ay / alen : 0.0;
    const std::uint8_t kind = seg.kind[s];
    const bool loaded = cushion.on[s] != 0;
    cushion.on[s] = 0;
    const bool wide = f.opening >= (kind == kSegmentGrid ? gaps.back : gaps.handover);
    if (kind == kSegmentNone || (kind == kSegmentGrid && !wide)) {
      seg.kind[s] = wide ? kSegmentGrid : kSegmentGas, seg.cons[s] = {0, 0, 0, 0, 0}, seg.volume[s] = V;
      if (kind == kSegmentGrid) handovers.reverted[s] = 1;  // its gap's cells give it their gas (after_cells)
      return;
    }
    if (kind != kSegmentGas) return;
    ChannelConserved c = seg.cons[s];
    const double V_old = seg.volume[s];
    const ChannelPrimitive P = segment_state(mat, c, V_old, vacuum_density);
    if (loaded && !is_vacuum(P)) {  // the work of the cushion's load over the last rock substep
      const double W_rock = cushion.applied[s] * swept_area(cushion.faces[s], f);
      const double W = expansion_work(c, W_rock, P.p, V_old, V);
      c.E -= W;
      ledger.wall_work[s] += W;
      ledger.unpaid_work[s] += W_rock - W;
    }
    seg.volume[s] = V;
    if (wide) {
      ChannelConserved h = handovers.pending[s] ? handovers.gas[s] : ChannelConserved{0, 0, 0, 0, 0};
      h = {h.m + c.m, h.q + c.q, h.E + c.E, h.m1 + c.m1, h.am + c.am};
      handovers.gas[s] = h, handovers.pending[s] = 1;
      seg.kind[s] = kSegmentGrid, c = {0, 0, 0, 0, 0};
    }
    seg.cons[s] = c;
  }
};

//! Calls visit(face, i, j, nearer_a) for every face point (face 0: x-faces, 1: y-faces) inside the gap of a
//! crack with faces f: the quadrilateral between them as two triangles (a0, a1, b0) and (a0, b0, b1), over the
//! points of the quadrilateral's box, in a fixed order; nearer_a: the point lies nearer face A than face B.
template <class Visit>
BLAST_HD inline void for_each_gap_point(const cip::GasGrid& g, const JointFaces& f, const Visit& visit) {
  const double tx[2][3] = {{f.a0.x, f.a1.x, f.b0.x}, {f.a0.x, f.b0.x, f.b1.x}};
  const double ty[2][3] = {{f.a0.y, f.a1.y, f.b0.y}, {f.a0.y, f.b0.y, f.b1.y}};
  const double qx[4] = {f.a0.x, f.a1.x, f.b0.x, f.b1.x}, qy[4] = {f.a0.y, f.a1.y, f.b0.y, f.b1.y};
  for (int face = 0; face < 2; ++face) {
    const FaceBox b = triangle_face_box(g, qx, qy, face);
    const FaceBox b2 = triangle_face_box(g, qx + 1, qy + 1, face);  // the quad's box: both triangles' union
    const int i0 = imin(b.i0, b2.i0), i1 = imax(b.i1, b2.i1), j0 = imin(b.j0, b2.j0), j1 = imax(b.j1, b2.j1);
    for (int j = j0; j <= j1; ++j)
      for (int i = i0; i <= i1; ++i) {
        const double px = g.x_min + (i + b.ox) * g.dx, py = g.y_min + (j + b.oy) * g.dy;
        double w[3];
        const bool in = (barycentric(tx[0], ty[0], px, py, w) && inside(w)) ||
                        (barycentric(tx[1], ty[1], px, py, w) && inside(w));
        if (in) visit(face, i, j, segment_distance2(f.a0, f.a1, px, py) <= segment_distance2(f.b0, f.b1, px, py));
      }
  }
}

//! The cells beside face point (i, j) of `face` (0: x-face between cells i - 1 and i; 1: y-face between j - 1
//! and j) that lie in the grid: calls visit(ci, cj) for each.
template <class Visit>
BLAST_HD inline void for_each_face_cell(const cip::GasGrid& g, int face, int i, int j, const Visit& visit) {
  const int i0 = face == 0 ? i - 1 : i, j0 = face == 0 ? j : j - 1;
  if (i0 >= 0 && j0 >= 0) visit(i0, j0);
  if (i < g.nx && j < g.ny) visit(i, j);
}

//! The gap of every crack that holds its own gas is solid to the grid (one thread per joint): the face points
//! (x-faces for u, y-faces for v) between its two faces take, as owner, the triangle of the nearer face, so a
//! crack narrower than the hand-over width opens no grid cell: the grid cannot carry its flow (a face row
//! along it would carry a cell's width of gas through a micron-wide crack, and a crack a few tenths of a cell
//! wide opens isolated cells), and its gas is the channel's alone. A segment that the grid just gave back
//! (`reverted`: the reverse hand-over) claims the cells beside those points (CellClaims): one covered with no
//! stable cell beside it gives the segment its gas (CrackClaimedGasKernel) instead of losing it. Only then: an
//! isolated pocket that a narrow crack closes (a cut cell over a crack line) holds a cell's volume of gas by the
//! grid's count, too much for a channel of microns. Order-independent (atomic maxima), as the triangles' own
//! cover.
struct CrackGapCoverKernel {
  fdem::RockView rock;
  cip::GasGrid g;
  CrackSegments<Access::read> seg;
  CrackHandovers<Access::read> handovers;  //!< reads `reverted`
  FaceOwners<Access::read_write> owners;
  Field2D<int> claim;  //!< CellClaims::claim
  BLAST_HD void operator()(index_t ji) const {
    const int s = static_cast<int>(ji);
    if (seg.kind[s] != kSegmentGas) return;
    const JointFaces f = joint_faces(rock, s);
    if (!(f.opening > 0.0)) return;
    const fdem::JointNodes jn = rock.joint.nodes[s];
    const int tri_a = jn.a0 / 3, tri_b = jn.b0 / 3;
    const bool claims = handovers.reverted[s] != 0;
    for_each_gap_point(g, f, [&](int face, int i, int j, bool nearer_a) {
      atomic_max(&(face == 0 ? owners.u : owners.v)(i, j), nearer_a ? tri_a : tri_b);
      if (claims) for_each_face_cell(g, face, i, j, [&](int ci, int cj) { atomic_max(&claim(ci, cj), s); });
    });
  }
};

//! The reverse hand-over (after_cells, one thread per joint): a gas segment that the grid just gave back collects
//! the gas that the cells it claims (CrackGapCoverKernel) gave up when they were covered with no stable cell
//! beside them
//! (ibm::TransitionKernel: their mass, internal energy with their faces' kinetic energy, and materials; their
//! momentum went to the walls, as any covered cell's), and clears it; the walls' ledger books what it took. The
//! cells are visited in the gap's fixed order, each once per face point beside it: what a cell gave is taken at
//! its first visit, so the sums do not depend on the schedule.
struct CrackClaimedGasKernel {
  fdem::RockView rock;
  cip::GasGrid g;
  CrackSegments<Access::read_write> seg;
  CrackHandovers<Access::read_write> handovers;  //!< `reverted`, cleared here
  CrackWallLedger<Access::read_write> ledger;
  Field2D<const int> claim;
  Field2D<cip::CellContent> taken;
  BLAST_HD void operator()(index_t ji) const {
    const int s = static_cast<int>(ji);
    if (!handovers.reverted[s]) return;
    handovers.reverted[s] = 0;
    if (seg.kind[s] != kSegmentGas) return;
    const JointFaces f = joint_faces(rock, s);
    if (!(f.opening > 0.0)) return;
    const double area = g.cell_area();
    ChannelConserved c = seg.cons[s];
    double m = 0, E = 0;
    for_each_gap_point(g, f, [&](int face, int i, int j, bool) {
      for_each_face_cell(g, face, i, j, [&](int ci, int cj) {
        if (claim(ci, cj) != s) return;
        const cip::CellContent t = taken(ci, cj);
        if (t.mass == 0.0 && t.energy == 0.0) return;
        m += t.mass * area, E += t.energy * area;
        c.m1 += t.products_mass * area, c.am += t.alpha_mass * area;
        taken(ci, cj) = cip::CellContent{0, 0, 0, 0};
      });
    });
    if (m == 0.0 && E == 0.0) return;
    c.m += m, c.E += E;
    seg.cons[s] = c;
    ledger.taken_mass[s] += m, ledger.taken_energy[s] += E;
  }
};

//! The active cell whose centre is nearest to (x, y) in the 3 x 3 block of cells around it, in (fi, fj);
//! false when none is active (or the point lies off the grid by more than a cell).
BLAST_HD inline bool nearest_active_cell(const cip::GasGrid& g, const Field2D<const std::uint8_t>& active, double x,
                                         double y, int& fi, int& fj) {
  const int ci = static_cast<int>(floor((x - g.x_min) / g.dx)), cj = static_cast<int>(floor((y - g.y_min) / g.dy));
  double best = 1e300;
  fi = fj = -1;
  for (int j = imax(0, cj - 1); j <= imin(g.ny - 1, cj + 1); ++j)
    for (int i = imax(0, ci - 1); i <= imin(g.nx - 1, ci + 1); ++i) {
      if (!active(i, j)) continue;
      const double dx = g.cell_x(i) - x, dy = g.cell_y(j) - y, d = dx * dx + dy * dy;
      if (d < best) best = d, fi = i, fj = j;
    }
  return fi >= 0;
}

//! Which junctions open into the grid gas, and its state there (one thread per junction). A junction is a
//! mouth where the crack network truly meets open gas: a vertex on the mesh outline (the blasthole wall, the
//! free face, the rim of a fragment) or a vertex where a crack that the grid carries (kSegmentGrid) ends. An
//! active cell over an interior vertex of narrow cracks is no mouth: it is a cut cell whose open part lies on
//! the far side of rock. The mouth's opening is the first gas segment's end there, from one face's node to the
//! other's; at kMouthSamples points across it, half a cell out of the crack, the nearest active cell (3 x 3
//! block) is one of the mouth's cells, and its reservoir is their gas, mixed, at rest (their mean density,
//! their mass-weighted energy and fractions). A mouth without an active cell is closed.
struct CrackMouthKernel {
  fdem::RockView rock;
  cip::GasMaterials mat;
  cip::GasGrid g;
  Field2D<const std::uint8_t> active;
  cip::GasCellsRead cells;
  CrackGraph graph;
  CrackSegments<Access::read> seg;
  CrackJunctionPlaces places;
  CrackMouths<Access::read_write> mouths;
  CrackMouthCells<Access::read_write> mouth_cells;
  double vacuum_density;  //!< [kg/m3] CrackGas::vacuum_density()
  BLAST_HD void operator()(index_t ji) const {
    const int J = static_cast<int>(ji);
    mouths.open[J] = 0;
    for (int k = 0; k < kMouthSamples; ++k) mouth_cells.cell[kMouthSamples * J + k] = -1;
    int end = -1;
    bool open = places.outline[J] != 0;
    for (int k = graph.junction_offset[J]; k < graph.junction_offset[J + 1]; ++k) {
      const std::uint8_t kind = seg.kind[graph.junction_entry[k] / 2];
      if (kind == kSegmentGas && end < 0) end = graph.junction_entry[k];
      open = open || kind == kSegmentGrid;
    }
    if (end < 0 || !open) return;
    const fdem::JointNodes jn = rock.joint.nodes[end / 2];
    const int na = end % 2 == 0 ? jn.a0 : jn.a1, nb = end % 2 == 0 ? jn.b1 : jn.b0;
    const int oa = end % 2 == 0 ? jn.a1 : jn.a0, ob = end % 2 == 0 ? jn.b0 : jn.b1;  // the segment's other end
    const double ax = rock.nodes.x[na], ay = rock.nodes.y[na], bx = rock.nodes.x[nb], by = rock.nodes.y[nb];
    // out of the crack: from the middle of its other end towards this one, half a cell
    double ox = 0.5 * (ax + bx - rock.nodes.x[oa] - rock.nodes.x[ob]), oy = 0.5 * (ay + by - rock.nodes.y[oa] - rock.nodes.y[ob]);
    const double len = sqrt(ox * ox + oy * oy), shift = 0.5 * (g.dx > g.dy ? g.dx : g.dy);
    ox = len > 0.0 ? shift * ox / len : 0.0, oy = len > 0.0 ? shift * oy / len : 0.0;
    double mass = 0.0, energy = 0.0, products = 0.0, alpha_mass = 0.0;
    ChannelConserved content[kMouthSamples];  // each sample cell's mass, internal energy, products, alpha mass
    int found = 0;
    for (int k = 0; k < kMouthSamples; ++k) {
      content[k] = {0, 0, 0, 0, 0};
      const double t = (k + 0.5) / kMouthSamples;
      int fi = -1, fj = -1;
      if (!nearest_active_cell(g, active, ax + t * (bx - ax) + ox, ay + t * (by - ay) + oy, fi, fj)) continue;
      mouth_cells.cell[kMouthSamples * J + k] = fj * g.nx + fi;
      ++found;
      const double rho = cells.s.rho.f(fi, fj);
      const cip::GasCellsRead::Fractions f = cells.fractions(fi, fj);
      content[k] = {rho, 0.0, rho * cells.s.e.f(fi, fj), rho * f.Y, rho * f.alpha};
      mass += rho, energy += content[k].E, products += content[k].m1, alpha_mass += content[k].am;
    }
    if (found == 0) return;
    mouths.open[J] = 1;
    mouths.reservoir[J] =
        channel_state(mat, mass / found, 0.0, energy / mass, products / mass, alpha_mass / mass, vacuum_density);
    // Each sample's share of what the mouth moves: of each quantity in proportion to its cell's own content of
    // it (a quantity none of them holds, in proportion to mass). So a draw takes the same fraction of every
    // sample cell's mass, internal energy and fractions, a cold cell does not pay for a hot neighbour's enthalpy,
    // and no cell's fraction leaves [0, 1].
    for (int k = 0; k < kMouthSamples; ++k) {
      const ChannelConserved& c = content[k];
      mouth_cells.share[kMouthSamples * J + k] =
          mouth_cells.cell[kMouthSamples * J + k] < 0
              ? ChannelConserved{0, 0, 0, 0, 0}
              : ChannelConserved{c.m / mass, 0.0, energy > 0.0 ? c.E / energy : c.m / mass,
                                 products > 0.0 ? c.m1 / products : c.m / mass,
                                 alpha_mass > 0.0 ? c.am / alpha_mass : c.m / mass};
    }
  }
};

//! How many mouth samples open into each cell (one thread per sorted record; the first of a run of equal cell
//! keys counts the run's mouth records and writes the count to each of them): cells shared by the mouths of
//! several junctions lend each of them only their share of their gas (MouthHeldGasKernel).
struct MouthSharersKernel {
  CrackDepositOrder<Access::read> order;
  CrackMouthCells<Access::read_write> mouth_cells;
  int mouth_records, records;
  BLAST_HD void operator()(index_t ki) const {
    const int k = static_cast<int>(ki);
    const int c = order.key[k];
    if (c == 0x7fffffff || (k > 0 && order.key[k - 1] == c)) return;
    int n = 0, end = k;
    for (; end < records && order.key[end] == c; ++end) n += order.record[end] < mouth_records ? 1 : 0;
    for (int r = k; r < end; ++r)
      if (order.record[r] < mouth_records) mouth_cells.sharers[order.record[r]] = n;
  }
};

//! The gas a mouth may draw on (one thread per open junction): its sample cells' gas over the largest number of
//! mouth samples that share one of them. The junction draws at most a quarter of it over a coupled step
//! (JunctionFluxKernel) and takes it from each sample cell in proportion to the cell's mass (CrackMouthKernel's
//! shares), so the mouths that open into one cell take at most a quarter of its gas together, and the same
//! fraction of its internal energy times h0 / e of the mixed reservoir (gamma for an ideal gas at rest: at most
//! 0.35 of it for gamma 1.4), which keeps it positive.
struct MouthHeldGasKernel {
  cip::GasGrid g;
  cip::GasCellsRead cells;
  CrackMouthCells<Access::read> mouth_cells;
  CrackMouths<Access::read_write> mouths;
  BLAST_HD void operator()(index_t ji) const {
    const int J = static_cast<int>(ji);
    if (!mouths.open[J]) return;
    double mass = 0.0;
    int most = 1;
    for (int k = 0; k < kMouthSamples; ++k) {
      const int rec = kMouthSamples * J + k, c = mouth_cells.cell[rec];
      if (c < 0) continue;
      mass += cells.s.rho.f(c % g.nx, c / g.nx) * g.cell_area();
      most = mouth_cells.sharers[rec] > most ? mouth_cells.sharers[rec] : most;
    }
    mouths.reservoir_mass[J] = mass / most;
  }
};

//! The cells each segment's handed gas goes to (one thread per segment, after the rock's substeps): at each of
//! kHandoverSamples points of its gap (kHandoverAlong along it, at the middles of equal parts, times
//! kHandoverAcross across it, at the middles of equal parts from face A to face B) the nearest active cell
//! (3 x 3 block), or -1; the segment's gas goes to them in equal shares (two points in one cell: two shares). A
//! segment whose gap opened no active cell (rare: other rock over it) takes its gas back and stays a gas
//! segment.
struct HandoverCellKernel {
  fdem::RockView rock;
  cip::GasGrid g;
  Field2D<const std::uint8_t> active;
  CrackSegments<Access::read_write> seg;
  CrackHandovers<Access::read_write> handovers;
  CrackHandoverCells<Access::read_write> cells;
  BLAST_HD void operator()(index_t si) const {
    const int s = static_cast<int>(si);
    for (int k = 0; k < kHandoverSamples; ++k) cells.cell[kHandoverSamples * s + k] = -1;
    handovers.samples[s] = 0;
    if (!handovers.pending[s]) return;
    const JointFaces f = joint_faces(rock, s);
    int found = 0;
    for (int a = 0; a < kHandoverAlong; ++a) {
      const double t = (a + 0.5) / kHandoverAlong;
      // face A from a0 to a1; face B runs the other way (b1 faces a0)
      const double ax = f.a0.x + t * (f.a1.x - f.a0.x), ay = f.a0.y + t * (f.a1.y - f.a0.y);
      const double bx = f.b1.x + t * (f.b0.x - f.b1.x), by = f.b1.y + t * (f.b0.y - f.b1.y);
      for (int c = 0; c < kHandoverAcross; ++c) {
        const double r = (c + 0.5) / kHandoverAcross;
        int fi = -1, fj = -1;
        if (!nearest_active_cell(g, active, ax + r * (bx - ax), ay + r * (by - ay), fi, fj)) continue;
        cells.cell[kHandoverSamples * s + kHandoverAcross * a + c] = fj * g.nx + fi;
        ++found;
      }
    }
    handovers.samples[s] = found;
    if (found > 0) return;
    // (a crack that closed back below the hand-over gap within the step is a gas segment again and may hold gas
    // its neighbours gave it since: the hand-over is added to it)
    const ChannelConserved h = handovers.gas[s];
    const ChannelConserved c = seg.kind[s] == kSegmentGas ? seg.cons[s] : ChannelConserved{0, 0, 0, 0, 0};
    seg.kind[s] = kSegmentGas, seg.cons[s] = {c.m + h.m, c.q + h.q, c.E + h.E, c.m1 + h.m1, c.am + h.am};
    handovers.pending[s] = 0, handovers.gas[s] = {0, 0, 0, 0, 0};
  }
};

//! One conserved quantity of segment s's hand-over not yet in a cell (0 without one), for reductions.
struct PendingHandoverOf {
  CrackHandovers<Access::read> h;
  double ChannelConserved::*field;
  BLAST_HD double operator()(index_t s) const { return h.pending[s] ? h.gas[s].*field : 0.0; }
};

//! Clears the hand-overs just deposited (one thread per segment).
struct HandoverClearKernel {
  CrackHandovers<Access::read_write> handovers;
  BLAST_HD void operator()(index_t si) const {
    const int s = static_cast<int>(si);
    if (handovers.samples[s] == 0) return;
    handovers.pending[s] = 0, handovers.gas[s] = {0, 0, 0, 0, 0}, handovers.samples[s] = 0;
  }
};

//! The cell key of every deposit record (0 .. kMouthSamples x junctions - 1: the mouths' cells, then the
//! segments' hand-over points, kHandoverSamples a segment; a record without a cell sorts last).
struct CrackDepositKeyKernel {
  CrackMouthCells<Access::read> mouth_cells;
  CrackHandoverCells<Access::read> handover_cells;
  CrackDepositOrder<Access::read_write> order;  //!< writes key
  int mouth_records;  //!< kMouthSamples x junctions
  BLAST_HD void operator()(index_t k) const {
    const int c = k < mouth_records ? mouth_cells.cell[k] : handover_cells.cell[k - mouth_records];
    order.key[k] = c < 0 ? 0x7fffffff : c;
  }
};

//! What deposit record `rec` gives its cell (cell left unset): a mouth cell its share of its junction's deposit,
//! of the gas that left the cracks (and its momentum) in proportion to its mass share (one gas: each cell takes
//! it at its own specific energy and fractions), of the gas drawn from it in proportion to its own content of
//! each quantity (CrackMouthKernel's shares); a hand-over point its equal share of its segment's gas, the axial
//! momentum q along the segment's axis.
BLAST_HD inline cip::CellDeposit deposit_record(const CrackMouthCells<Access::read>& mouth_cells,
                                                const CrackDeposits<Access::read>& deposits,
                                                const CrackHandovers<Access::read>& handovers,
                                                const CrackGeometry<Access::read>& geo, int mouth_records, int rec) {
  if (rec >= mouth_records) {
    const int s = (rec - mouth_records) / kHandoverSamples;
    const ChannelConserved h = handovers.gas[s];
    const double share = 1.0 / handovers.samples[s];
    return {-1, share * h.m, 0.0, share * h.q * geo.axis_x[s], share * h.q * geo.axis_y[s], share * h.E,
            share * h.m1, share * h.am};
  }
  const int J = rec / kMouthSamples;
  const ChannelConserved d = deposits.deposit[J], dr = deposits.drawn[J], f = mouth_cells.share[rec];
  return {-1,
          (d.m - dr.m) * f.m,
          dr.m * f.m,
          deposits.momentum_x[J] * f.m,
          deposits.momentum_y[J] * f.m,
          (d.E - dr.E) * f.m + dr.E * f.E,
          (d.m1 - dr.m1) * f.m + dr.m1 * f.m1,
          (d.am - dr.am) * f.m + dr.am * f.am};
}

//! What the cracks give each cell, as the grid's deposit entries (cip::CellDeposits; one thread per sorted
//! position: the first of a run of equal cell keys sums the run's records in sorted order, so the bytes do not
//! depend on the thread schedule; the other positions give nothing). Records 0 .. kMouthSamples x junctions - 1
//! are the mouths' cells, the rest the segments' hand-over points (deposit_record()). Each record's share goes to
//! its ledger.
struct CrackDepositKernel {
  CrackDepositOrder<Access::read> order;  //!< sorted cell keys (INT_MAX: none), the record of each sorted position
  CrackMouthCells<Access::read> mouth_cells;
  CrackDeposits<Access::read> deposits;
  CrackHandovers<Access::read> handovers;
  CrackGeometry<Access::read> geo;
  CrackExchangeLedger<Access::read_write> ledger;
  cip::CellDepositList<Access::read_write> entries;  //!< one per sorted position
  int mouth_records, records;
  BLAST_HD void operator()(index_t ki) const {
    const int k = static_cast<int>(ki);
    const int c = order.key[k];
    cip::CellDeposit sum{-1, 0, 0, 0, 0, 0, 0, 0};
    if (c != 0x7fffffff && (k == 0 || order.key[k - 1] != c)) {
      sum.cell = c;
      for (int r = k; r < records && order.key[r] == c; ++r) {
        const int rec = order.record[r];
        const cip::CellDeposit d = deposit_record(mouth_cells, deposits, handovers, geo, mouth_records, rec);
        sum.given += d.given, sum.drawn += d.drawn, sum.px += d.px, sum.py += d.py, sum.energy += d.energy;
        sum.products_mass += d.products_mass, sum.alpha_mass += d.alpha_mass;
        ChannelConserved& l = ledger.to_grid[rec];
        l.m += d.given + d.drawn, l.E += d.energy, l.m1 += d.products_mass, l.am += d.alpha_mass;
        ledger.momentum_x[rec] += d.px, ledger.momentum_y[rec] += d.py;
      }
    }
    entries.entry[k] = sum;
  }
};

//! The momentum each cell had no free face to take (cip::CellDeposits::last()), booked to the first record of
//! its run (one thread per sorted position).
struct CrackRefusedKernel {
  CrackDepositOrder<Access::read> order;
  cip::CellDepositList<Access::read> entries;
  cip::CellDepositScratch<Access::read> last;
  CrackExchangeLedger<Access::read_write> ledger;
  BLAST_HD void operator()(index_t k) const {
    if (entries.entry[k].cell < 0) return;
    const int rec = order.record[k];
    ledger.refused_x[rec] += last.refused_x[k], ledger.refused_y[rec] += last.refused_y[k];
  }
};

//! The gas of a crack as a cushion between its faces over the coming rock substep (docs/coupling.md "Gas in the
//! cracks"), one thread per joint, after the channel solver advanced the crack gas over that substep: the faces
//! carry the gas's pressure times crack_width()'s dw_dopening over the grid gas's load (face A is edge slot a0,
//! face B slot b0), and where they stand is kept, so that the next CrackGeometryKernel pays the work of that
//! load, its pressure times swept_area(): the rock's own ledger of the load's work. The gas's own state follows
//! its faces substep by substep, so a crack that closes on its gas stiffens as it closes and the energy budget
//! closes whatever way the faces move. Positions are taken at x - v dt / 2 (`lag`), where the rock's work ledger
//! measures a substep's moves.
struct CrackCushionKernel {
  fdem::RockView rock;
  CrackSegmentParams params;
  CrackSegments<Access::read> seg;
  CrackCushion<Access::read_write> cushion;
  double residual_aperture;
  double lag;  //!< [s] half the rock's last step (joint_faces())
  BLAST_HD void operator()(index_t si) const {
    const int s = static_cast<int>(si);
    if (seg.kind[s] != kSegmentGas) return;
    const JointFaces f = joint_faces(rock, s, lag);
    const ChannelPrimitive P = seg.prim[s];
    const CrackWidth cw = segment_width(rock, params, s, f, P.p, residual_aperture);
    const ChannelConserved c = seg.cons[s];
    const double U = c.m > 0.0 ? c.E - 0.5 * c.q * c.q / c.m : 0.0;
    const double p = is_vacuum(P) || !(U > 0.0) ? 0.0 : P.p;
    cushion.on[s] = 1;
    const fdem::JointNodes jn = rock.joint.nodes[s];
    const fdem::NodeMotion<Access::read>& x = rock.nodes;
    const fdem::Vec2 na = fdem::edge_outward_normal(x.position(jn.a0), x.position(jn.a1));
    const fdem::Vec2 nb = fdem::edge_outward_normal(x.position(jn.b0), x.position(jn.b1));
    cushion.faces[s] = {f.a0.x, f.a0.y, f.a1.x, f.a1.y, f.b0.x, f.b0.y, f.b1.x, f.b1.y, na.x, na.y, nb.x, nb.y};
    const double applied = p * cw.dw_dopening;
    cushion.applied[s] = applied;
    rock.loads.pressure[jn.a0] = applied;
    rock.loads.pressure[jn.b0] = applied;
  }
};

// ---- what the crack gas reports (CrackGasCoupling::outer_blast_fraction(), blast_front(), add_diagnostics()) ----

//! Of gas segment s at a pressure of at least min_pressure [Pa] with an end at a junction on the mesh outline
//! whose node lies beyond `radius` of `center` (a crack's mouth on the outer surface): its blast-gas fraction;
//! else 0 (a maximum over the segments).
struct OuterBlastFraction {
  CrackGraph g;
  CrackSegments<Access::read> seg;
  fdem::JointParams joint;              //!< nodes
  fdem::NodeMotion<Access::read> nodes;
  CrackJunctionPlaces places;           //!< outline
  double cx, cy, r2;                    //!< [m] the centre, [m2] the radius squared
  double min_pressure;                  //!< [Pa]
  BLAST_HD double operator()(index_t si) const {
    const int s = static_cast<int>(si);
    if (seg.kind[s] != kSegmentGas || !(seg.prim[s].p >= min_pressure)) return 0.0;
    const fdem::JointNodes jn = joint.nodes[s];
    double y = 0.0;
    for (int e = 0; e < 2; ++e) {
      if (!places.outline[g.segment_junction[2 * s + e]]) continue;
      const int node = e == 0 ? jn.a0 : jn.a1;
      const double dx = nodes.x[node] - cx, dy = nodes.y[node] - cy;
      if (dx * dx + dy * dy > r2) y = seg.prim[s].Y;
    }
    return y;
  }
};

//! Of gas segment s whose blast-gas fraction and pressure reach min_fraction and min_pressure [Pa]: the distance
//! [m] of its middle (its joint's four nodes) from (cx, cy); else 0 (a maximum over the segments: the front).
struct BlastFrontOf {
  CrackSegments<Access::read> seg;
  fdem::JointParams joint;  //!< nodes
  fdem::NodeMotion<Access::read> x;
  double cx, cy, min_fraction, min_pressure;
  BLAST_HD double operator()(index_t si) const {
    const int s = static_cast<int>(si);
    const ChannelPrimitive& P = seg.prim[s];
    if (seg.kind[s] != kSegmentGas || !(P.Y >= min_fraction) || !(P.p >= min_pressure)) return 0.0;
    const fdem::JointNodes jn = joint.nodes[s];
    const double dx = 0.25 * (x.x[jn.a0] + x.x[jn.a1] + x.x[jn.b0] + x.x[jn.b1]) - cx;
    const double dy = 0.25 * (x.y[jn.a0] + x.y[jn.a1] + x.y[jn.b0] + x.y[jn.b1]) - cy;
    return sqrt(dx * dx + dy * dy);
  }
};

//! Segment s's entry of the walls' ledger, for reductions: the work of its gas on the walls [J/m], the work its
//! loads did on the rock beyond what its gas paid [J/m], or the gas [kg/m] and energy [J/m] it took from covered
//! cells.
struct WallLedgerOf {
  enum class Entry { wall_work, unpaid_work, taken_mass, taken_energy };
  CrackWallLedger<Access::read> walls;
  Entry entry;
  BLAST_HD double operator()(index_t s) const {
    switch (entry) {
      case Entry::wall_work: return walls.wall_work[s];
      case Entry::unpaid_work: return walls.unpaid_work[s];
      case Entry::taken_mass: return walls.taken_mass[s];
      default: return walls.taken_energy[s];
    }
  }
};

}  // namespace blastsim::ibm
