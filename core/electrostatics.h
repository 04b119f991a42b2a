// Electrostatics on a multi-material tet mesh with linear (P1) finite elements: the
// analysis check of issue 6 (Date et al., section V.C compares the accuracy of an
// analysis on simplified and dense meshes; here the analysis is a capacitance).
//
// Solves -div(eps grad u) = 0 with eps > 0 constant per material:
//  - Dirichlet: every node of a conductor material is held at its potential; every
//    node of a ground material, and (optionally) every node on the outer boundary, at 0;
//  - natural (zero normal flux) everywhere else on the boundary.
// Dirichlet rows are eliminated symmetrically, so the system of the free nodes is
// symmetric positive definite when every connected free region touches a Dirichlet
// node (checked). It is solved by a direct sparse LDL^T factorisation for small
// systems and by preconditioned conjugate gradients otherwise.
//
// Outputs: the field energy W = 1/2 sum_t eps_t V_t |grad u_t|^2 (exact for P1), the
// capacitance C = 2 W / V^2 where V is the largest minus the smallest Dirichlet
// potential (the capacitance between two electrodes; with more electrodes at several
// potentials it is only a normalised energy), the potential per node and |E| = |grad u|
// per tet.
//
// Since u_h minimises the energy over P1 functions with the same Dirichlet data, W_h
// (and C_h) is never below the exact energy of the same (polyhedral) geometry and
// decreases under nested refinement (refine.h).
//
// Units: eps and lengths in any consistent units; with eps in F/m and lengths in m,
// C is in farads. No globals: solves may run in parallel threads.
#pragma once

#include <atomic>
#include <cstdint>
#include <functional>
#include <string>
#include <utility>
#include <vector>

#include "core/status.h"
#include "core/tet_mesh.h"

namespace tetlod {

struct ElectrostaticsProblem {
  // (material, potential): every node of a tet of that material is held at the
  // potential, 0 or of magnitude in [1e-30, 1e30]. At least one is needed.
  std::vector<std::pair<int32_t, double>> conductors;
  // Materials whose nodes are held at 0.
  std::vector<int32_t> ground_materials;
  // Also hold every node of the outer boundary at 0.
  bool ground_boundary = false;
  // Surfaces held at a potential (0 for a ground): the input's surface groups (a Gmsh
  // physical surface, say) given by their vertices, each < the mesh's vertex count.
  struct HeldSurface {
    std::string name;  // for messages
    std::vector<uint32_t> vertices;
    double potential = 0;
    bool ground = false;  // a ground (held at 0), else a conductor
  };
  std::vector<HeldSurface> surfaces;
  // (material, eps), eps in [1e-30, 1e30]. Materials not listed get default_permittivity.
  std::vector<std::pair<int32_t, double>> permittivities;
  double default_permittivity = 1.0;
};

enum class SolverMethod {
  kAuto,       // direct up to SolveOptions::direct_max_unknowns, else kIterative
  kDirect,     // Eigen::SimplicialLDLT
  kIterative,  // conjugate gradients with the chosen preconditioner
};

// Jacobi is the default: on the meshes measured (spheres and motor, 16k-1.1M tets,
// docs/PERFORMANCE.md) IC halves the iterations but its factorisation and triangular
// solves cost more than it saves, single-threaded.
enum class Preconditioner {
  kJacobi,              // diagonal scaling
  kIncompleteCholesky,  // Eigen::IncompleteCholesky (threshold IC with a diagonal shift)
};

// Below this relative residual the rounding of double precision decides, not CG:
// the iteration would stall or break down rather than converge.
inline constexpr double kMinSolverTolerance = 1e-14;

struct SolveOptions {
  SolverMethod method = SolverMethod::kAuto;
  Preconditioner preconditioner = Preconditioner::kJacobi;
  // The direct solver is exact but its fill grows fast in 3D (1 s at 14k unknowns
  // against 0.03 s for CG), so it is kept for small systems.
  size_t direct_max_unknowns = 2000;
  // CG stops when |b - A x| <= tolerance * |b| (2-norms of the reduced system);
  // in [kMinSolverTolerance, 1).
  double tolerance = 1e-10;
  // CG gives up (an error, not a wrong number) after this many iterations.
  int max_iterations = 20000;
};

struct ElectrostaticsSolution {
  std::vector<double> potential;                // per vertex
  std::vector<double> field_magnitude;          // per tet, |grad u|
  double energy = 0;                            // W
  double voltage = 0;                           // V = largest - smallest Dirichlet potential
  double capacitance = 0;                       // C = 2 W / V^2
  size_t free_count = 0;                        // unknowns
  size_t dirichlet_count = 0;                   // nodes with a prescribed potential
  size_t nonzeros = 0;                          // entries of the reduced matrix (both triangles)
  SolverMethod method = SolverMethod::kDirect;  // the one used (never kAuto)
  int iterations = 0;                           // CG iterations (0 for the direct solver)
  double relative_residual = 0;                 // |b - A x| / |b|, recomputed from the solution
  bool cancelled = false;                       // stopped by the cancel flag: nothing else is valid
  double seconds_setup = 0;                     // checks, Dirichlet marking, sparsity pattern
  double seconds_assemble = 0;                  // stiffness values and right-hand side
  double seconds_factor = 0;                    // preconditioner or direct factorisation
  double seconds_solve = 0;  // CG iterations or triangular solves, and the outputs
};

struct SolveProgress {
  const char* phase = "";  // "setup", "assemble", "factor", "solve"
  double fraction = 0;     // of the phase, in [0, 1]; for "solve" an estimate from the residual
  int iteration = 0;
  double relative_residual = 0;
};
using SolveProgressCallback = std::function<void(const SolveProgress&)>;

// A material given twice: as a conductor or ground twice (or both), or two
// permittivities; the error names it. One of check_electrostatics_problem()'s checks,
// for a caller that merges the lists (the viewer's Analysis panel holds one role a
// material).
Status check_repeated_materials(const ElectrostaticsProblem& problem);

// The problem's own checks (solve_electrostatics() makes them too): every material it
// names is one of `mesh`'s, none twice, permittivities (> 0) and potentials finite
// and within 1e30 in magnitude; the error names the value. A caller that took them
// from a user can tell a bad option from a bad mesh.
Status check_electrostatics_problem(const ElectrostaticsProblem& problem, const TetMesh& mesh);

// Checks the problem against the mesh, assembles and solves. Errors, which name the
// offending value, for: a mesh that breaks the invariants of tet_mesh.h (an index out
// of range, non-finite coordinates, an inverted or degenerate tet), a material id in
// the problem that no tet has, a material given twice, eps <= 0 or not finite, a
// non-finite potential, no conductor, a conductor node that is also held at another
// potential (a conductor touching the ground or another conductor), equal potentials
// everywhere, a free region connected to no Dirichlet node (the potential there is
// undetermined), and CG that does not converge (or whose recomputed residual is over
// 1000x the tolerance). `progress` is called from the calling thread; `cancel`, if set,
// is polled between phases and every CG iteration, and a cancelled solve returns ok
// with solution->cancelled set. Meant to run in a worker thread: no globals, the mesh
// and problem are only read.
Status solve_electrostatics(const TetMesh& mesh, const ElectrostaticsProblem& problem,
                            const SolveOptions& options, ElectrostaticsSolution* solution,
                            const SolveProgressCallback& progress = {},
                            const std::atomic<bool>* cancel = nullptr);

// The exact capacitance of concentric spherical shells: a conductor ball of radius
// radii[0], shells radii[i] < r < radii[i+1] of permittivity eps[i], and a grounded
// sphere of radius radii.back():
//   1/C = sum_i (1 / (4 pi eps_i)) (1/r_i - 1/r_{i+1}).
// For the `spheres` model: radii {r1, r2, r3}, eps {eps2, eps3}.
// Precondition: radii increasing and positive, eps.size() == radii.size() - 1.
double concentric_spheres_capacitance(const std::vector<double>& radii,
                                      const std::vector<double>& eps);

}  // namespace tetlod
