// P1 electrostatics (see electrostatics.h). The recipe:
//   check the problem -> check the mesh -> mark Dirichlet nodes -> number the free
//   nodes -> sparsity pattern of the free block (CSR, both triangles) -> check every
//   free region reaches a Dirichlet node -> assemble values and right-hand side ->
//   solve (LDL^T or PCG) -> energy, capacitance, |E|.
// The element stiffness of a linear tet is K_ab = eps V grad(l_a) . grad(l_b) with
// the barycentric gradients grad(l_1) = (e2 x e3) / 6V, grad(l_2) = (e3 x e1) / 6V,
// grad(l_3) = (e1 x e2) / 6V, grad(l_0) = -(sum of the others), e_i = p_i - p_0
// (e.g. Zienkiewicz & Taylor, The Finite Element Method, vol. 1, ch. 6).
#include "core/electrostatics.h"

#include <Eigen/IterativeLinearSolvers>
#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <optional>
#include <string>

#include "core/adjacency.h"

namespace tetlod {
namespace {

using Clock = std::chrono::steady_clock;
using SparseMatrix = Eigen::SparseMatrix<double, Eigen::ColMajor, int>;
using SparseMap = Eigen::Map<const SparseMatrix>;

double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

std::string format_double(double value) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.17g", value);
  return buffer;
}

std::string describe_node(const TetMesh& mesh, uint32_t v) {
  const Vec3& p = mesh.positions[v];
  char buffer[160];
  std::snprintf(buffer, sizeof buffer, "node %u at (%.9g, %.9g, %.9g)", v, p.x, p.y, p.z);
  return buffer;
}

bool cancelled(const std::atomic<bool>* cancel) {
  return cancel && cancel->load(std::memory_order_relaxed);
}

// Sorted unique material ids of the mesh.
std::vector<int32_t> mesh_materials(const TetMesh& mesh) {
  std::vector<int32_t> ids = mesh.materials;
  std::sort(ids.begin(), ids.end());
  ids.erase(std::unique(ids.begin(), ids.end()), ids.end());
  return ids;
}

// Potentials and permittivities within these keep the energy eps |grad u|^2 V finite
// on every mesh validate_mesh() accepts (edges up to 1e60): far beyond physics (MV,
// vacuum's 8.85e-12 F/m), short of overflow. A nonzero potential is at least 1e-30
// in magnitude, so that the energy, of order V^2, stays clear of the subnormal
// numbers (at 1e-160 the capacitance was 0.14 % off, at 1e-170 NaN).
constexpr double kMinPotential = 1e-30, kMaxPotential = 1e30;
constexpr double kMinPermittivity = 1e-30, kMaxPermittivity = 1e30;

}  // namespace

Status check_repeated_materials(const ElectrostaticsProblem& problem) {
  // The first id listed twice in `ids`, if any.
  const auto repeat = [](std::vector<int32_t> ids) -> std::optional<int32_t> {
    std::sort(ids.begin(), ids.end());
    const auto at = std::adjacent_find(ids.begin(), ids.end());
    return at == ids.end() ? std::nullopt : std::optional<int32_t>(*at);
  };
  std::vector<int32_t> electrodes = problem.ground_materials, dielectrics;
  for (const auto& [m, potential] : problem.conductors) electrodes.push_back(m);
  for (const auto& [m, eps] : problem.permittivities) dielectrics.push_back(m);
  if (const auto m = repeat(std::move(electrodes)))
    return Status::error("material " + std::to_string(*m) +
                         " is given more than once as a conductor or ground");
  if (const auto m = repeat(std::move(dielectrics)))
    return Status::error("permittivity of material " + std::to_string(*m) +
                         " is given more than once");
  return Status();
}

namespace {

Status check_problem(const ElectrostaticsProblem& problem, const std::vector<int32_t>& ids) {
  auto exists = [&](int32_t m) { return std::binary_search(ids.begin(), ids.end(), m); };
  // Every material named once across conductors and grounds, once among permittivities.
  const bool conductor_surface =
      std::any_of(problem.surfaces.begin(), problem.surfaces.end(),
                  [](const ElectrostaticsProblem::HeldSurface& h) { return !h.ground; });
  if (problem.conductors.empty() && !conductor_surface) {
    return Status::error(
        "no conductor: at least one material or surface must be held at a potential");
  }
  for (size_t k = 0; k < problem.surfaces.size(); ++k) {
    const ElectrostaticsProblem::HeldSurface& h = problem.surfaces[k];
    for (size_t j = 0; j < k; ++j)
      if (problem.surfaces[j].name == h.name)
        return Status::error("surface '" + h.name +
                             "' is given more than once as a conductor or ground");
    const std::string what = (h.ground ? "ground surface '" : "conductor surface '") + h.name + "'";
    if (h.vertices.empty()) return Status::error(what + " has no vertices");
    if (!(std::fabs(h.potential) <= kMaxPotential) || (h.ground && h.potential != 0) ||
        (h.potential != 0 && std::fabs(h.potential) < kMinPotential)) {
      return Status::error(what + ": potential " + format_double(h.potential) +
                           " is not 0 or a magnitude in [1e-30, 1e30]");
    }
  }
  for (const auto& [m, potential] : problem.conductors) {
    if (!exists(m)) {
      return Status::error("conductor material " + std::to_string(m) +
                           " does not exist in the mesh");
    }
    if (!(std::fabs(potential) <= kMaxPotential)) {
      return Status::error("conductor material " + std::to_string(m) + ": potential " +
                           format_double(potential) + " is not a number in [-1e30, 1e30]");
    }
    if (potential != 0 && std::fabs(potential) < kMinPotential) {
      return Status::error("conductor material " + std::to_string(m) + ": potential " +
                           format_double(potential) +
                           " is too small: give 0, or a magnitude of at least 1e-30 (the "
                           "capacitance does not depend on the scale of the potentials)");
    }
  }
  for (const int32_t m : problem.ground_materials) {
    if (!exists(m)) {
      return Status::error("ground material " + std::to_string(m) + " does not exist in the mesh");
    }
  }
  if (Status s = check_repeated_materials(problem); !s) return s;
  for (const auto& [m, eps] : problem.permittivities) {
    if (!exists(m)) {
      return Status::error("permittivity for material " + std::to_string(m) +
                           ", which does not exist in the mesh");
    }
    if (!std::isfinite(eps) || eps <= 0) {
      return Status::error("permittivity of material " + std::to_string(m) + " is " +
                           format_double(eps) + ", not a finite number > 0");
    }
    if (!(eps >= kMinPermittivity && eps <= kMaxPermittivity)) {
      return Status::error("permittivity of material " + std::to_string(m) + " is " +
                           format_double(eps) + ", not a number in [1e-30, 1e30]");
    }
  }
  if (!(problem.default_permittivity >= kMinPermittivity &&
        problem.default_permittivity <= kMaxPermittivity)) {
    return Status::error("default permittivity " + format_double(problem.default_permittivity) +
                         " is not a number in [1e-30, 1e30]");
  }
  return Status();
}

// The invariants the assembly relies on (a validated mesh has them; a mesh made in
// code may not). Same zero-volume rule as validate_mesh().
Status check_mesh(const TetMesh& mesh) {
  if (mesh.tets.empty()) return Status::error("the mesh has no tets");
  if (mesh.materials.size() != mesh.tets.size()) {
    return Status::error("the mesh has " + std::to_string(mesh.materials.size()) +
                         " materials for " + std::to_string(mesh.tets.size()) + " tets");
  }
  if (mesh.vertex_count() >= kInvalidIndex) return Status::error("too many vertices");
  for (size_t v = 0; v < mesh.vertex_count(); ++v) {
    if (!is_finite(mesh.positions[v])) {
      return Status::error("vertex " + std::to_string(v) + " has a non-finite coordinate");
    }
  }
  for (size_t t = 0; t < mesh.tet_count(); ++t) {
    const Tet& tet = mesh.tets[t];
    for (const uint32_t v : tet) {
      if (v >= mesh.vertex_count()) {
        return Status::error("tet " + std::to_string(t) + " uses vertex " + std::to_string(v) +
                             ", out of range");
      }
    }
    const Vec3& a = mesh.positions[tet[0]];
    double longest = 0;
    for (const auto& e : kTetEdge) {
      longest =
          std::max(longest, squared_length(mesh.positions[tet[e[0]]] - mesh.positions[tet[e[1]]]));
    }
    longest = std::sqrt(longest);
    const double volume6 =
        signed_volume6(a, mesh.positions[tet[1]], mesh.positions[tet[2]], mesh.positions[tet[3]]);
    if (!(volume6 > 1e-12 * longest * longest * longest)) {
      return Status::error("tet " + std::to_string(t) + " (material " +
                           std::to_string(mesh.materials[t]) + ") is " +
                           (volume6 < 0 ? "inverted" : "degenerate") +
                           " (6 x volume = " + format_double(volume6) + ")");
    }
  }
  return Status();
}

// Barycentric gradients of a positively oriented tet and its volume.
struct ElementGeometry {
  Vec3 gradient[4];
  double volume = 0;
};

ElementGeometry element_geometry(const TetMesh& mesh, const Tet& tet) {
  const Vec3& p0 = mesh.positions[tet[0]];
  const Vec3 e1 = mesh.positions[tet[1]] - p0;
  const Vec3 e2 = mesh.positions[tet[2]] - p0;
  const Vec3 e3 = mesh.positions[tet[3]] - p0;
  const double volume6 = dot(e1, cross(e2, e3));
  const double inverse = 1.0 / volume6;
  ElementGeometry g;
  g.gradient[1] = cross(e2, e3) * inverse;
  g.gradient[2] = cross(e3, e1) * inverse;
  g.gradient[3] = cross(e1, e2) * inverse;
  g.gradient[0] = (g.gradient[1] + g.gradient[2] + g.gradient[3]) * -1.0;
  g.volume = volume6 / 6.0;
  return g;
}

// Permittivity per tet, looked up once.
std::vector<double> tet_permittivities(const TetMesh& mesh, const ElectrostaticsProblem& problem) {
  std::vector<std::pair<int32_t, double>> table = problem.permittivities;
  std::sort(table.begin(), table.end());
  std::vector<double> eps(mesh.tet_count(), problem.default_permittivity);
  if (table.empty()) return eps;
  for (size_t t = 0; t < mesh.tet_count(); ++t) {
    const auto it = std::lower_bound(
        table.begin(), table.end(),
        std::make_pair(mesh.materials[t], -std::numeric_limits<double>::infinity()));
    if (it != table.end() && it->first == mesh.materials[t]) eps[t] = it->second;
  }
  return eps;
}

constexpr double kFree = std::numeric_limits<double>::quiet_NaN();

// Sets value[v] = potential for every node of the tets of `material`; an error if a
// node already holds another potential.
Status hold_material(const TetMesh& mesh, int32_t material, double potential, const char* role,
                     std::vector<double>* value, std::vector<int32_t>* holder) {
  for (size_t t = 0; t < mesh.tet_count(); ++t) {
    if (mesh.materials[t] != material) continue;
    for (const uint32_t v : mesh.tets[t]) {
      double& current = (*value)[v];
      if (std::isnan(current)) {
        current = potential;
        (*holder)[v] = material;
      } else if (current != potential) {
        const int32_t other = (*holder)[v];
        const std::string other_name =
            other == kOutsideMaterial
                ? std::string("the grounded outer boundary")
                : "material " + std::to_string(other) + " (held at " + format_double(current) + ")";
        return Status::error(std::string(role) + " material " + std::to_string(material) +
                             " (held at " + format_double(potential) + ") touches " + other_name +
                             " at " + describe_node(mesh, v));
      }
    }
  }
  return Status();
}

// The free block in CSR (both triangles, columns sorted per row): row i is free
// node i, columns are free node ids.
struct FreeSystem {
  std::vector<uint32_t> free_of_vertex;  // kInvalidIndex for a Dirichlet node
  std::vector<uint32_t> vertex_of_free;
  std::vector<int> row_offsets;
  std::vector<int> columns;
  std::vector<double> values;
  std::vector<double> rhs;
};

// Builds the pattern; returns an error naming a free region that reaches no
// Dirichlet node.
Status build_pattern(const TetMesh& mesh, const std::vector<double>& dirichlet, FreeSystem* sys) {
  const size_t vertex_count = mesh.vertex_count();
  sys->free_of_vertex.assign(vertex_count, kInvalidIndex);
  sys->vertex_of_free.clear();
  for (uint32_t v = 0; v < vertex_count; ++v) {
    if (std::isnan(dirichlet[v])) {
      sys->free_of_vertex[v] = static_cast<uint32_t>(sys->vertex_of_free.size());
      sys->vertex_of_free.push_back(v);
    }
  }
  const size_t free_count = sys->vertex_of_free.size();
  const VertexTets vertex_tets = build_vertex_tets(mesh);
  std::vector<uint8_t> touches_dirichlet(free_count, 0);
  // The least and the greatest potential held next to each free node.
  std::vector<double> held_lo(free_count, std::numeric_limits<double>::infinity());
  std::vector<double> held_hi(free_count, -std::numeric_limits<double>::infinity());
  sys->row_offsets.assign(free_count + 1, 0);
  sys->columns.clear();
  sys->columns.reserve(free_count * 16);
  std::vector<int> row;
  for (size_t i = 0; i < free_count; ++i) {
    const uint32_t v = sys->vertex_of_free[i];
    row.clear();
    for (const uint32_t* t = vertex_tets.begin(v); t != vertex_tets.end(v); ++t) {
      for (const uint32_t w : mesh.tets[*t]) {
        const uint32_t f = sys->free_of_vertex[w];
        if (f == kInvalidIndex) {
          touches_dirichlet[i] = 1;
          held_lo[i] = std::min(held_lo[i], dirichlet[w]);
          held_hi[i] = std::max(held_hi[i], dirichlet[w]);
        } else {
          row.push_back(static_cast<int>(f));
        }
      }
    }
    std::sort(row.begin(), row.end());
    row.erase(std::unique(row.begin(), row.end()), row.end());
    sys->columns.insert(sys->columns.end(), row.begin(), row.end());
    if (sys->columns.size() > size_t(std::numeric_limits<int>::max())) {
      return Status::error("the system is too large (more than 2^31 matrix entries)");
    }
    sys->row_offsets[i + 1] = static_cast<int>(sys->columns.size());
  }
  // Every connected free region must reach a Dirichlet node, or the potential there
  // is only determined up to a constant (a singular matrix).
  std::vector<uint8_t> seen(free_count, 0);
  std::vector<int> stack;
  // Whether any free region lies between two potentials (else the field is 0
  // everywhere: no capacitance to measure).
  bool field = false;
  for (size_t start = 0; start < free_count; ++start) {
    if (seen[start]) continue;
    bool anchored = false;
    size_t region_size = 0;
    double lo = std::numeric_limits<double>::infinity(), hi = -lo;
    stack.assign(1, static_cast<int>(start));
    seen[start] = 1;
    while (!stack.empty()) {
      const int i = stack.back();
      stack.pop_back();
      ++region_size;
      anchored = anchored || touches_dirichlet[i];
      lo = std::min(lo, held_lo[i]);
      hi = std::max(hi, held_hi[i]);
      for (int k = sys->row_offsets[i]; k < sys->row_offsets[i + 1]; ++k) {
        const int j = sys->columns[k];
        if (!seen[j]) {
          seen[j] = 1;
          stack.push_back(j);
        }
      }
    }
    if (!anchored) {
      const uint32_t v = sys->vertex_of_free[start];
      const int32_t material = mesh.materials[*vertex_tets.begin(v)];
      return Status::error("a floating region of " + std::to_string(region_size) +
                           " nodes (material " + std::to_string(material) + ", " +
                           describe_node(mesh, v) +
                           ") touches no conductor or ground: its potential is undetermined");
    }
    field = field || hi > lo;
  }
  // (A tet whose corners are all held at two potentials has a field too.)
  for (size_t t = 0; t < mesh.tet_count() && !field; ++t) {
    const Tet& tet = mesh.tets[t];
    bool held = true;
    for (const uint32_t v : tet) held = held && !std::isnan(dirichlet[v]);
    if (held)
      for (const uint32_t v : tet) field = field || dirichlet[v] != dirichlet[tet[0]];
  }
  if (!field)
    return Status::error(
        "no dielectric lies between two potentials (each body holds one: the conductors and "
        "the grounds are separate bodies), so there is no field and no capacitance to measure");
  sys->values.assign(sys->columns.size(), 0.0);
  sys->rhs.assign(free_count, 0.0);
  return Status();
}

void assemble(const TetMesh& mesh, const std::vector<double>& eps,
              const std::vector<double>& dirichlet, FreeSystem* sys) {
  for (size_t t = 0; t < mesh.tet_count(); ++t) {
    const Tet& tet = mesh.tets[t];
    uint32_t free_id[4];
    bool any_free = false;
    for (int a = 0; a < 4; ++a) {
      free_id[a] = sys->free_of_vertex[tet[a]];
      any_free = any_free || free_id[a] != kInvalidIndex;
    }
    if (!any_free) continue;
    const ElementGeometry g = element_geometry(mesh, tet);
    const double scale = eps[t] * g.volume;
    for (int a = 0; a < 4; ++a) {
      if (free_id[a] == kInvalidIndex) continue;
      const int row_begin = sys->row_offsets[free_id[a]];
      const int row_end = sys->row_offsets[free_id[a] + 1];
      for (int b = 0; b < 4; ++b) {
        const double k = scale * dot(g.gradient[a], g.gradient[b]);
        if (free_id[b] == kInvalidIndex) {
          sys->rhs[free_id[a]] -= k * dirichlet[tet[b]];
        } else {
          const int* position =
              std::lower_bound(sys->columns.data() + row_begin, sys->columns.data() + row_end,
                               static_cast<int>(free_id[b]));
          sys->values[position - sys->columns.data()] += k;
        }
      }
    }
  }
}

using Vector = Eigen::VectorXd;

// y = A x for the CSR matrix of `sys`.
void multiply(const FreeSystem& sys, const Vector& x, Vector* y) {
  const size_t n = sys.rhs.size();
  const int* offsets = sys.row_offsets.data();
  const int* columns = sys.columns.data();
  const double* values = sys.values.data();
  for (size_t i = 0; i < n; ++i) {
    double sum = 0;
    for (int k = offsets[i]; k < offsets[i + 1]; ++k) sum += values[k] * x[columns[k]];
    (*y)[i] = sum;
  }
}

SparseMap as_eigen(const FreeSystem& sys) {
  // The matrix is symmetric, so its CSR arrays are also its CSC arrays.
  const int n = static_cast<int>(sys.rhs.size());
  return SparseMap(n, n, static_cast<int>(sys.values.size()), sys.row_offsets.data(),
                   sys.columns.data(), sys.values.data());
}

struct SolveReport {
  int iterations = 0;
  bool cancelled = false;
  double seconds_factor = 0;
};

Status solve_direct(const FreeSystem& sys, Vector* x, SolveReport* report) {
  const auto start = Clock::now();
  Eigen::SimplicialLDLT<SparseMatrix, Eigen::Lower> ldlt;
  ldlt.compute(as_eigen(sys));
  report->seconds_factor = seconds_since(start);
  if (ldlt.info() != Eigen::Success) {
    return Status::error("the direct solver could not factor the matrix (not positive definite)");
  }
  const Eigen::Map<const Vector> b(sys.rhs.data(), Eigen::Index(sys.rhs.size()));
  *x = ldlt.solve(b);
  if (ldlt.info() != Eigen::Success) return Status::error("the direct solver failed");
  return Status();
}

// Preconditioned conjugate gradients (Saad, Iterative Methods for Sparse Linear
// Systems, 2nd ed., Algorithm 9.1), written out so that it can report progress and
// be cancelled every iteration.
template <typename ApplyPreconditioner>
Status run_pcg(const FreeSystem& sys, const ApplyPreconditioner& precondition,
               const SolveOptions& options, Vector* x, SolveReport* report,
               const SolveProgressCallback& progress, const std::atomic<bool>* cancel) {
  const Eigen::Index n = Eigen::Index(sys.rhs.size());
  const Eigen::Map<const Vector> b(sys.rhs.data(), n);
  x->setZero(n);
  const double b_norm = b.norm();
  if (b_norm == 0) return Status();  // x = 0 solves it exactly
  Vector r = b, z(n), p(n), q(n);
  precondition(r, &z);
  p = z;
  double rz = r.dot(z);
  const double target = options.tolerance * b_norm;
  const double log_span = std::log(std::max(options.tolerance, 1e-300));
  double r_norm = b_norm;
  for (int iteration = 1; iteration <= options.max_iterations; ++iteration) {
    if (cancelled(cancel)) {
      report->cancelled = true;
      return Status();
    }
    multiply(sys, p, &q);
    const double pq = p.dot(q);
    if (!(pq > 0)) {
      return Status::error("conjugate gradients broke down (p.Ap = " + format_double(pq) +
                           "): the matrix is not positive definite");
    }
    const double alpha = rz / pq;
    *x += alpha * p;
    r -= alpha * q;
    r_norm = r.norm();
    report->iterations = iteration;
    if (progress && iteration % 16 == 0) {
      SolveProgress sp;
      sp.phase = "solve";
      sp.iteration = iteration;
      sp.relative_residual = r_norm / b_norm;
      sp.fraction = std::clamp(std::log(r_norm / b_norm) / log_span, 0.0, 1.0);
      progress(sp);
    }
    if (r_norm <= target) return Status();
    precondition(r, &z);
    const double rz_next = r.dot(z);
    p = z + (rz_next / rz) * p;
    rz = rz_next;
  }
  return Status::error("conjugate gradients did not converge in " +
                       std::to_string(options.max_iterations) + " iterations (relative residual " +
                       format_double(r_norm / b_norm) + ", asked for " +
                       format_double(options.tolerance) + ")");
}

Status solve_iterative(const FreeSystem& sys, const SolveOptions& options, Vector* x,
                       SolveReport* report, const SolveProgressCallback& progress,
                       const std::atomic<bool>* cancel) {
  const size_t n = sys.rhs.size();
  const auto start = Clock::now();
  if (options.preconditioner == Preconditioner::kJacobi) {
    Vector inverse_diagonal(static_cast<Eigen::Index>(n));
    for (size_t i = 0; i < n; ++i) {
      const int* begin = sys.columns.data() + sys.row_offsets[i];
      const int* end = sys.columns.data() + sys.row_offsets[i + 1];
      const int* d = std::lower_bound(begin, end, static_cast<int>(i));
      inverse_diagonal[Eigen::Index(i)] = 1.0 / sys.values[d - sys.columns.data()];
    }
    report->seconds_factor = seconds_since(start);
    return run_pcg(
        sys, [&](const Vector& r, Vector* z) { *z = inverse_diagonal.cwiseProduct(r); }, options, x,
        report, progress, cancel);
  }
  Eigen::IncompleteCholesky<double, Eigen::Lower, Eigen::NaturalOrdering<int>> ic;
  ic.compute(as_eigen(sys));
  report->seconds_factor = seconds_since(start);
  if (ic.info() != Eigen::Success) {
    return Status::error("the incomplete Cholesky preconditioner failed");
  }
  return run_pcg(
      sys, [&](const Vector& r, Vector* z) { *z = ic.solve(r); }, options, x, report, progress,
      cancel);
}

}  // namespace

Status solve_electrostatics(const TetMesh& mesh, const ElectrostaticsProblem& problem,
                            const SolveOptions& options, ElectrostaticsSolution* solution,
                            const SolveProgressCallback& progress,
                            const std::atomic<bool>* cancel) {
  *solution = ElectrostaticsSolution();
  auto report_phase = [&](const char* phase) {
    if (!progress) return;
    SolveProgress sp;
    sp.phase = phase;
    progress(sp);
  };
  auto stop = [&] {
    if (!cancelled(cancel)) return false;
    solution->cancelled = true;
    return true;
  };
  if (!(options.tolerance >= kMinSolverTolerance) || !(options.tolerance < 1) ||
      options.max_iterations < 1) {
    return Status::error("solver tolerance " + format_double(options.tolerance) + " must be in [" +
                         format_double(kMinSolverTolerance) + ", 1) and max iterations " +
                         std::to_string(options.max_iterations) + " >= 1");
  }
  auto start = Clock::now();
  report_phase("setup");
  if (Status s = check_mesh(mesh); !s) return s;
  if (Status s = check_problem(problem, mesh_materials(mesh)); !s) return s;

  // Dirichlet values: NaN marks a free node. Grounds first, so that a conductor
  // touching a ground is reported from the conductor's side.
  const size_t vertex_count = mesh.vertex_count();
  std::vector<double> dirichlet(vertex_count, kFree);
  std::vector<int32_t> holder(vertex_count, kOutsideMaterial);
  if (problem.ground_boundary) {
    std::vector<uint32_t> neighbors;
    const FaceProblem face_problem = build_face_neighbors(mesh, &neighbors);
    if (face_problem.kind != FaceProblem::Kind::kNone) {
      return Status::error("tets " + std::to_string(face_problem.tet_a) + " and " +
                           std::to_string(face_problem.tet_b) +
                           (face_problem.kind == FaceProblem::Kind::kOverlap
                                ? " overlap across a shared face"
                                : " share a face with a third tet"));
    }
    for (size_t t = 0; t < mesh.tet_count(); ++t) {
      for (int corner = 0; corner < 4; ++corner) {
        if (neighbors[4 * t + corner] != kInvalidIndex) continue;
        for (const int local : kTetFace[corner]) dirichlet[mesh.tets[t][local]] = 0.0;
      }
    }
  }
  for (const int32_t m : problem.ground_materials) {
    if (Status s = hold_material(mesh, m, 0.0, "ground", &dirichlet, &holder); !s) return s;
  }
  for (const auto& [m, potential] : problem.conductors) {
    if (Status s = hold_material(mesh, m, potential, "conductor", &dirichlet, &holder); !s) {
      return s;
    }
  }
  // Surfaces after materials: one held at another potential where it touches a
  // conductor, a ground or another surface is an error naming both.
  std::vector<uint32_t> surface_of(vertex_count, kInvalidIndex);
  for (size_t k = 0; k < problem.surfaces.size(); ++k) {
    const ElectrostaticsProblem::HeldSurface& h = problem.surfaces[k];
    for (const uint32_t v : h.vertices) {
      if (v >= vertex_count) {
        return Status::error("surface '" + h.name + "': vertex " + std::to_string(v) +
                             " is not in the mesh");
      }
      double& current = dirichlet[v];
      if (std::isnan(current)) {
        current = h.potential;
        surface_of[v] = uint32_t(k);
      } else if (current != h.potential) {
        const std::string other = surface_of[v] != kInvalidIndex
                                      ? "surface '" + problem.surfaces[surface_of[v]].name + "'"
                                  : holder[v] == kOutsideMaterial
                                      ? std::string("the grounded outer boundary")
                                      : "material " + std::to_string(holder[v]);
        return Status::error(std::string(h.ground ? "ground" : "conductor") + " surface '" +
                             h.name + "' (held at " + format_double(h.potential) + ") touches " +
                             other + " (held at " + format_double(current) + ") at " +
                             describe_node(mesh, v));
      }
    }
  }
  double lowest = std::numeric_limits<double>::infinity();
  double highest = -lowest;
  for (const double value : dirichlet) {
    if (std::isnan(value)) continue;
    lowest = std::min(lowest, value);
    highest = std::max(highest, value);
    ++solution->dirichlet_count;
  }
  solution->voltage = highest - lowest;
  if (!(solution->voltage > 0)) {
    return Status::error("every conductor and ground is at potential " + format_double(highest) +
                         ": no potential difference, no field");
  }

  FreeSystem sys;
  if (Status s = build_pattern(mesh, dirichlet, &sys); !s) return s;
  solution->free_count = sys.vertex_of_free.size();
  solution->nonzeros = sys.values.size();
  solution->seconds_setup = seconds_since(start);
  if (stop()) return Status();

  start = Clock::now();
  report_phase("assemble");
  const std::vector<double> eps = tet_permittivities(mesh, problem);
  assemble(mesh, eps, dirichlet, &sys);
  solution->seconds_assemble = seconds_since(start);
  if (stop()) return Status();

  start = Clock::now();
  report_phase("factor");
  solution->method = options.method;
  if (solution->method == SolverMethod::kAuto) {
    solution->method = solution->free_count <= options.direct_max_unknowns
                           ? SolverMethod::kDirect
                           : SolverMethod::kIterative;
  }
  Vector x;
  SolveReport report;
  if (solution->free_count > 0) {
    const Status s = solution->method == SolverMethod::kDirect
                         ? solve_direct(sys, &x, &report)
                         : solve_iterative(sys, options, &x, &report, progress, cancel);
    if (!s) return s;
    if (report.cancelled) {
      solution->cancelled = true;
      return Status();
    }
  }
  solution->seconds_factor = report.seconds_factor;
  solution->iterations = report.iterations;

  // The residual of the reduced system, recomputed rather than taken from CG.
  const Eigen::Index n = Eigen::Index(sys.rhs.size());
  if (n > 0) {
    Vector ax(n);
    multiply(sys, x, &ax);
    const Eigen::Map<const Vector> b(sys.rhs.data(), n);
    const double b_norm = b.norm();
    solution->relative_residual = b_norm > 0 ? (b - ax).norm() / b_norm : (ax).norm();
    if (!std::isfinite(solution->relative_residual)) {
      return Status::error("the solver produced a non-finite solution");
    }
    // CG's updated residual can drift from the true one; a solution whose true
    // residual is far above the request is not reported as a result.
    const double accepted = std::max(1e3 * options.tolerance, 1e-8);
    if (solution->method == SolverMethod::kIterative && solution->relative_residual > accepted) {
      return Status::error("conjugate gradients stopped with a true relative residual of " +
                           format_double(solution->relative_residual) + " (asked for " +
                           format_double(options.tolerance) + ")");
    }
  }

  solution->potential = dirichlet;
  for (size_t i = 0; i < sys.vertex_of_free.size(); ++i) {
    solution->potential[sys.vertex_of_free[i]] = x[Eigen::Index(i)];
  }
  solution->field_magnitude.resize(mesh.tet_count());
  double energy = 0;
  for (size_t t = 0; t < mesh.tet_count(); ++t) {
    const Tet& tet = mesh.tets[t];
    const ElementGeometry g = element_geometry(mesh, tet);
    Vec3 gradient;
    for (int a = 0; a < 4; ++a) gradient = gradient + g.gradient[a] * solution->potential[tet[a]];
    const double squared = squared_length(gradient);
    solution->field_magnitude[t] = std::sqrt(squared);
    energy += 0.5 * eps[t] * g.volume * squared;
  }
  solution->energy = energy;
  solution->capacitance = 2 * energy / (solution->voltage * solution->voltage);
  solution->seconds_solve = seconds_since(start) - solution->seconds_factor;
  return Status();
}

double concentric_spheres_capacitance(const std::vector<double>& radii,
                                      const std::vector<double>& eps) {
  constexpr double kPi = 3.14159265358979323846;
  double inverse = 0;
  for (size_t i = 0; i + 1 < radii.size(); ++i) {
    inverse += (1 / radii[i] - 1 / radii[i + 1]) / (4 * kPi * eps[i]);
  }
  return 1 / inverse;
}

Status check_electrostatics_problem(const ElectrostaticsProblem& problem, const TetMesh& mesh) {
  return check_problem(problem, mesh_materials(mesh));
}

}  // namespace tetlod
