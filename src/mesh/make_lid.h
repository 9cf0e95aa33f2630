// The lid: panels on the interior free surface (the waterplane z = 0 inside the waterline), for
// panel codes that remove irregular frequencies (WAMIT IRR = 1, HAMS WaterplaneMesh.pnl,
// Capytaine's lid_mesh, NEMOH 3). Made from a finished wetted mesh in the floating frame: its
// waterline (the boundary edges on z = 0, or for a hull meshed above the waterline too, the
// edges on z = 0 between its wet and dry panels) bounds the lid, and the lid's border vertices
// are the hull's waterline vertices, so hull and lid meet vertex to vertex.
#pragma once

#include <vector>

#include "mesh/surface_mesh.h"

namespace hm {

struct LidOptions {
  // Target edge length (m); 0 takes the edge of an equilateral triangle with the mean area of
  // the hull's panels (as many lid panels per square metre as hull panels).
  double edge_length = 0;
  // A hull vertex with |z| at most this is on the waterplane (m); 0 takes 1e-9 of the hull size.
  double plane_tol = 0;
  // A half hull's waterline ends within this of y = 0 (m); 0 takes 1e-6 of the hull size.
  double centre_tol = 0;
};

struct LidReport {
  std::size_t loops = 0;               // closed waterlines (one lid region each)
  std::size_t waterline_vertices = 0;  // shared with the hull
  std::size_t centre_vertices = 0;     // added on y = 0 to close a half hull's waterline
  std::size_t interior_vertices = 0;
  double edge_length = 0;  // the target used (m)
  double area = 0;         // of the lid (m^2): the waterplane area inside the waterline
  bool half = false;       // closed along y = 0 (a half hull)
};

struct Lid {
  // Triangles on z = 0 exactly, counter-clockwise seen from above (normal +z, so that hull and
  // lid together are a closed surface with its normals out of the enclosed volume).
  // face_patch and face_block are kInvalid (no source patch).
  SurfaceMesh mesh;
  // Per lid vertex: the hull vertex it coincides with, kInvalid for the new ones.
  std::vector<Index> vert_lid2hull;
  LidReport report;
};

// Throws GeometryError when the hull has no waterline on z = 0, when the waterline is not closed
// (open ends off the centre plane: a hole in the hull at the waterline), when it branches, or
// when one waterline lies inside another (a moonpool: not a lid).
Lid make_lid(const SurfaceMesh& hull, const LidOptions& options = {});

// The hull with the lid's panels appended after its own (lid vertices that coincide with hull
// vertices reuse them): one file for the codes that read body and lid together (WAMIT IRR = 1).
SurfaceMesh append_lid(const SurfaceMesh& hull, const Lid& lid);

}  // namespace hm
