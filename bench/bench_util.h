// Timing helpers shared by the benchmarks.
#pragma once

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "core/io/mesh_io.h"
#include "core/io/sol.h"
#include "core/simplify.h"
#include "core/size_map.h"

namespace tetlod::bench {

using Clock = std::chrono::steady_clock;

inline double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

inline double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

// The simplifier benchmarks' command line, FILE --size S [--tolerance T] [--stretch D]
// [--valence V] [--size-field SPEC] [--material-size M=S,...] [--size-map FILE.sol]
// [--repeat N], and the mesh FILE (--size inf: no uniform size). Returns 0, or the exit code after
// printing the usage (2) or the read error (1) prefixed with `name`.
inline int load_simplify_bench(const char* name, int argc, char** argv, TetMesh* mesh,
                               SimplifyParams* params, int* repeat) {
  if (argc < 4 || std::string(argv[2]) != "--size") {
    std::fprintf(stderr,
                 "usage: %s FILE --size S [--tolerance T] [--stretch D] [--valence V] "
                 "[--size-field SPEC] [--material-size M=S,...] [--size-map FILE.sol] "
                 "[--repeat N]\n",
                 name);
    return 2;
  }
  params->sizing.uniform = std::atof(argv[3]);
  for (int i = 4; i + 1 < argc; i += 2) {
    const std::string flag = argv[i];
    if (flag == "--tolerance") params->tolerance = std::atof(argv[i + 1]);
    if (flag == "--stretch") params->min_stretch = std::atof(argv[i + 1]);
    if (flag == "--valence") params->max_valence = static_cast<uint32_t>(std::atoi(argv[i + 1]));
    if (flag == "--repeat") *repeat = std::max(1, std::atoi(argv[i + 1]));
    Status rules;
    if (flag == "--size-field") rules = parse_size_field(argv[i + 1], &params->sizing);
    if (flag == "--material-size") rules = parse_material_sizes(argv[i + 1], &params->sizing);
    if (!rules) {
      std::fprintf(stderr, "%s: %s\n", name, rules.message().c_str());
      return 2;
    }
  }
  ReadInfo info;
  const Status s = read_mesh(argv[1], mesh, &info);
  if (!s) {
    std::fprintf(stderr, "%s: %s\n", name, s.message().c_str());
    return 1;
  }
  // --size-map FILE.sol: sizes at the vertices of FILE (which must use every vertex).
  for (int i = 4; i + 1 < argc; i += 2) {
    if (std::string(argv[i]) != "--size-map") continue;
    std::vector<double> sizes;
    Status m = read_sol_sizes(argv[i + 1], &sizes);
    if (m) m = SizeMap::build(*mesh, std::move(sizes), &params->sizing.map);
    if (!m) {
      std::fprintf(stderr, "%s: %s: %s\n", name, argv[i + 1], m.message().c_str());
      return 1;
    }
  }
  return 0;
}

}  // namespace tetlod::bench
