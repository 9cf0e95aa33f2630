// cgal_collapse: CGAL's edge-collapse simplification of a triangle mesh, the peer of hullmesh's
// coarsening in scripts/compare-peers.
//
//   cgal_collapse IN.(off|obj|stl) OUT.(off|stl) --faces 4000 --policy lt|gh|edge-length
//
// Border edges are constrained (as in CGAL's example edge_collapse_constrained_border_surface_mesh)
// so that the hull's open edges stay where they are. Prints one line,
//   collapse_seconds <s> faces_in <n> faces_out <m>
// where the time is of the edge_collapse call alone, without reading or writing.
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/IO/polygon_mesh_io.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/Surface_mesh_simplification/Policies/Edge_collapse/Constrained_placement.h>
#include <CGAL/Surface_mesh_simplification/Policies/Edge_collapse/Edge_length_cost.h>
#include <CGAL/Surface_mesh_simplification/Policies/Edge_collapse/GarlandHeckbert_plane_policies.h>
#include <CGAL/Surface_mesh_simplification/Policies/Edge_collapse/LindstromTurk_cost.h>
#include <CGAL/Surface_mesh_simplification/Policies/Edge_collapse/LindstromTurk_placement.h>
#include <CGAL/Surface_mesh_simplification/Policies/Edge_collapse/Midpoint_placement.h>
#include <CGAL/Surface_mesh_simplification/edge_collapse.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <string>

namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Mesh = CGAL::Surface_mesh<Kernel::Point_3>;
using EdgeDescriptor = boost::graph_traits<Mesh>::edge_descriptor;
namespace sms = CGAL::Surface_mesh_simplification;

// Marks the border edges as constrained: edge_collapse never collapses them, and
// Constrained_placement keeps their vertices in place.
struct BorderIsConstrained {
  using key_type = EdgeDescriptor;
  using value_type = bool;
  using reference = bool;
  using category = boost::readable_property_map_tag;
  const Mesh* mesh;
  friend bool get(const BorderIsConstrained& m, EdgeDescriptor e) {
    return CGAL::is_border(e, *m.mesh);
  }
};

// Stops at the face count. CGAL 5.5 has only Count_stop_predicate on edges
// (Face_count_stop_predicate came with 6.0); the live face count is exact and costs nothing.
struct FaceCountStop {
  std::size_t target;
  template <typename Cost, typename Profile>
  bool operator()(const Cost&, const Profile& profile, std::size_t, std::size_t) const {
    return profile.surface_mesh().number_of_faces() <= target;
  }
};

[[noreturn]] void fail(const std::string& message) {
  std::fprintf(stderr, "cgal_collapse: %s\n", message.c_str());
  std::exit(1);
}

bool has_suffix(const std::string& s, const std::string& suffix) {
  return s.size() >= suffix.size() &&
         s.compare(s.size() - suffix.size(), suffix.size(), suffix) == 0;
}

// Reads the mesh as it is; falls back to CGAL's soup repair and orientation (needed for STL).
Mesh read_mesh(const std::string& path) {
  Mesh mesh;
  if (!CGAL::IO::read_polygon_mesh(path, mesh) || mesh.is_empty()) {
    mesh.clear();
    if (!CGAL::Polygon_mesh_processing::IO::read_polygon_mesh(path, mesh) || mesh.is_empty()) {
      fail(path + ": cannot read a polygon mesh (missing, unknown format or not a manifold)");
    }
  }
  if (!CGAL::is_triangle_mesh(mesh)) fail(path + ": not a triangle mesh");
  return mesh;
}

// Runs edge_collapse with the policy's cost and placement; returns the seconds it took.
template <typename Cost, typename Placement>
double collapse(Mesh& mesh, std::size_t faces, const Cost& cost, const Placement& placement) {
  const BorderIsConstrained border{&mesh};
  const auto start = std::chrono::steady_clock::now();
  sms::edge_collapse(
      mesh, FaceCountStop{faces},
      CGAL::parameters::edge_is_constrained_map(border).get_cost(cost).get_placement(
          sms::Constrained_placement<Placement, BorderIsConstrained>(border, placement)));
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace

int main(int argc, char** argv) {
  std::string in, out, policy;
  long faces = 0;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--faces" && i + 1 < argc) {
      faces = std::strtol(argv[++i], nullptr, 10);
    } else if (arg == "--policy" && i + 1 < argc) {
      policy = argv[++i];
    } else if (in.empty()) {
      in = arg;
    } else if (out.empty()) {
      out = arg;
    } else {
      fail("unexpected argument " + arg);
    }
  }
  if (in.empty() || out.empty() || faces <= 0 ||
      (policy != "lt" && policy != "gh" && policy != "edge-length")) {
    fail(
        "usage: cgal_collapse IN.(off|obj|stl) OUT.(off|stl) --faces N --policy lt|gh|edge-length");
  }
  if (!has_suffix(out, ".off") && !has_suffix(out, ".stl")) fail(out + ": write .off or .stl");

  Mesh mesh = read_mesh(in);
  const std::size_t faces_in = mesh.number_of_faces();
  double seconds = 0;
  if (policy == "lt") {
    seconds = collapse(mesh, faces, sms::LindstromTurk_cost<Mesh>(),
                       sms::LindstromTurk_placement<Mesh>());
  } else if (policy == "gh") {
    // The policy object is both cost and placement; its quadrics live in a shared property map.
    const sms::GarlandHeckbert_plane_policies<Mesh, Kernel> gh(mesh);
    seconds = collapse(mesh, faces, gh.get_cost(), gh.get_placement());
  } else {
    seconds = collapse(mesh, faces, sms::Edge_length_cost<Mesh>(), sms::Midpoint_placement<Mesh>());
  }
  mesh.collect_garbage();

  if (!CGAL::IO::write_polygon_mesh(out, mesh, CGAL::parameters::stream_precision(17))) {
    fail(out + ": cannot write");
  }
  std::printf("collapse_seconds %.6f faces_in %zu faces_out %zu\n", seconds, faces_in,
              static_cast<std::size_t>(mesh.number_of_faces()));
  return 0;
}
