// Hostile and broken files, per reader: truncated, negative or huge counts (10^12 panels must be
// refused before anything is allocated), NaN, and references out of range. Each asserts the
// error type and that the message names the file and the line.
#include <gtest/gtest.h>

#include <cstring>
#include <limits>
#include <string>

#include "core/error.h"
#include "io/read_mesh.h"

namespace hm {
namespace {

template <typename E>
void expect_error(const char* ext, const std::string& text, const std::string& where) {
  const std::string name = std::string("bad") + ext;
  try {
    read_mesh_from_memory(text, ext, name);
    ADD_FAILURE() << ext << ": no error for\n" << text;
  } catch (const E& e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find(name), std::string::npos) << msg;
    EXPECT_NE(msg.find(where), std::string::npos) << "expected '" << where << "' in: " << msg;
  } catch (const std::exception& e) {
    ADD_FAILURE() << ext << ": wrong error type: " << e.what();
  }
}

const std::string kGdfHead = "title\n1 9.80665\n0 1\n";
const std::string kPanel = "0 0 0\n1 0 0\n1 1 0\n0 1 0\n";

TEST(BadInput, Gdf) {
  expect_error<InputError>(".gdf", kGdfHead + "2\n" + kPanel + "0.25 0.25 0.25\n1.0 0.125 ",
                           "line 10");
  expect_error<InputError>(".gdf", kGdfHead + "-1\n", "line 4");
  expect_error<LimitError>(".gdf", kGdfHead + "1000000000000\n" + kPanel, "line 4");
  expect_error<InputError>(".gdf", kGdfHead + "1\n0 0 0\n1 nan 0\n1 1 0\n0 1 0\n", "line 6");
  expect_error<InputError>(".gdf", kGdfHead + "1\n0 0 0\n0 0 0\n0 0 0\n1 1 0\n", "line 8");
  expect_error<InputError>(".gdf", "title\n1 9.8\n2 0\n1\n" + kPanel, "line 3");
  expect_error<InputError>(".gdf", "", "line 0");
  // A count the file could never hold is refused before allocating for it.
  expect_error<InputError>(".gdf", kGdfHead + "40000000\n" + kPanel, "line 4");
}

TEST(BadInput, Nemoh) {
  const std::string nodes = "2 0\n1 0 0 0\n2 1 0 0\n3 1 1 0\n0 0. 0. 0.\n";
  expect_error<InputError>(".dat", nodes + "1 2 3 3\n", "line 6");  // no closing 0 0 0 0
  expect_error<InputError>(".dat", nodes + "1 2 9 3\n0 0 0 0\n", "line 6");
  expect_error<InputError>(".dat", nodes + "1 2 -3 3\n0 0 0 0\n", "line 6");
  expect_error<InputError>(".dat", "2 0\n1 0 0 0\n2 1 NaN 0\n", "line 3");
  expect_error<InputError>(".dat", "2 0\n1 0 0 0\n3 1 0 0\n", "line 3");  // out of order
  expect_error<InputError>(".dat", "3 0\n", "line 1");
}

const std::string kPnlHead =
    "    --------------Hull Mesh File---------------\n \n"
    "    # Number of Panels, Nodes, X-Symmetry and Y-Symmetry\n";
const std::string kPnlNodes =
    "    #Start Definition of Node Coordinates\n 1 0 0 0\n 2 1 0 0\n 3 1 1 0\n"
    "   #End Definition of Node Coordinates\n \n   #Start Definition of Node Relations\n";

TEST(BadInput, Pnl) {
  expect_error<InputError>(".pnl", kPnlHead + "    1 3 0 0\n" + kPnlNodes + " 1 3 1 2 3\n",
                           "line 12");  // truncated: no End line
  expect_error<InputError>(".pnl", kPnlHead + "    -1 3 0 0\n", "line 4");
  expect_error<LimitError>(".pnl", kPnlHead + "    1000000000000 3 0 0\n", "line 4");
  expect_error<InputError>(".pnl", kPnlHead + "    1 3 0 0\n" + kPnlNodes + " 1 3 1 2 4\n",
                           "line 12");
  expect_error<InputError>(".pnl",
                           kPnlHead +
                               "    1 1 0 0\n    #Start Definition of Node Coordinates\n"
                               " 1 0 inf 0\n",
                           "line 6");
  expect_error<InputError>(".pnl", "not a mesh\n", "line 1");
}

TEST(BadInput, Hst) {
  const std::string nodes =
      "COORDINATES TYPE 0\n1 0.0 0.0 0.0\n2 1.0 0.0 0.0\n3 1.0 1.0 0.0\n"
      "ENDCOORDINATES\n";
  expect_error<InputError>(".hst", nodes + "PANEL TYPE 0\n1 2 3\n", "line 7");
  expect_error<LimitError>(".hst", "NUMPANEL 1 1 1000000000000\n" + nodes, "line 1");
  expect_error<InputError>(".hst", "NUMPANEL 1 1 -5\n" + nodes, "line 1");
  expect_error<InputError>(".hst", nodes + "PANEL TYPE 0\n1 2 7\nENDPANEL\n", "line 7");
  expect_error<InputError>(".hst", "COORDINATES TYPE 0\n1 0.0 nan 0.0\n", "line 2");
  expect_error<InputError>(".hst", "NBBODY 2\n", "line 1");
}

const std::string kMshHead = "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n";

TEST(BadInput, Msh) {
  const std::string nodes = "$Nodes\n1 3 1 3\n2 1 0 3\n1\n2\n3\n0 0 0\n1 0 0\n1 1 0\n$EndNodes\n";
  expect_error<InputError>(".msh", kMshHead + nodes + "$Elements\n1 1 1 1\n2 1 2 1\n1 1 2",
                           "line 17");
  expect_error<InputError>(".msh", kMshHead + "$Nodes\n1 -3 1 3\n", "line 5");
  expect_error<LimitError>(".msh", kMshHead + "$Nodes\n1 1000000000000 1 3\n", "line 5");
  expect_error<InputError>(".msh", kMshHead + "$Nodes\n1 1 1 1\n2 1 0 1\n1\n0 nan 0\n", "line 8");
  expect_error<InputError>(
      ".msh", kMshHead + nodes + "$Elements\n1 1 1 1\n2 1 2 1\n1 1 2 9\n$EndElements\n", "line 17");
  expect_error<InputError>(".msh", "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n", "line 2");
  expect_error<InputError>(
      ".msh", kMshHead + nodes + "$Elements\n1 1 1 1\n2 1 9 1\n1 1 2 3 1 2 3\n$EndElements\n",
      "line 16");
}

const std::string kVtkHead = "# vtk DataFile Version 3.0\nt\nASCII\nDATASET POLYDATA\n";

TEST(BadInput, Vtk) {
  const std::string pts = "POINTS 3 double\n0 0 0\n1 0 0\n1 1 0\n";
  expect_error<InputError>(".vtk", kVtkHead + pts + "POLYGONS 1 4\n3 0 1", "line 9");
  expect_error<InputError>(".vtk", kVtkHead + "POINTS -3 double\n", "line 5");
  expect_error<LimitError>(".vtk", kVtkHead + "POINTS 1000000000000 double\n", "line 5");
  expect_error<InputError>(".vtk", kVtkHead + "POINTS 1 double\n0 nan 0\n", "line 6");
  expect_error<InputError>(".vtk", kVtkHead + pts + "POLYGONS 1 4\n3 0 1 5\n", "line 10");
  expect_error<InputError>(".vtk", "# vtk DataFile Version 3.0\nt\nBINARY\n", "line 3");
}

// Found by fuzz_mesh: a FIELD array with zero components divided by zero.
TEST(BadInput, VtkFieldArrayWithNoComponents) {
  expect_error<InputError>(
      ".vtk", kVtkHead + "POINTS 1 double\n0 0 0\nFIELD FieldData 1\nsymmetry 0 1 int\n1 0\n",
      "line 8");
}

TEST(BadInput, Vtu) {
  const std::string head = "<VTKFile type=\"UnstructuredGrid\">\n<UnstructuredGrid>\n";
  auto piece = [&](const std::string& np, const std::string& points, const std::string& conn) {
    return head + "<Piece NumberOfPoints=\"" + np + "\" NumberOfCells=\"1\">\n" +
           "<Points>\n<DataArray type=\"Float64\" NumberOfComponents=\"3\" format=\"ascii\">\n" +
           points + "</DataArray>\n</Points>\n<Cells>\n" +
           "<DataArray type=\"Int64\" Name=\"connectivity\" format=\"ascii\">\n" + conn +
           "</DataArray>\n<DataArray type=\"Int64\" Name=\"offsets\" format=\"ascii\">\n3\n"
           "</DataArray>\n<DataArray type=\"UInt8\" Name=\"types\" format=\"ascii\">\n5\n"
           "</DataArray>\n</Cells>\n</Piece>\n</UnstructuredGrid>\n</VTKFile>\n";
  };
  const std::string good_pts = "0 0 0\n1 0 0\n1 1 0\n";
  ASSERT_NO_THROW(read_mesh_from_memory(piece("3", good_pts, "0 1 2\n"), ".vtu", "ok.vtu"));
  const std::string full = piece("3", good_pts, "0 1 2\n");
  expect_error<InputError>(".vtu", full.substr(0, full.find("0 1 2\n") + 6), "line 12");
  expect_error<InputError>(".vtu", piece("-3", good_pts, "0 1 2\n"), "line 3");
  expect_error<LimitError>(".vtu", piece("1000000000000", good_pts, "0 1 2\n"), "line 3");
  expect_error<InputError>(".vtu", piece("3", "0 0 0\n1 nan 0\n1 1 0\n", "0 1 2\n"), "line 7");
  expect_error<InputError>(".vtu", piece("3", good_pts, "0 1 7\n"), "line 12");
}

TEST(BadInput, Stl) {
  const std::string facet =
      "facet normal 0 0 1\n outer loop\n  vertex 0 0 0\n  vertex 1 0 0\n  vertex 1 1 0\n"
      " endloop\nendfacet\n";
  expect_error<InputError>(".stl", "solid s\n" + facet, "line 8");  // no endsolid
  expect_error<InputError>(".stl", "solid s\n" + facet.substr(0, 60), "line 5");
  expect_error<InputError>(".stl", "solid s\nfacet normal 0 0 1\n outer loop\n  vertex 0 nan 0\n",
                           "line 4");
  // Binary: 10^9 declared triangles in a 134-byte file is a truncated file, not an allocation.
  std::string bin(134, '\0');
  const std::uint32_t n = 1000000000u;
  for (int b = 0; b < 4; ++b) bin[80 + b] = char((n >> (8 * b)) & 0xff);
  expect_error<InputError>(".stl", bin, "declares 1000000000 triangles");
  std::string one(134, '\0');
  one[80] = 1;
  const float nan = std::numeric_limits<float>::quiet_NaN();
  std::memcpy(one.data() + 84 + 16, &nan, 4);
  expect_error<InputError>(".stl", one, "triangle 1 (byte offset 84)");
  ReadOptions small;
  small.limits.max_triangles = 0;
  std::string ok(134, '\0');
  ok[80] = 1;
  EXPECT_THROW(read_mesh_from_memory(ok, ".stl", "m.stl", small), LimitError);
  expect_error<InputError>(".stl", "hello", "not an STL file");
}

TEST(BadInput, Obj) {
  expect_error<InputError>(".obj", "v 0 0 0\nv 1 0 0\nv 1 1 0\nf 1 2 4\n", "line 4");
  expect_error<InputError>(".obj", "v 0 0 0\nv 1 0 0\nv 1 1 0\nf 1 2 -4\n", "line 4");
  expect_error<InputError>(".obj", "v 0 0 0\nv 1 nan 0\n", "line 2");
  expect_error<InputError>(".obj", "v 0 0 0\nv 1 0 0\nf 1 2\n", "line 3");
  ReadOptions small;
  small.limits.max_triangles = 1;
  EXPECT_THROW(read_mesh_from_memory("v 0 0 0\nv 1 0 0\nv 1 1 0\nf 1 2 3\nf 1 2 3\n", ".obj",
                                     "m.obj", small),
               LimitError);
}

}  // namespace
}  // namespace hm
