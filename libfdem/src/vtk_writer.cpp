//! \file vtk_writer.cpp
//! \brief The rock's .vtu files through vtkXMLUnstructuredGridWriter (VTK in the build: BLASTSIM_HAVE_VTK).
#include "blastsim/fdem/vtk_writer.hpp"

#include "blastsim/core/output_files.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

#if defined(BLASTSIM_HAVE_VTK)
#include <vtkCellArray.h>
#include <vtkCellData.h>
#include <vtkDoubleArray.h>
#include <vtkIntArray.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkUnsignedCharArray.h>
#include <vtkUnstructuredGrid.h>
#include <vtkXMLUnstructuredGridWriter.h>
#endif

namespace blastsim::fdem {

#if defined(BLASTSIM_HAVE_VTK)
namespace {
vtkNew<vtkDoubleArray> array(const char* name, int components, vtkIdType tuples) {
  vtkNew<vtkDoubleArray> a;
  a->SetName(name);
  a->SetNumberOfComponents(components);
  a->SetNumberOfTuples(tuples);
  return a;
}

void write_grid(const std::string& path, vtkUnstructuredGrid* grid) {
  vtkNew<vtkXMLUnstructuredGridWriter> writer;
  writer->SetInputData(grid);
  write_vtk_atomically(writer.Get(), path);
}
}  // namespace

void write_rock_vtu(const std::string& path, const RockSnapshot& s, const RockCellFields& cells) {
  const vtkIdType nodes = static_cast<vtkIdType>(s.x.size()), triangles = nodes / 3;
  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  points->SetNumberOfPoints(nodes);
  auto displacement = array("displacement", 3, nodes), velocity = array("velocity", 3, nodes);
  for (vtkIdType n = 0; n < nodes; ++n) {
    points->SetPoint(n, s.x[n], s.y[n], 0.0);
    displacement->SetTuple3(n, s.x[n] - s.x0[n], s.y[n] - s.y0[n], 0.0);
    velocity->SetTuple3(n, s.vx[n], s.vy[n], 0.0);
  }
  vtkNew<vtkUnstructuredGrid> grid;
  grid->SetPoints(points);
  grid->Allocate(triangles);
  auto stress = array("stress", 3, triangles), smax = array("principal_max", 1, triangles),
       smin = array("principal_min", 1, triangles);
  for (vtkIdType t = 0; t < triangles; ++t) {
    const vtkIdType ids[3] = {3 * t, 3 * t + 1, 3 * t + 2};
    grid->InsertNextCell(5 /* VTK_TRIANGLE */, 3, ids);
    const double sxx = s.stress[3 * t], sxy = s.stress[3 * t + 1], syy = s.stress[3 * t + 2];
    const double mean = 0.5 * (sxx + syy), radius = std::sqrt(0.25 * (sxx - syy) * (sxx - syy) + sxy * sxy);
    stress->SetTuple3(t, sxx, syy, sxy);
    smax->SetValue(t, mean + radius);
    smin->SetValue(t, mean - radius);
  }
  grid->GetPointData()->AddArray(displacement);
  grid->GetPointData()->AddArray(velocity);
  grid->GetCellData()->AddArray(stress);
  grid->GetCellData()->AddArray(smax);
  grid->GetCellData()->AddArray(smin);
  vtkNew<vtkIntArray> fragment;
  if (cells.fragment_id.size() == static_cast<size_t>(triangles)) {
    fragment->SetName("fragment_id");
    fragment->SetNumberOfTuples(triangles);
    for (vtkIdType t = 0; t < triangles; ++t) fragment->SetValue(t, cells.fragment_id[t]);
    grid->GetCellData()->AddArray(fragment);
  }
  auto damage = array("damage", 1, cells.damage.size() == static_cast<size_t>(triangles) ? triangles : 0);
  if (cells.damage.size() == static_cast<size_t>(triangles)) {
    for (vtkIdType t = 0; t < triangles; ++t) damage->SetValue(t, cells.damage[t]);
    grid->GetCellData()->AddArray(damage);
  }
  write_grid(path, grid);
}

void write_joints_vtu(const std::string& path, const RockSnapshot& s, const std::vector<JointField>& fields) {
  const vtkIdType joints = static_cast<vtkIdType>(s.joint_nodes.size());
  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  points->SetNumberOfPoints(2 * joints);
  vtkNew<vtkUnstructuredGrid> grid;
  grid->Allocate(joints);
  auto damage = array("damage", 1, joints);
  vtkNew<vtkUnsignedCharArray> broken;
  broken->SetName("broken");
  broken->SetNumberOfTuples(joints);
  for (vtkIdType j = 0; j < joints; ++j) {
    const auto& n = s.joint_nodes[j];  // a0, a1, b0, b1: a0 faces b1, a1 faces b0
    points->SetPoint(2 * j, 0.5 * (s.x[n[0]] + s.x[n[3]]), 0.5 * (s.y[n[0]] + s.y[n[3]]), 0.0);
    points->SetPoint(2 * j + 1, 0.5 * (s.x[n[1]] + s.x[n[2]]), 0.5 * (s.y[n[1]] + s.y[n[2]]), 0.0);
    const vtkIdType ids[2] = {2 * j, 2 * j + 1};
    grid->InsertNextCell(3 /* VTK_LINE */, 2, ids);
    damage->SetValue(j, s.joint_damage[j]);
    broken->SetValue(j, s.joint_broken[j]);
  }
  grid->SetPoints(points);
  grid->GetCellData()->AddArray(damage);
  grid->GetCellData()->AddArray(broken);
  for (const JointField& f : fields) {
    if (f.values.size() != static_cast<std::size_t>(joints)) continue;
    auto a = array(f.name.c_str(), 1, joints);
    for (vtkIdType j = 0; j < joints; ++j) a->SetValue(j, f.values[j]);
    grid->GetCellData()->AddArray(a);
  }
  write_grid(path, grid);
}
#else
void write_rock_vtu(const std::string& path, const RockSnapshot&, const RockCellFields&) {
  throw std::runtime_error("cannot write '" + path + "': this build has no VTK (BLASTSIM_ENABLE_VTK=OFF)");
}
void write_joints_vtu(const std::string& path, const RockSnapshot&, const std::vector<JointField>&) {
  throw std::runtime_error("cannot write '" + path + "': this build has no VTK (BLASTSIM_ENABLE_VTK=OFF)");
}
#endif

}  // namespace blastsim::fdem
