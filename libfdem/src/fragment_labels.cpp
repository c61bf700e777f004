//! \file fragment_labels.cpp
//! \brief fragment_labels(): the fragments of the rock on the device, by label propagation over the joints that
//! still hold (fragment_kernels.hpp).
#include "blastsim/core/device_groups.hpp"
#include "blastsim/fdem/fragment_kernels.hpp"
#include "blastsim/fdem/fragments.hpp"

#include <stdexcept>

namespace blastsim::fdem {

namespace detail {
BLASTSIM_STATE_STORAGE(FragmentLabels, BLASTSIM_FRAGMENT_LABELS)
}

std::vector<int> fragment_labels(const RockReadView& rock) {
  const int triangles = rock.triangle_count;
  detail::FragmentLabelsArrays a, b;  // the sweep reads one and writes the other
  a.label.resize(triangles), b.label.resize(triangles);
  fill_indices("fdem.fragments.labels", a.label);
  const FragmentLinks links{rock.edge, rock.joints};
  detail::FragmentLabelsArrays* in = &a;
  detail::FragmentLabelsArrays* out = &b;
  // Each sweep at least halves the label chains (pointer jumping) or carries a label one triangle further,
  // so the count is bounded by the triangles; the bound only guards against a logic error.
  for (int sweep = 0; sweep <= triangles; ++sweep) {
    for_each_index("fdem.fragments.sweep", triangles, LabelSweepKernel{links, in->read(), out->view()});
    const int changed = reduce_max("fdem.fragments.changed", triangles, 0, LabelChanged{in->read(), out->read()});
    std::swap(in, out);
    if (!changed) return to_host(in->label);
  }
  throw std::logic_error("fragment_labels: label propagation did not converge");
}

}  // namespace blastsim::fdem
