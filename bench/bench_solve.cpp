// Speed of the electrostatic solve (issue 6: assemble and solve 100k tets in <= 1 s,
// 1M tets in <= 15 s, one core). The input is the bundled spheres model refined
// uniformly 1:8 once (~129k tets) and twice (~1.03M tets), solved as the two-layer
// spherical capacitor (material 1 at 1, material 4 grounded, eps2 = 2, eps3 = 5).
// With --box, material 4 is a dielectric (eps 1) and the box boundary is grounded
// instead. Any other mesh: --conductor M (at 1) and --ground M|boundary, every other
// material eps 1. Prints the median of N runs of each phase, the iterations and C.
//
//   bench_solve [--repeat N] [--levels L] [--box] [--ic] [--direct] [--tolerance T]
//               [--conductor M --ground M|boundary] [MESH]
//
// MESH defaults to assets/spheres.mesh (run from the repository root).
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "bench/bench_util.h"
#include "core/electrostatics.h"
#include "core/io/mesh_io.h"
#include "core/refine.h"

using tetlod::bench::Clock;
using tetlod::bench::median;
using tetlod::bench::seconds_since;

int main(int argc, char** argv) {
  using namespace tetlod;
  std::string path = "assets/spheres.mesh";
  int repeat = 5, levels = 2;
  SolveOptions options;
  bool box = false;
  int conductor = -1, ground = -1;  // -1: the spheres capacitor; ground -2: boundary
  options.method = SolverMethod::kIterative;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--repeat" && i + 1 < argc) {
      repeat = std::max(1, std::atoi(argv[++i]));
    } else if (a == "--levels" && i + 1 < argc) {
      levels = std::max(0, std::atoi(argv[++i]));
    } else if (a == "--tolerance" && i + 1 < argc) {
      options.tolerance = std::atof(argv[++i]);
    } else if (a == "--conductor" && i + 1 < argc) {
      conductor = std::atoi(argv[++i]);
    } else if (a == "--ground" && i + 1 < argc) {
      ++i;
      ground = std::string(argv[i]) == "boundary" ? -2 : std::atoi(argv[i]);
    } else if (a == "--box") {
      box = true;
    } else if (a == "--ic") {
      options.preconditioner = Preconditioner::kIncompleteCholesky;
    } else if (a == "--direct") {
      options.method = SolverMethod::kDirect;
    } else if (!a.empty() && a[0] != '-') {
      path = a;
    } else {
      std::fprintf(stderr,
                   "usage: bench_solve [--repeat N] [--levels L] [--box] [--ic] [--direct] "
                   "[--tolerance T] [--conductor M --ground M|boundary] [MESH]\n");
      return 2;
    }
  }
  TetMesh mesh;
  if (const Status s = read_mesh(path, &mesh); !s) {
    std::fprintf(stderr, "bench_solve: %s\n", s.message().c_str());
    return 1;
  }
  ElectrostaticsProblem problem;
  problem.conductors = {{1, 1.0}};
  problem.ground_materials = {4};
  problem.permittivities = {{2, 2.0}, {3, 5.0}};
  if (box) {
    problem.ground_materials.clear();
    problem.ground_boundary = true;
  }
  if (conductor >= 0) {
    problem = ElectrostaticsProblem();
    problem.conductors = {{conductor, 1.0}};
    if (ground == -2) {
      problem.ground_boundary = true;
    } else {
      problem.ground_materials = {ground};
    }
  }
  std::printf("%-9s %9s %9s %7s %8s %8s %8s %8s %8s %6s %10s %9s\n", "level", "tets", "unknowns",
              "nnz/1e6", "setup", "assemble", "factor", "solve", "total", "iters", "residual", "C");
  for (int level = 0; level <= levels; ++level) {
    if (level > 0) mesh = refine_uniform(mesh);
    std::vector<double> setup, assemble, factor, solve, total;
    ElectrostaticsSolution solution;
    for (int r = 0; r < repeat; ++r) {
      const auto start = Clock::now();
      if (const Status s = solve_electrostatics(mesh, problem, options, &solution); !s) {
        std::fprintf(stderr, "bench_solve: %s\n", s.message().c_str());
        return 1;
      }
      total.push_back(seconds_since(start));
      setup.push_back(solution.seconds_setup);
      assemble.push_back(solution.seconds_assemble);
      factor.push_back(solution.seconds_factor);
      solve.push_back(solution.seconds_solve);
    }
    std::printf("refine x%d %9zu %9zu %7.2f %8.3f %8.3f %8.3f %8.3f %8.3f %6d %10.2e %9.6f\n",
                level, mesh.tet_count(), solution.free_count, solution.nonzeros / 1e6,
                median(setup), median(assemble), median(factor), median(solve), median(total),
                solution.iterations, solution.relative_residual, solution.capacitance);
    std::fflush(stdout);
  }
  return 0;
}
