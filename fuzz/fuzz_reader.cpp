// libFuzzer target for one mesh reader, chosen at build time by TETLOD_FUZZ_FORMAT
// (fuzz/CMakeLists.txt builds one executable per reader). The reader must never
// crash, hang or allocate without bound, and a mesh it accepts must hold the
// invariants of tet_mesh.h; the surface groups and material names it gives must be
// usable (SurfacePatches and group_surface() over them, names sorted). For TetGen the
// input is "node text \0 ele text", or "node text \0 ele text \0 face text".
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "core/io/mesh_io.h"
#include "core/surface.h"

namespace {

constexpr tetlod::MeshFormat kFormat = tetlod::MeshFormat::TETLOD_FUZZ_FORMAT;

void check_invariants(const tetlod::TetMesh& mesh) {
  if (mesh.tets.empty() || mesh.materials.size() != mesh.tets.size()) __builtin_trap();
  for (size_t t = 0; t < mesh.tet_count(); ++t) {
    for (uint32_t v : mesh.tets[t]) {
      if (v >= mesh.vertex_count()) __builtin_trap();
    }
    if (!(tetlod::signed_volume6(mesh, mesh.tets[t]) > 0) || mesh.materials[t] < 0) {
      __builtin_trap();
    }
  }
  for (const tetlod::Vec3& p : mesh.positions) {
    if (!tetlod::is_finite(p)) __builtin_trap();
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string_view input(reinterpret_cast<const char*>(data), size);
  tetlod::TetMesh mesh;
  tetlod::ReadInfo info;
  tetlod::Status status;
  if constexpr (kFormat == tetlod::MeshFormat::kTetGen) {
    const size_t split = std::min(input.find('\0'), input.size());
    const std::string_view rest = input.substr(std::min(split + 1, input.size()));
    const size_t face_split = rest.find('\0');
    if (face_split == std::string_view::npos) {
      status = tetlod::read_tetgen_from_memory(input.substr(0, split), rest, "fuzz.node",
                                               "fuzz.ele", &mesh, &info);
    } else {
      status = tetlod::read_tetgen_from_memory(input.substr(0, split), rest.substr(0, face_split),
                                               rest.substr(face_split + 1), "fuzz.node", "fuzz.ele",
                                               "fuzz.face", &mesh, &info);
    }
  } else {
    status = tetlod::read_mesh_from_memory(input, kFormat, "fuzz", &mesh, &info);
  }
  if (!status.ok()) return 0;
  check_invariants(mesh);
  for (size_t i = 1; i < info.material_names.size(); ++i)
    if (info.material_names[i].material <= info.material_names[i - 1].material) __builtin_trap();
  if (!info.surface_groups.empty()) {
    const tetlod::SurfacePatches patches(mesh, info.surface_groups);
    tetlod::SurfaceGroups groups;
    if (tetlod::group_surface(mesh, &groups, patches).ok()) {
      size_t triangles = 0;
      for (const tetlod::SurfaceGroup& g : groups.groups) triangles += g.triangles.size();
      if (triangles != groups.surface.size()) __builtin_trap();  // each in one group
    }
    // With the triangles inside a material (as convert writes them): on this very mesh,
    // every one the patches counted, each a face between two tets of its material.
    const size_t surface = groups.surface.size();
    if (tetlod::group_surface(mesh, &groups, patches, true).ok()) {
      size_t triangles = 0, inside = 0;
      for (const tetlod::SurfaceGroup& g : groups.groups) triangles += g.triangles.size();
      for (const auto& g : patches.groups()) inside += g.inside;
      if (triangles != groups.surface.size() || groups.surface.size() != surface + inside)
        __builtin_trap();
      for (size_t i = surface; i < groups.surface.size(); ++i) {
        const tetlod::SurfaceTriangle& t = groups.surface[i];
        const tetlod::Tet& tet = mesh.tets[t.tet];
        if (t.inner != t.outer || mesh.materials[t.tet] != t.inner) __builtin_trap();
        for (uint32_t v : t.v)
          if (std::find(tet.begin(), tet.end(), v) == tet.end() || v == tet[t.corner])
            __builtin_trap();
      }
    }
  }
  return 0;
}
