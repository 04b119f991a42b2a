// libFuzzer target for the collapse-history reader (tetlod lod HISTORY, the viewer's
// history files). A history the reader accepts must replay without going astray:
// seeks to the end, back to the start and to the middle (with a render delta), and
// the levels extracted there reference only their own vertices and have only
// positive tets (the reader's replay checks promise that much); saved thresholds it
// accepts pass check_params().
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <unistd.h>

#include "core/lod.h"
#include "core/simplify.h"
#include "core/validate.h"

namespace {

void check_level(const tetlod::TetMesh& level) {
  if (level.materials.size() != level.tets.size()) __builtin_trap();
  for (const tetlod::Tet& t : level.tets) {
    for (uint32_t v : t)
      if (v >= level.vertex_count()) __builtin_trap();
    if (!(tetlod::signed_volume6(level, t) > 0)) __builtin_trap();
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  // read_history() reads a file: give it one (per process, reused).
  static const std::string path = "/tmp/tetlod_fuzz_history_" + std::to_string(getpid()) + ".tlh";
  // A file that ends as a history does (an end block) is sealed again with the checksum
  // of its bytes (history_checksum()), so that the mutations reach every check after it.
  std::string bytes(reinterpret_cast<const char*>(data), size);
  if (size >= 16 && bytes.compare(size - 16, 8, "TLENDOF2") == 0) {
    const uint64_t sum = tetlod::history_checksum(std::string_view(bytes).substr(0, size - 8));
    std::memcpy(&bytes[size - 8], &sum, 8);
  }
  std::FILE* f = std::fopen(path.c_str(), "wb");
  if (!f) return 0;
  std::fwrite(bytes.data(), 1, bytes.size(), f);
  std::fclose(f);
  tetlod::TetMesh base;
  tetlod::CollapseHistory history;
  std::optional<tetlod::SimplifyParams> params;
  std::vector<tetlod::MaterialName> names;
  tetlod::SurfacePatches patches;
  if (!tetlod::read_history(path, &base, &history, &params, &names, &patches).ok()) return 0;
  if (params && !tetlod::check_params(*params).ok()) __builtin_trap();  // accepted: valid
  for (size_t i = 0; i < names.size(); ++i) {  // accepted: sorted, not empty, of the mesh
    if (names[i].name.empty() || (i > 0 && names[i].material <= names[i - 1].material) ||
        std::find(base.materials.begin(), base.materials.end(), names[i].material) ==
            base.materials.end())
      __builtin_trap();
  }
  tetlod::Lod lod(base, &history);
  tetlod::LodDelta delta;
  lod.seek(lod.step_count(), &delta);
  check_level(lod.extract());
  lod.seek(0, &delta);
  check_level(lod.extract());
  lod.seek(lod.step_count() / 2, &delta);
  check_level(lod.extract());
  (void)lod.step_for_elements(1);
  // The saved groups over a level (validated as the commands do), with their triangles
  // inside a material as lod writes them: every triangle in one group.
  tetlod::TetMesh level = lod.extract();
  tetlod::ValidationReport report;
  if ((patches.any() || !patches.inside_entries().empty()) &&
      tetlod::validate_mesh(&level, "fuzz", {}, &report).ok()) {
    tetlod::SurfaceGroups groups;
    if (tetlod::group_surface(level, &groups, patches, true).ok()) {
      size_t triangles = 0;
      for (const tetlod::SurfaceGroup& g : groups.groups) triangles += g.triangles.size();
      if (triangles != groups.surface.size()) __builtin_trap();
    }
  }
  return 0;
}
