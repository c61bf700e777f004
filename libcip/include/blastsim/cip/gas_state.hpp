//! \file gas_state.hpp
//! \brief Owning device arrays of the gas state and the non-owning views kernels and couplers use.
#pragma once

#include "blastsim/cip/grid.hpp"
#include "blastsim/core/backend.hpp"

#include <cstdint>

namespace blastsim::cip {

//! View of one CIP unknown: value and its x and y derivatives on the same padded shape.
struct CipFieldView {
  Field2D<double> f, gx, gy;
};

//! View of the whole gas state. rho [kg/m3] and e [J/kg] at cell centres, u [m/s] on x-faces,
//! v [m/s] on y-faces, each with its derivatives (grid.hpp has the index conventions).
struct GasStateView {
  CipFieldView rho, e, u, v;
};

//! Owning storage of one CIP unknown.
struct CipField {
  DeviceVector<double> f, gx, gy;
  void resize(index_t n) {
    f.assign(n, 0.0);
    gx.assign(n, 0.0);
    gy.assign(n, 0.0);
  }
  CipFieldView view(PaddedShape s) {
    return {make_field_view(f, s), make_field_view(gx, s), make_field_view(gy, s)};
  }
};

//! Owning storage of the gas state.
struct GasState {
  CipField rho, e, u, v;
  void resize(index_t n) {
    rho.resize(n);
    e.resize(n);
    u.resize(n);
    v.resize(n);
  }
  GasStateView view(PaddedShape s) { return {rho.view(s), e.view(s), u.view(s), v.view(s)}; }
};

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

//! Owning storage of the immersed-boundary input; by default every cell active and no face prescribed.
struct ImmersedBoundaryArrays {
  DeviceVector<std::uint8_t> cell_active, u_prescribed, v_prescribed;
  DeviceVector<double> u_imposed, v_imposed;
  void resize(index_t n) {
    cell_active.assign(n, 1);
    u_prescribed.assign(n, 0);
    v_prescribed.assign(n, 0);
    u_imposed.assign(n, 0.0);
    v_imposed.assign(n, 0.0);
  }
  ImmersedBoundaryView view(PaddedShape s) {
    return {make_field_view(cell_active, s), make_field_view(u_prescribed, s), make_field_view(v_prescribed, s),
            make_field_view(u_imposed, s), make_field_view(v_imposed, s)};
  }
};

}  // namespace blastsim::cip
