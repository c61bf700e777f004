//! \file cell_deposits.cpp
//! \brief CellDeposits: its arrays (deposit_kernels.hpp's lists) and the four passes of a deposit.
#include "blastsim/cip/cell_deposits.hpp"

#include "blastsim/cip/gas_solver.hpp"
#include "blastsim/core/device_groups.hpp"

namespace blastsim::cip {

namespace detail {
BLASTSIM_STATE_STORAGE(CellDepositList, BLASTSIM_CELL_DEPOSIT_LIST)
BLASTSIM_FIELD_STORAGE(CellDepositSlots, BLASTSIM_CELL_DEPOSIT_SLOTS)
BLASTSIM_STATE_STORAGE(CellDepositScratch, BLASTSIM_CELL_DEPOSIT_SCRATCH)
struct CellDepositArrays {
  CellDepositListArrays list;       // per entry
  CellDepositSlotsArrays slots;     // per cell (the grid's padded shape)
  CellDepositScratchArrays scratch; // per entry
};
}  // namespace detail

CellDeposits::CellDeposits(const GasGrid& grid) : grid_(grid), a_(std::make_unique<detail::CellDepositArrays>()) {
  a_->slots.slot.assign(static_cast<std::size_t>(grid.padded_shape().size()), -1);
}
CellDeposits::~CellDeposits() = default;
CellDeposits::CellDeposits(CellDeposits&&) noexcept = default;
CellDeposits& CellDeposits::operator=(CellDeposits&&) noexcept = default;

CellDepositList<Access::read_write> CellDeposits::entries(index_t n) {
  if (static_cast<index_t>(a_->list.entry.size()) != n) {
    a_->list.entry.assign(static_cast<std::size_t>(n), CellDeposit{-1, 0, 0, 0, 0, 0, 0, 0});
    a_->scratch.before.resize(static_cast<std::size_t>(n));
    a_->scratch.refused_x.assign(static_cast<std::size_t>(n), 0.0);
    a_->scratch.refused_y.assign(static_cast<std::size_t>(n), 0.0);
  }
  n_ = n;
  return a_->list.view();
}

void CellDeposits::set_entries(const std::vector<CellDeposit>& entries) {
  this->entries(static_cast<index_t>(entries.size()));
  copy_from_host(a_->list.entry, entries);
}

void CellDeposits::apply(GasSolver& gas) {
  const PaddedShape shape = grid_.padded_shape();
  const CellDepositList<Access::read> list = a_->list.read();
  for_each_index("cip.deposit.gather", n_,
                 DepositGatherKernel{grid_, list, a_->slots.view(shape), gas.state(), gas.immersed_boundary(),
                                     a_->scratch.view()});
  for_each_index("cip.deposit.momentum", n_,
                 DepositMomentumKernel{grid_, list, a_->slots.read(shape), a_->scratch.view(), gas.state()});
  for_each_index("cip.deposit.cells", n_, DepositCellKernel{grid_, list, a_->slots.read(shape), a_->scratch.read(), gas.cells()});
  for_each_index("cip.deposit.clear", n_, DepositClearKernel{grid_, list, a_->slots.view(shape)});
}

CellDepositScratch<Access::read> CellDeposits::last() const { return a_->scratch.read(); }
CellDepositList<Access::read> CellDeposits::list() const { return a_->list.read(); }

}  // namespace blastsim::cip
