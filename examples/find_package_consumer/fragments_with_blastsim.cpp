//! \file fragments_with_blastsim.cpp
//! \brief Example of linking libfdem from another code: a block cut into 3 x 2 pieces, its fragments and sizes.
#include <blastsim/fdem/fragments.hpp>
#include <blastsim/fdem/rock_solver.hpp>

#include <cmath>
#include <cstdio>

int main() {
  using namespace blastsim::fdem;
  // A 0.3 x 0.2 m block of the paper's rock, with joints cut along x = 0.1, x = 0.2 and y = 0.1.
  const FdemTopology topo = build_topology(structured_rectangle(30, 20, 0.0, 0.3, 0.0, 0.2));
  RockSolver rock(topo, RockMaterial::paper_table2(), RockOptions{});
  for (double x : {0.1, 0.2}) rock.break_joints(rock.joints_on_segment(x, 0.0, x, 0.2, 1e-9));
  rock.break_joints(rock.joints_on_segment(0.0, 0.1, 0.3, 0.1, 1e-9));
  const RockSnapshot snap = rock.snapshot();
  const std::vector<Fragment> fragments = measure_fragments(snap, fragment_labels(rock.view()), rock.material().density);
  const SizeDistribution sizes = size_distribution(fragments, 0.5);
  std::printf("%zu fragments (expected 6); each %.4f m2, sieve size %.4f m (expected 0.01 m2, 0.1 m); X50 %.4f m\n",
              fragments.size(), fragments[0].area, fragments[0].sieve_size, sizes.x50);
  bool ok = fragments.size() == 6;
  for (const Fragment& f : fragments) ok = ok && std::fabs(f.area - 0.01) < 1e-12 && std::fabs(f.sieve_size - 0.1) < 1e-12;
  return ok ? 0 : 1;
}
