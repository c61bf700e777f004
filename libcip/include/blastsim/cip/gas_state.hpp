//! \file gas_state.hpp
//! \brief The non-owning views of the gas state that kernels and couplers use (the owning arrays live behind
//! GasSolver, in libcip/src/gas_storage.hpp); plain header, no backend dependency.
#pragma once

#include "blastsim/cip/eos.hpp"
#include "blastsim/cip/grid.hpp"
#include "blastsim/core/access.hpp"
#include "blastsim/core/field2d.hpp"

#include <cstdint>
#include <type_traits>

namespace blastsim::cip {

//! The gas's arrays, each declared once in a field list (core/access.hpp; the storage, generated from the same
//! lists, is libcip/src/gas_storage.hpp). Every array lives on the grid's padded shape (grid.hpp has the index
//! conventions); the views below are Field2D views of access A.
//!
//! The CIP unknowns X(name, comment): each a value with its x and y derivatives.
#define BLASTSIM_GAS_UNKNOWNS(X)                         \
  X(rho, "density [kg/m3] at cell centres")              \
  X(e, "specific internal energy [J/kg] at cell centres") \
  X(u, "x velocity [m/s] on x-faces")                    \
  X(v, "y velocity [m/s] on y-faces")
#define BLASTSIM_CIP_FIELD_PARTS(X) X(double, f, "the value") X(double, gx, "its x derivative") X(double, gy, "its y derivative")
//! The material fields at cell centres (GasMaterials), present only in a run with products.
#define BLASTSIM_GAS_MATERIAL_FIELDS(X)                                         \
  X(double, alpha, "volume fraction of the detonation products [-]")          \
  X(double, m1, "partial density of the products alpha rho1 [kg/m3]")
//! The immersed-boundary input of the gas solver (the paper's Fig. 1a), written by a coupler on the device:
//! - cell_active(i, j) = 0 marks an inactive cell: CIP does not advance it and keeps whatever state the
//!   coupler put there (the paper: ambient gas); active neighbours see it as a zero-gradient wall;
//! - u_prescribed(i, j) = 1 imposes u_imposed(i, j) [m/s] on that x-face (likewise v on y-faces): the face
//!   moves with the solid. Faces next to an inactive cell should be prescribed.
#define BLASTSIM_GAS_IMMERSED_INPUT(X)                                     \
  X(std::uint8_t, cell_active, "1: the cell is advanced, 0: inactive")    \
  X(std::uint8_t, u_prescribed, "1: the x-face's velocity is imposed")    \
  X(std::uint8_t, v_prescribed, "1: the y-face's velocity is imposed")    \
  X(double, u_imposed, "the imposed velocity of a prescribed x-face [m/s]") \
  X(double, v_imposed, "the imposed velocity of a prescribed y-face [m/s]")

#define BLASTSIM_GAS_UNKNOWN_MEMBER(name, comment) CipField<A> name;
#define BLASTSIM_GAS_UNKNOWN_COPY(name, comment) name,

//! One CIP unknown: value and its x and y derivatives on the same padded shape.
BLASTSIM_FIELD_GROUP(CipField, BLASTSIM_CIP_FIELD_PARTS)
//! The whole gas state: rho and e at cell centres, u on x-faces, v on y-faces, each with its derivatives.
template <Access A>
struct GasState {
  BLASTSIM_GAS_UNKNOWNS(BLASTSIM_GAS_UNKNOWN_MEMBER)
  BLASTSIM_READ_CONVERSION(GasState, BLASTSIM_GAS_UNKNOWNS(BLASTSIM_GAS_UNKNOWN_COPY))
};
//! The products' volume fraction alpha [-] and partial density m1 = alpha rho1 [kg/m3] (empty fields, never
//! read, in a run without products).
BLASTSIM_FIELD_GROUP(MaterialFields, BLASTSIM_GAS_MATERIAL_FIELDS)
BLASTSIM_FIELD_GROUP(ImmersedBoundaryInput, BLASTSIM_GAS_IMMERSED_INPUT)
using CipFieldView = CipField<Access::read_write>;
using CipFieldReadView = CipField<Access::read>;
using GasStateView = GasState<Access::read_write>;
using GasStateReadView = GasState<Access::read>;
using MaterialView = MaterialFields<Access::read_write>;
using MaterialReadView = MaterialFields<Access::read>;
using ImmersedBoundaryView = ImmersedBoundaryInput<Access::read_write>;
using ImmersedBoundaryReadView = ImmersedBoundaryInput<Access::read>;

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
  return {p, mat.air_only(alpha) ? mat.air.sound_speed(rho, e) : mat.mixture_sound_speed(rho, alpha, m1, p)};
}


//! What a cell holds, as the coupling moves gas between cells: per unit area of the cell [kg/m3, J/m3]
//! (GasCells::own(), add_share(), replace(); what a coupling gives cells from outside the grid is a CellDeposit,
//! deposit_kernels.hpp). The products' volume fraction travels as alpha x mass, so a mix of several contents takes
//! their mass-weighted mean fraction.
struct CellContent {
  double mass;           //!< rho
  double energy;         //!< rho e, and whatever kinetic energy the giver hands on
  double products_mass;  //!< m1: alpha rho1, or the traced gas (0 in a one-gas run without a tracer)
  double alpha_mass;     //!< alpha rho (0 in a one-gas run)
};

//! Which material fills a cell entirely (GasCells::fill()).
enum class GasPhase { air, products };

//! The cells of the gas state, with their material fields, as the coupling sees them: it takes, mixes,
//! deposits and replaces what cells hold through these calls, which handle the material fields (present only
//! in a run with products or a tracer), so a coupling kernel never branches on the number of materials.
//! Access read_write for a kernel that writes (GasCells), read for one that only reads (GasCellsRead).
template <Access A>
struct GasCellsOf {
  GasState<A> s;
  MaterialFields<A> m;  //!< empty in a one-gas run without a tracer
  bool two;             //!< GasMaterials::two: alpha and m1 are the products'
  bool traced;          //!< GasMaterials::traced(): m1 exists (the products', or the traced gas's)
  //! The solver's positivity ledger [J/m3 per cell] (GasSolver::positivity_energy()): energy a deposit could not
  //! take from a cell's internal energy.
  access_field<double, A> positivity_heat;
  BLASTSIM_READ_CONVERSION(GasCellsOf, s BLASTSIM_COMMA m BLASTSIM_COMMA two BLASTSIM_COMMA traced BLASTSIM_COMMA
                                           positivity_heat)

  //! What cell (i, j) holds per unit area, with `energy` [J/m3] as its energy (its internal energy, or more).
  BLAST_HD CellContent own(int i, int j, double energy) const {
    const double rho = s.rho.f(i, j);
    return {rho, energy, traced ? m.m1(i, j) : 0.0, two ? m.alpha(i, j) * rho : 0.0};
  }
  //! Adds `share` of cell (i, j)'s content to c, with `energy` [J/m3] as that cell's energy.
  BLAST_HD void add_share(CellContent& c, double share, int i, int j, double energy) const {
    c.mass += share * s.rho.f(i, j);
    c.energy += share * energy;
    if (traced) c.products_mass += share * m.m1(i, j);
    if (two) c.alpha_mass += share * m.alpha(i, j) * s.rho.f(i, j);
  }
  //! The products' volume fraction alpha (0 in a one-gas run) and the traced gas's mass fraction Y of cell
  //! (i, j): the products', or the tracer's (0 without either).
  struct Fractions {
    double alpha, Y;
  };
  BLAST_HD Fractions fractions(int i, int j) const {
    return {two ? m.alpha(i, j) : 0.0, traced ? m.m1(i, j) / s.rho.f(i, j) : 0.0};
  }

  // --- writes (GasCells only) ---
  //! Makes cell (i, j) hold c (per unit area): its density, specific energy and fractions from c, its
  //! derivatives zero.
  BLAST_HD void replace(int i, int j, const CellContent& c) const {
    s.rho.f(i, j) = c.mass, s.rho.gx(i, j) = 0.0, s.rho.gy(i, j) = 0.0;
    s.e.f(i, j) = c.energy / c.mass, s.e.gx(i, j) = 0.0, s.e.gy(i, j) = 0.0;
    if (two) m.alpha(i, j) = c.alpha_mass / c.mass;
    if (traced) m.m1(i, j) = c.products_mass;
  }
  //! Fills cell (i, j) with one material at density rho [kg/m3] and specific internal energy e [J/kg], its
  //! derivatives zero (GasPhase::products needs a run with products); air holds no traced gas.
  BLAST_HD void fill(int i, int j, GasPhase phase, double rho, double e) const {
    s.rho.f(i, j) = rho, s.rho.gx(i, j) = 0.0, s.rho.gy(i, j) = 0.0;
    s.e.f(i, j) = e, s.e.gx(i, j) = 0.0, s.e.gy(i, j) = 0.0;
    const bool products = phase == GasPhase::products;
    if (two) m.alpha(i, j) = products ? 1.0 : 0.0;
    if (traced) m.m1(i, j) = products ? rho : 0.0;
  }
};
using GasCells = GasCellsOf<Access::read_write>;
using GasCellsRead = GasCellsOf<Access::read>;


}  // namespace blastsim::cip
