// The simplifier's fuzz harness (fuzz/fuzz_simplify.cpp) on its seeds, in every test
// run (and under ASan + UBSan in CI): the small bundled and test meshes behind five
// sets of threshold bytes. It also writes them, as the fuzzer's seeds, to
// tests/out/fuzz_simplify_seeds/ in the build directory. So the harness's
// checks (positive tets, no created violation, regions and interfaces kept, no bodies
// pushed into each other, exact replay, complete seek deltas, and --improve's
// guarantees) run on every change, and
// the harness keeps compiling without clang.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <stdexcept>
#include <string>

namespace {
int checked_runs = 0;
}  // namespace
#define TETLOD_FUZZ_FAIL() throw std::runtime_error("check at line " + std::to_string(__LINE__))
#define TETLOD_FUZZ_CHECKED() ++checked_runs
#include "../../fuzz/fuzz_simplify.cpp"  // NOLINT: the harness itself, not a copy

namespace tetlod {
namespace {

TEST(FuzzSeeds, SimplifyHarnessHoldsOnEverySeed) {
  const char* meshes[] = {"assets/box2.mesh",
                          "tests/data/medit_sections.mesh",
                          "tests/data/topology/checker.mesh",
                          "tests/data/topology/edge_touch.mesh",
                          "tests/data/topology/vertex_touch.mesh",
                          "tests/data/topology/apart.mesh",
                          "tests/data/topology/bead.mesh"};
  // size, stretch, valence, tolerance, flags (1 subdivide, 2 radial, 4 material size,
  // 8 element target), field, target, crease angle: see fuzz_simplify.cpp.
  const unsigned char params[][8] = {{0x40, 0x20, 0x15, 0x02, 0x01, 0x00, 0x00, 0x1e},
                                     {0xff, 0x05, 0x10, 0x00, 0x00, 0x00, 0x00, 0x1e},
                                     {0x10, 0x30, 0x19, 0x03, 0x07, 0x80, 0x00, 0x1e},
                                     {0x80, 0x20, 0x15, 0x01, 0x0e, 0x40, 0x30, 0xa0},
                                     // valence 6, the smallest size: tets stay above
                                     // it, and runs past the valence make red levels
                                     {0x00, 0x1e, 0x02, 0x02, 0x01, 0x28, 0x00, 0x1e}};
  const std::string seeds = std::string(TETLOD_TEST_OUTPUT_DIR) + "/fuzz_simplify_seeds";
  std::filesystem::create_directories(seeds);
  int seed_count = 0;
  for (const char* name : meshes) {
    std::ifstream in(std::string(TETLOD_SOURCE_DIR) + "/" + name, std::ios::binary);
    const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    ASSERT_FALSE(text.empty()) << name;
    for (const auto& p : params) {
      const std::string input = std::string(reinterpret_cast<const char*>(p), 8) + text;
      std::ofstream(seeds + "/seed_" + std::to_string(seed_count++), std::ios::binary) << input;
      EXPECT_NO_THROW(
          LLVMFuzzerTestOneInput(reinterpret_cast<const uint8_t*>(input.data()), input.size()))
          << name << " with thresholds byte " << int(p[0]);
    }
  }
  // Every seed went through the whole pipeline (none was refused by the reader, none
  // too large for the harness, none stopped by a threshold check).
  EXPECT_EQ(checked_runs, 35);
}

}  // namespace
}  // namespace tetlod
