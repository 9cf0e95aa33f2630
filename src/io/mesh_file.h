// A mesh as a file carries it: the panels plus what panel codes keep beside them (symmetry,
// WAMIT's ULEN and GRAV, a title) and, for VTK formats, named per-face values.
//
// Internal convention, for every reader and writer in io/:
//   - positions in metres, ship frame: x forward, y to port, z up;
//   - faces have 3 or 4 corners; a triangle's fourth index is kInvalid;
//   - the normal by the right-hand rule over the corners (face_normal) points INTO THE FLUID,
//     i.e. out of the ship. Each format's file states how its own convention maps onto this one;
//     a writer converts on the way out and the reader converts back, so that a round trip keeps
//     the corner order.
#pragma once

#include <string>
#include <vector>

#include "mesh/surface_mesh.h"

namespace hm {

// Which planes of symmetry the file declares. The stored panels are then the half (or quarter)
// on the positive side: y >= 0 for about_y0 (the port half), x >= 0 for about_x0.
struct MeshSymmetry {
  bool about_y0 = false;  // the xz-plane y = 0 (a ship's centre plane)
  bool about_x0 = false;  // the yz-plane x = 0 (only some formats can say so)

  bool any() const { return about_y0 || about_x0; }
  friend bool operator==(const MeshSymmetry&, const MeshSymmetry&) = default;
};

struct MeshFileInfo {
  std::string title = "hullmesh";  // header line, where the format has one
  MeshSymmetry symmetry;
  double ulen = 1.0;      // WAMIT ULEN: the characteristic length, in the file's length unit (m)
  double grav = 9.80665;  // WAMIT GRAV: gravity in that unit per s^2
  // HAMS: the file is a WaterplaneMesh.pnl (interior waterplane lid), not a HullMesh.pnl.
  bool waterplane_lid = false;
};

// A named per-face value read back from VTK cell data (one value per face).
struct NamedFaceField {
  std::string name;
  std::vector<double> values;
};

struct MeshFile {
  SurfaceMesh mesh;  // face_patch always has one entry per face (0 where the format has no groups)
  MeshFileInfo info;
  std::vector<NamedFaceField> fields;  // cell data other than patch and block (VTK, VTU)
};

}  // namespace hm
