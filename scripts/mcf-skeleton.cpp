// A mean-curvature-flow curve skeleton (CGAL's Mean_curvature_flow_skeletonization at
// its default parameters), written as the OBJ polylines `eval --skeletons` reads as a
// reference: `v` lines, and one `l` line per chain between points whose degree is not 2
// (junctions and tips shared; a cycle of degree-2 points is one closed chain).
//
// Build (Debian: `apt-get install libcgal-dev libeigen3-dev`):
//   g++ -O2 -std=c++17 -DNDEBUG -DCGAL_EIGEN3_ENABLED -I/usr/include/eigen3 \
//       scripts/mcf-skeleton.cpp -o mcf-skeleton -lgmp -lmpfr
// Use:
//   mcf-skeleton MESH.obj OUT.mcf.obj
// The mesh must be a closed triangle mesh; one whose faces point inwards is turned
// outwards first (the flow depends on it). The shared references
// (`../shared/data/skeleton/*.mcf.obj`) were made the same way with CGAL 5.5.1.
#include <CGAL/extract_mean_curvature_flow_skeleton.h>
#include <CGAL/Mean_curvature_flow_skeletonization.h>
#include <CGAL/Polygon_mesh_processing/orientation.h>
#include <CGAL/Simple_cartesian.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/boost/graph/IO/polygon_mesh_io.h>

#include <fstream>
#include <iomanip>
#include <iostream>
#include <map>
#include <vector>

using Kernel = CGAL::Simple_cartesian<double>;
using Mesh = CGAL::Surface_mesh<Kernel::Point_3>;
using Skeletonization = CGAL::Mean_curvature_flow_skeletonization<Mesh>;
using Skeleton = Skeletonization::Skeleton;

int main(int argc, char** argv) {
  if (argc != 3) {
    std::cerr << "usage: mcf-skeleton MESH OUT.obj\n";
    return 2;
  }
  Mesh mesh;
  if (!CGAL::IO::read_polygon_mesh(argv[1], mesh) || !CGAL::is_triangle_mesh(mesh)) {
    std::cerr << argv[1] << ": not a triangle mesh\n";
    return 1;
  }
  if (!CGAL::is_closed(mesh)) {
    std::cerr << argv[1] << ": not closed (the flow needs a solid's boundary)\n";
    return 1;
  }
  if (!CGAL::Polygon_mesh_processing::is_outward_oriented(mesh)) {
    CGAL::Polygon_mesh_processing::reverse_face_orientations(mesh);
  }
  Skeleton skeleton;
  CGAL::extract_mean_curvature_flow_skeleton(mesh, skeleton);

  const std::size_t n = num_vertices(skeleton);
  std::vector<std::vector<std::size_t>> neighbours(n);
  for (auto e : CGAL::make_range(edges(skeleton))) {
    std::size_t a = source(e, skeleton), b = target(e, skeleton);
    neighbours[a].push_back(b);
    neighbours[b].push_back(a);
  }
  // Chains between points whose degree is not 2, each edge walked once.
  std::map<std::pair<std::size_t, std::size_t>, bool> walked;
  auto take = [&](std::size_t a, std::size_t b) {
    auto key = std::make_pair(std::min(a, b), std::max(a, b));
    if (walked[key]) return false;
    walked[key] = true;
    return true;
  };
  std::vector<std::vector<std::size_t>> chains;
  auto walk = [&](std::size_t start, std::size_t next) {
    std::vector<std::size_t> chain{start};
    std::size_t at = next;
    for (;;) {
      chain.push_back(at);
      if (neighbours[at].size() != 2 || at == start) break;
      std::size_t ahead = n;
      for (std::size_t w : neighbours[at])
        if (take(at, w)) { ahead = w; break; }
      if (ahead == n) break;
      at = ahead;
    }
    chains.push_back(chain);
  };
  for (int pass = 0; pass < 2; ++pass)  // branches first, then cycles of degree-2 points
    for (std::size_t v = 0; v < n; ++v)
      if ((neighbours[v].size() != 2) == (pass == 0))
        for (std::size_t w : neighbours[v])
          if (take(v, w)) walk(v, w);

  std::ofstream out(argv[2]);
  out << std::setprecision(17) << "# CGAL " << CGAL_VERSION_STR
      << " Mean_curvature_flow_skeletonization, default parameters, of " << argv[1] << "\n";
  for (std::size_t v = 0; v < n; ++v) {
    const auto& p = skeleton[v].point;
    out << "v " << p.x() << " " << p.y() << " " << p.z() << "\n";
  }
  for (const auto& chain : chains) {
    out << "l";
    for (std::size_t i : chain) out << " " << i + 1;
    out << "\n";
  }
  std::cout << argv[1] << ": " << n << " skeleton points, " << chains.size() << " polylines\n";
  return out ? 0 : 1;
}
