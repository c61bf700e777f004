//! \file input_analysis.cpp
//! \brief [analysis]: fragments, size distribution and damage zones at every snapshot (docs/input.md,
//! docs/analysis.md).
#include "case.hpp"

namespace blastsim::app {

void read_analysis(TableReader& root, Case& c) {
  TableReader a = root.table("analysis");
  AnalysisSettings& s = c.analysis;
  s.fragments = a.boolean("fragments", true);
  s.min_fragment_triangles =
      static_cast<int>(a.integer("min_fragment_triangles", "", 1, fdem::kDefaultMinFragmentTriangles, 1000000));
  s.oversize = a.number("oversize", "m", Range::positive(), 0.5);
  s.ring_width = a.number("damage_ring_width", "m", Range::non_negative(), 0.0);
  s.crushed_fraction = a.number("crushed_fraction", "", Range{0.0, 1.0, true, false}, 0.5);
  for (TableReader& h : a.table_array("hole")) {
    s.holes_given = true;
    AnalysisSettings::Hole d;
    d.center = h.pair("center", "m");
    d.radius = h.number("radius", "m", Range::positive());
    d.behind = h.pair("behind", "", std::array<double, 2>{0.0, 0.0});
    h.finish();
    s.holes.push_back(d);
  }
  a.finish();
  // The default holes: the mesh's (a coupled case puts its charges' holes first, read_charges()).
  const fdem::MeshSpec& m = c.rock.model.mesh;
  if (s.holes.empty() && (m.shape == fdem::MeshShape::disc_with_hole || m.shape == fdem::MeshShape::rectangle_with_hole))
    s.holes.push_back({m.center, m.hole_radius});
  if (!s.holes_given)
    for (const fdem::Circle& h : m.holes) s.holes.push_back({h.center, h.radius});
}

}  // namespace blastsim::app
