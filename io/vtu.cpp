#include "io/vtu.hpp"

#include <algorithm>
#include <sstream>

#include <vtkCellArray.h>
#include <vtkDoubleArray.h>
#include <vtkIdTypeArray.h>
#include <vtkIntArray.h>
#include <vtkCellData.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkSmartPointer.h>
#include <vtkUnstructuredGrid.h>
#include <vtkXMLUnstructuredGridWriter.h>

#include "common/error.hpp"
#include "io/atomic_file.hpp"

namespace sw {

namespace {

/// The mesh as a VTK grid: points, VTK_QUADRATIC_TETRA cells (our node order is VTK's), "region" cell data; arrays
/// filled in place, not value by value.
vtkSmartPointer<vtkUnstructuredGrid> vtk_grid(const TetMesh& mesh) {
  const vtkIdType n = static_cast<vtkIdType>(mesh.n_nodes()), ne = static_cast<vtkIdType>(mesh.tets.size());
  vtkNew<vtkDoubleArray> xyz;
  xyz->SetNumberOfComponents(3);
  xyz->SetNumberOfTuples(n);
  std::copy_n(mesh.nodes.data(), 3 * n, xyz->GetPointer(0));  // row-major n x 3: VTK's interleaved layout
  vtkNew<vtkPoints> points;
  points->SetData(xyz);
  vtkNew<vtkIdTypeArray> offsets, connectivity;
  offsets->SetNumberOfValues(ne + 1);
  connectivity->SetNumberOfValues(10 * ne);
  for (vtkIdType e = 0; e <= ne; ++e) offsets->SetValue(e, 10 * e);
  vtkIdType* ids = connectivity->GetPointer(0);
  for (const auto& t : mesh.tets) ids = std::copy(t.begin(), t.end(), ids);
  vtkNew<vtkCellArray> cells;
  cells->SetData(offsets, connectivity);
  auto grid = vtkSmartPointer<vtkUnstructuredGrid>::New();
  grid->SetPoints(points);
  grid->SetCells(VTK_QUADRATIC_TETRA, cells);
  vtkNew<vtkIntArray> region;
  region->SetName("region");
  region->SetNumberOfValues(ne);
  for (vtkIdType e = 0; e < ne; ++e)
    region->SetValue(e, static_cast<std::size_t>(e) < mesh.region.size() ? mesh.region[static_cast<std::size_t>(e)] : 0);
  grid->GetCellData()->AddArray(region);
  return grid;
}

/// A nodal field as a VTK array (interleaved components).
vtkSmartPointer<vtkDoubleArray> vtk_array(const NodalField& f) {
  auto a = vtkSmartPointer<vtkDoubleArray>::New();
  a->SetName(f.name.c_str());
  a->SetNumberOfComponents(static_cast<int>(f.values.cols()));
  a->SetNumberOfTuples(f.values.rows());
  Eigen::Map<Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>>(a->GetPointer(0), f.values.rows(),
                                                                                     f.values.cols()) = f.values;
  return a;
}

}  // namespace

void write_vtu(const std::filesystem::path& path, const TetMesh& mesh, const std::vector<NodalField>& fields) {
  const vtkSmartPointer<vtkUnstructuredGrid> grid = vtk_grid(mesh);
  for (const auto& f : fields) {
    if (static_cast<std::size_t>(f.values.rows()) != mesh.n_nodes())
      throw std::logic_error("field " + f.name + " has the wrong number of rows");
    const vtkSmartPointer<vtkDoubleArray> a = vtk_array(f);
    grid->GetPointData()->AddArray(a);
    if (f.name == "displacement") grid->GetPointData()->SetVectors(a);
  }
  write_via_temp(path, [&](const std::filesystem::path& tmp) {
    vtkNew<vtkXMLUnstructuredGridWriter> writer;
    writer->SetFileName(tmp.c_str());
    writer->SetInputData(grid);
    writer->SetDataModeToAppended();
    writer->EncodeAppendedDataOff();
    writer->SetCompressorTypeToLZ4();  // bench/README.md: as fast as none, a fifth smaller; zlib is 20x slower
    writer->SetCompressionLevel(9);    // LZ4's strongest: the same speed as its fastest, a few per cent smaller
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
