//! \file gas_state.hpp
//! \brief The non-owning views of the gas state that kernels and couplers use (the owning arrays live behind
//! GasSolver, in libcip/src/gas_storage.hpp); plain header, no backend dependency.
#pragma once

#include "blastsim/cip/eos.hpp"
#include "blastsim/cip/grid.hpp"
#include "blastsim/core/field2d.hpp"

#include <cstdint>
#include <type_traits>

namespace blastsim::cip {

//! View of one CIP unknown: value and its x and y derivatives on the same padded shape. T = double for a
//! kernel that writes, const double for one that only reads (CipFieldReadView).
template <class T>
struct BasicCipFieldView {
  Field2D<T> f, gx, gy;
  //! A writable view converts to a read-only one.
  template <class U = T, class = std::enable_if_t<!std::is_const_v<U>>>
  BLAST_HD operator BasicCipFieldView<const U>() const {
    return {f, gx, gy};
  }
};
using CipFieldView = BasicCipFieldView<double>;
using CipFieldReadView = BasicCipFieldView<const double>;

//! View of the whole gas state. rho [kg/m3] and e [J/kg] at cell centres, u [m/s] on x-faces,
//! v [m/s] on y-faces, each with its derivatives (grid.hpp has the index conventions).
template <class T>
struct BasicGasStateView {
  BasicCipFieldView<T> rho, e, u, v;
  template <class U = T, class = std::enable_if_t<!std::is_const_v<U>>>
  BLAST_HD operator BasicGasStateView<const U>() const {
    return {rho, e, u, v};
  }
};
using GasStateView = BasicGasStateView<double>;
using GasStateReadView = BasicGasStateView<const double>;

//! View of the material fields at cell centres (GasMaterials): the products' volume fraction alpha [-] and
//! partial density m1 = alpha rho1 [kg/m3]. Both zero in a run without products.
template <class T>
struct BasicMaterialView {
  Field2D<T> alpha, m1;
  template <class U = T, class = std::enable_if_t<!std::is_const_v<U>>>
  BLAST_HD operator BasicMaterialView<const U>() const {
    return {alpha, m1};
  }
};
using MaterialView = BasicMaterialView<double>;
using MaterialReadView = BasicMaterialView<const double>;

//! Pressure [Pa] of cell (i, j) from its density, energy and (two-material runs) material fields.
BLAST_HD inline double cell_pressure(const GasMaterials& mat, const MaterialReadView& m, double rho, double e, int i,
                                     int j) {
  return mat.two ? mat.pressure(rho, e, m.alpha(i, j), m.m1(i, j)) : mat.air.pressure(rho, e);
}
//! Pressure [Pa] and sound speed [m/s] of cell (i, j), the mixture pressure computed once.
struct PressureSound {
  double p, c;
};
BLAST_HD inline PressureSound cell_pressure_and_sound_speed(const GasMaterials& mat, const MaterialReadView& m,
                                                            double rho, double e, int i, int j) {
  if (!mat.two) return {mat.air.pressure(rho, e), mat.air.sound_speed(rho, e)};
  const double alpha = m.alpha(i, j), m1 = m.m1(i, j);
  const double p = mat.pressure(rho, e, alpha, m1);
  return {p, alpha > GasMaterials::kMinFraction ? mat.mixture_sound_speed(rho, alpha, m1, p) : mat.air.sound_speed(rho, e)};
}


//! The immersed-boundary input of the gas solver (the paper's Fig. 1a), written by a coupler on the device:
//! - cell_active(i, j) = 0 marks an inactive cell: CIP does not advance it and keeps whatever state the
//!   coupler put there (the paper: ambient gas); active neighbours see it as a zero-gradient wall;
//! - u_prescribed(i, j) = 1 imposes u_imposed(i, j) [m/s] on that x-face (likewise v on y-faces): the face
//!   moves with the solid. Faces next to an inactive cell should be prescribed.
struct ImmersedBoundaryView {
  Field2D<std::uint8_t> cell_active;
  Field2D<std::uint8_t> u_prescribed;
  Field2D<std::uint8_t> v_prescribed;
  Field2D<double> u_imposed;
  Field2D<double> v_imposed;
};

}  // namespace blastsim::cip
