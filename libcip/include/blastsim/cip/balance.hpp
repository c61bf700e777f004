//! \file balance.hpp
//! \brief The gas's conservation balance: what is in the domain plus what left through its outer boundary,
//! against the initial totals (the conservation monitor of a gas-only run). Plain header.
#pragma once

#include "blastsim/cip/gas_types.hpp"

namespace blastsim::cip {

//! Relative drift of the mass and energy balances: (in domain + out) / initial - 1 [-].
struct BalanceDrift {
  double mass = 0;
  double energy = 0;
};

//! The drift of `now` (totals over the domain) and `out` (cumulative outflow) from `initial`, less the
//! energy `added` [J/m] by the positivity bound of the transport (GasSolver::positivity_energy()); 0 for a
//! scheme that conserves to round-off.
inline BalanceDrift balance_drift(const GasTotals& now, const BoundaryOutflow& out, const GasTotals& initial,
                                  double added = 0.0) {
  return {(now.mass + out.mass) / initial.mass - 1,
          (now.total_energy() + out.energy - added) / initial.total_energy() - 1};
}

}  // namespace blastsim::cip
