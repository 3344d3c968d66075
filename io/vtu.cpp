#include "io/vtu.hpp"

#include <sstream>

#include <vtkCellArray.h>
#include <vtkDoubleArray.h>
#include <vtkIntArray.h>
#include <vtkCellData.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkUnstructuredGrid.h>
#include <vtkXMLUnstructuredGridWriter.h>

#include "common/error.hpp"
#include "io/atomic_file.hpp"

namespace sw {

void write_vtu(const std::filesystem::path& path, const TetMesh& mesh, const std::vector<NodalField>& fields) {
  vtkNew<vtkUnstructuredGrid> grid;
  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  points->SetNumberOfPoints(static_cast<vtkIdType>(mesh.n_nodes()));
  for (std::size_t i = 0; i < mesh.n_nodes(); ++i)
    points->SetPoint(static_cast<vtkIdType>(i), mesh.nodes(i, 0), mesh.nodes(i, 1), mesh.nodes(i, 2));
  grid->SetPoints(points);
  grid->Allocate(static_cast<vtkIdType>(mesh.tets.size()));
  vtkIdType ids[10];
  for (const auto& t : mesh.tets) {
    for (int a = 0; a < 10; ++a) ids[a] = t[a];
    grid->InsertNextCell(VTK_QUADRATIC_TETRA, 10, ids);  // our node order is VTK's
  }
  vtkNew<vtkIntArray> region;
  region->SetName("region");
  region->SetNumberOfValues(static_cast<vtkIdType>(mesh.tets.size()));
  for (std::size_t e = 0; e < mesh.tets.size(); ++e)
    region->SetValue(static_cast<vtkIdType>(e), e < mesh.region.size() ? mesh.region[e] : 0);
  grid->GetCellData()->AddArray(region);
  for (const auto& f : fields) {
    if (static_cast<std::size_t>(f.values.rows()) != mesh.n_nodes())
      throw std::logic_error("field " + f.name + " has the wrong number of rows");
    vtkNew<vtkDoubleArray> a;
    a->SetName(f.name.c_str());
    a->SetNumberOfComponents(static_cast<int>(f.values.cols()));
    a->SetNumberOfTuples(f.values.rows());
    for (Eigen::Index i = 0; i < f.values.rows(); ++i)
      for (Eigen::Index k = 0; k < f.values.cols(); ++k) a->SetComponent(i, static_cast<int>(k), f.values(i, k));
    grid->GetPointData()->AddArray(a);
    if (f.name == "displacement") grid->GetPointData()->SetVectors(a);
  }
  write_via_temp(path, [&](const std::filesystem::path& tmp) {
    vtkNew<vtkXMLUnstructuredGridWriter> writer;
    writer->SetFileName(tmp.c_str());
    writer->SetInputData(grid);
    writer->SetDataModeToAppended();
    writer->EncodeAppendedDataOff();
    writer->SetCompressorTypeToZLib();
    if (writer->Write() != 1) throw InputError(path.string() + ": VTK could not write the file");
  });
}

void write_pvd(const std::filesystem::path& path, const std::vector<std::pair<std::string, std::string>>& datasets) {
  std::ostringstream s;
  s << "<?xml version=\"1.0\"?>\n<VTKFile type=\"Collection\" version=\"0.1\">\n  <Collection>\n";
  for (std::size_t k = 0; k < datasets.size(); ++k)
    s << "    <DataSet timestep=\"" << k << "\" name=\"" << datasets[k].first << "\" file=\"" << datasets[k].second
      << "\"/>\n";
  s << "  </Collection>\n</VTKFile>\n";
  write_file_atomic(path, s.str());
}

}  // namespace sw
