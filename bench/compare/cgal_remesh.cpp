// CGAL's tetrahedral isotropic remeshing on a Medit mesh, timed: the baseline that
// bench/run_compare_cgal.sh sets against TetLOD. Not part of the CMake build (CGAL is
// not a TetLOD dependency); the script compiles it.
//
//   cgal_remesh IN.mesh OUT.mesh TARGET_EDGE_LENGTH ITERATIONS [MODE]
//
// Prints the read, remesh and write times in seconds. The subdomains are the Medit tet
// references; CGAL keeps their interfaces and, as features, the curves where three or
// more subdomains meet. MODE:
//   default      CGAL's defaults, nothing else;
//   sharp=DEG    also constrain every interface edge whose two interface triangles
//                bend by more than DEG degrees (what TetLOD's --crease-angle marks as
//                a curve), so that box edges and the magnets' edges are kept;
//   frozen       remesh_boundaries(false): no interface or boundary may change.
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/IO/File_medit.h>
#include <CGAL/Tetrahedral_remeshing/Remeshing_triangulation_3.h>
#include <CGAL/tetrahedral_remeshing.h>

#include <boost/functional/hash.hpp>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <string>
#include <unordered_set>
#include <utility>

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Triangulation = CGAL::Tetrahedral_remeshing::Remeshing_triangulation_3<Kernel>;
using Clock = std::chrono::steady_clock;
using Vertex_handle = Triangulation::Vertex_handle;
using Vertex_pair = std::pair<Vertex_handle, Vertex_handle>;
using Constraints = std::unordered_set<Vertex_pair, boost::hash<Vertex_pair>>;

// Interface edges where the surface bends by more than `degrees`, and edges with more
// than two interface triangles around them.
static Constraints sharp_edges(const Triangulation& tr, double degrees) {
  Constraints out;
  const double cos_limit = std::cos((180.0 - degrees) * M_PI / 180.0);
  for (const auto& e : tr.finite_edges()) {
    const Vertex_handle a = e.first->vertex(e.second), b = e.first->vertex(e.third);
    const auto pa = a->point(), pb = b->point();
    std::vector<Kernel::Vector_3> sides;  // towards each interface triangle's third corner
    auto fc = tr.incident_facets(e), done = fc;
    do {
      const auto mirror = tr.mirror_facet(*fc);
      if (fc->first->subdomain_index() == mirror.first->subdomain_index()) continue;
      for (int k = 0; k < 4; ++k) {
        const Vertex_handle v = fc->first->vertex(k);
        if (k == fc->second || v == a || v == b) continue;
        if (tr.is_infinite(v)) break;
        const Kernel::Vector_3 axis = pb - pa, r = v->point() - pa;
        sides.push_back(r - axis * ((r * axis) / (axis * axis)));
      }
    } while (++fc != done);
    bool sharp = sides.size() > 2;
    if (sides.size() == 2) {
      // Flat: the two half-planes point opposite ways (180 degrees between them).
      const double c =
          (sides[0] * sides[1]) / std::sqrt((sides[0] * sides[0]) * (sides[1] * sides[1]));
      sharp = c > cos_limit;
    }
    if (sharp) out.insert(a < b ? Vertex_pair(a, b) : Vertex_pair(b, a));
  }
  return out;
}

static double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

int main(int argc, char** argv) {
  if (argc != 5 && argc != 6) {
    std::fprintf(stderr,
                 "usage: cgal_remesh IN.mesh OUT.mesh TARGET_EDGE_LENGTH ITERATIONS "
                 "[default|sharp=DEG|frozen]\n");
    return 2;
  }
  const double target = std::atof(argv[3]);
  const int iterations = std::atoi(argv[4]);
  const std::string mode = argc == 6 ? argv[5] : "default";
  double sharp_degrees = -1;
  if (mode.rfind("sharp=", 0) == 0) {
    sharp_degrees = std::atof(mode.c_str() + 6);
  } else if (mode != "default" && mode != "frozen") {
    std::fprintf(stderr, "cgal_remesh: unknown mode '%s'\n", mode.c_str());
    return 2;
  }
  if (!(target > 0) || iterations < 1) {
    std::fprintf(stderr, "cgal_remesh: need a positive length and at least one iteration\n");
    return 2;
  }
  auto start = Clock::now();
  std::ifstream in(argv[1]);
  Triangulation tr;
  if (!in || !CGAL::IO::read_MEDIT(in, tr)) {
    std::fprintf(stderr, "cgal_remesh: %s: cannot read as a Medit triangulation\n", argv[1]);
    return 1;
  }
  const double read_s = seconds_since(start);
  const std::size_t cells_in = tr.number_of_finite_cells();

  start = Clock::now();
  std::size_t constrained = 0;
  if (sharp_degrees >= 0) {
    Constraints edges = sharp_edges(tr, sharp_degrees);
    constrained = edges.size();
    CGAL::tetrahedral_isotropic_remeshing(
        tr, target,
        CGAL::parameters::number_of_iterations(iterations)
            .edge_is_constrained_map(CGAL::make_boolean_property_map(edges)));
  } else {
    CGAL::tetrahedral_isotropic_remeshing(
        tr, target,
        CGAL::parameters::number_of_iterations(iterations).remesh_boundaries(mode != "frozen"));
  }
  const double remesh_s = seconds_since(start);

  start = Clock::now();
  std::ofstream out(argv[2]);
  out.precision(17);  // every double exactly: rounding could flatten a thin tet
  CGAL::IO::write_MEDIT(out, tr);
  out.close();
  if (!out) {
    std::fprintf(stderr, "cgal_remesh: %s: write failed\n", argv[2]);
    return 1;
  }
  std::printf(
      "cgal_remesh (%s, %zu constrained edges): %zu -> %zu finite cells; read %.3f s, "
      "remesh %.3f s%s, write %.3f s\n",
      mode.c_str(), constrained, cells_in, tr.number_of_finite_cells(), read_s, remesh_s,
      sharp_degrees >= 0 ? " (finding the sharp edges included)" : "", seconds_since(start));
  return 0;
}
