// The VTU files read back with VTK's own XML reader (the one ParaView uses): quadratic tetra cells, the node order,
// the fields and their values survive the round trip; the .pvd names every load case.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include <vtkCellData.h>
#include <vtkDataArray.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkUnstructuredGrid.h>
#include <vtkXMLUnstructuredGridReader.h>

#include "io/vtu.hpp"
#include "tests/fem/box_mesh.hpp"

namespace sw {
namespace {

TEST(Vtu, RoundTripsThroughVtksReaderWithQuadraticTetraAndFields) {
  const TetMesh m = test::distorted_box(2, 0.01, 0.2);
  NodalField disp{"displacement", Eigen::MatrixXd(m.n_nodes(), 3)};
  for (std::size_t i = 0; i < m.n_nodes(); ++i) disp.values.row(i) << 1e-3 * i, -2e-3 * i, 0.5;
  NodalField hoop{"stress_hoop", Eigen::MatrixXd::Constant(m.n_nodes(), 1, 123.0)};
  const auto path = std::filesystem::temp_directory_path() / "sw_test_roundtrip.vtu";
  write_vtu(path, m, {disp, hoop});

  vtkNew<vtkXMLUnstructuredGridReader> reader;
  reader->SetFileName(path.c_str());
  reader->Update();
  vtkUnstructuredGrid* grid = reader->GetOutput();
  ASSERT_EQ(grid->GetNumberOfPoints(), static_cast<vtkIdType>(m.n_nodes()));
  ASSERT_EQ(grid->GetNumberOfCells(), static_cast<vtkIdType>(m.tets.size()));
  EXPECT_EQ(grid->GetCellType(0), VTK_QUADRATIC_TETRA);
  vtkIdType npts;
  const vtkIdType* ids;
  grid->GetCellPoints(3, npts, ids);
  ASSERT_EQ(npts, 10);
  for (int a = 0; a < 10; ++a) EXPECT_EQ(ids[a], m.tets[3][a]);
  vtkDataArray* d = grid->GetPointData()->GetArray("displacement");
  ASSERT_NE(d, nullptr);
  EXPECT_EQ(grid->GetPointData()->GetVectors(), d);  // Warp By Vector picks it up without choosing
  EXPECT_DOUBLE_EQ(d->GetComponent(7, 1), -2e-3 * 7);
  ASSERT_NE(grid->GetPointData()->GetArray("stress_hoop"), nullptr);
  ASSERT_NE(grid->GetCellData()->GetArray("region"), nullptr);
  std::filesystem::remove(path);

  const auto pvd = std::filesystem::temp_directory_path() / "sw_test.pvd";
  write_pvd(pvd, {{"generator", "a.vtu"}, {"torque", "b.vtu"}});
  std::ifstream in(pvd);
  std::stringstream text;
  text << in.rdbuf();
  EXPECT_NE(text.str().find("name=\"torque\" file=\"b.vtu\""), std::string::npos);
  std::filesystem::remove(pvd);
}

}  // namespace
}  // namespace sw
