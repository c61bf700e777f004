//! \file vtk_writer.cpp
//! \brief The gas's .vti files through vtkXMLImageDataWriter (VTK in the build: BLASTSIM_HAVE_VTK).
#include "blastsim/cip/vtk_writer.hpp"

#include "blastsim/core/output_files.hpp"

#include <stdexcept>
#include <string>

#if defined(BLASTSIM_HAVE_VTK)
#include <vtkCellData.h>
#include <vtkDoubleArray.h>
#include <vtkImageData.h>
#include <vtkNew.h>
#include <vtkUnsignedCharArray.h>
#include <vtkXMLImageDataWriter.h>
#endif

namespace blastsim::cip {

#if defined(BLASTSIM_HAVE_VTK)
bool vtk_available() { return true; }

namespace {
void add_scalar(vtkImageData* image, const char* name, const std::vector<double>& values) {
  vtkNew<vtkDoubleArray> a;
  a->SetName(name);
  a->SetNumberOfComponents(1);
  a->SetNumberOfTuples(static_cast<vtkIdType>(values.size()));
  for (size_t k = 0; k < values.size(); ++k) a->SetValue(static_cast<vtkIdType>(k), values[k]);
  image->GetCellData()->AddArray(a);
}
}  // namespace

void write_gas_vti(const std::string& path, const GasGrid& grid, const HostGasFields& h) {
  vtkNew<vtkImageData> image;
  image->SetDimensions(grid.nx + 1, grid.ny + 1, 1);  // points; cells are the gas cells, i fastest
  image->SetOrigin(grid.x_min, grid.y_min, 0.0);
  image->SetSpacing(grid.dx, grid.dy, 1.0);
  add_scalar(image, "density", h.rho);
  add_scalar(image, "pressure", h.p);
  add_scalar(image, "internal_energy", h.e);
  if (!h.alpha.empty()) add_scalar(image, "products_fraction", h.alpha);
  if (!h.traced.empty()) add_scalar(image, "blast_gas_fraction", h.traced);
  vtkNew<vtkDoubleArray> vel;
  vel->SetName("velocity");
  vel->SetNumberOfComponents(3);
  vel->SetNumberOfTuples(static_cast<vtkIdType>(h.u.size()));
  for (size_t k = 0; k < h.u.size(); ++k) vel->SetTuple3(static_cast<vtkIdType>(k), h.u[k], h.v[k], 0.0);
  image->GetCellData()->AddArray(vel);
  vtkNew<vtkUnsignedCharArray> active;
  active->SetName("active");
  active->SetNumberOfTuples(static_cast<vtkIdType>(h.active.size()));
  for (size_t k = 0; k < h.active.size(); ++k) active->SetValue(static_cast<vtkIdType>(k), h.active[k]);
  image->GetCellData()->AddArray(active);

  vtkNew<vtkXMLImageDataWriter> writer;
  writer->SetInputData(image);
  write_vtk_atomically(writer.Get(), path);
}
#else
bool vtk_available() { return false; }
void write_gas_vti(const std::string& path, const GasGrid&, const HostGasFields&) {
  throw std::runtime_error("cannot write '" + path + "': this build has no VTK (BLASTSIM_ENABLE_VTK=OFF)");
}
#endif

}  // namespace blastsim::cip
