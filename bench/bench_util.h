// Timing helpers shared by the benchmarks.
#pragma once

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <string>
#include <vector>

#include "core/simplify.h"

namespace tetlod::bench {

using Clock = std::chrono::steady_clock;

inline double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

inline double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

// The simplifier benchmarks' command line: FILE --size S [--tolerance T] [--stretch D]
// [--valence V] [--repeat N]. False if it does not start with FILE --size S.
inline bool parse_simplify_flags(int argc, char** argv, SimplifyParams* params, int* repeat) {
  if (argc < 4 || std::string(argv[2]) != "--size") return false;
  params->sizing.uniform = std::atof(argv[3]);
  for (int i = 4; i + 1 < argc; i += 2) {
    const std::string flag = argv[i];
    if (flag == "--tolerance") params->tolerance = std::atof(argv[i + 1]);
    if (flag == "--stretch") params->min_stretch = std::atof(argv[i + 1]);
    if (flag == "--valence") params->max_valence = static_cast<uint32_t>(std::atoi(argv[i + 1]));
    if (flag == "--repeat") *repeat = std::max(1, std::atoi(argv[i + 1]));
  }
  return true;
}

}  // namespace tetlod::bench
