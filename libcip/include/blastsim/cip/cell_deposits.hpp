//! \file cell_deposits.hpp
//! \brief CellDeposits: adds what a coupling gives a sparse set of cells (mass with its momentum, drawn mass,
//! energy, materials) to the gas, mass, momentum and total energy exact as GasTotals measures them
//! (deposit_kernels.hpp; docs/coupling.md "Deposits into the grid").
#pragma once

#include "blastsim/cip/deposit_kernels.hpp"
#include "blastsim/cip/grid.hpp"

#include <memory>
#include <vector>

namespace blastsim::cip {

class GasSolver;
namespace detail {
struct CellDepositArrays;
}

//! The entries a coupling fills (one per cell at most, in an order it chooses: the sums do not depend on the
//! threads), then apply() adds them to the gas in four passes of one thread an entry.
class CellDeposits {
 public:
  explicit CellDeposits(const GasGrid& grid);
  ~CellDeposits();
  CellDeposits(CellDeposits&&) noexcept;
  CellDeposits& operator=(CellDeposits&&) noexcept;

  //! Room for n entries, and their view for the kernel that fills them (an entry with cell -1 gives nothing).
  CellDepositList<Access::read_write> entries(index_t n);
  //! The entries from the host (tests, host-side couplings).
  void set_entries(const std::vector<CellDeposit>& entries);
  //! Adds the n entries filled since entries(n) to the gas's cells and faces (its immersed boundary says which
  //! faces are free); each entry's refused momentum is kept until the next call.
  void apply(GasSolver& gas);
  //! Per entry of the last apply(): the momentum [kg/s] its cell had no free face to take.
  CellDepositScratch<Access::read> last() const;
  //! The entries of the last entries(n), read-only.
  CellDepositList<Access::read> list() const;

 private:
  GasGrid grid_;
  index_t n_ = 0;
  std::unique_ptr<detail::CellDepositArrays> a_;
};

}  // namespace blastsim::cip
