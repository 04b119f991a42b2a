// Collapse-history files (write_history / read_history, core/lod.h): a round trip
// gives the same history, and a damaged or forged file gives an error that says what
// is wrong, never a crash, and never a history whose replay makes a flat or inverted
// tet (what `tetlod lod` would then write).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <optional>
#include <random>
#include <string>
#include <vector>

#include "core/io/mesh_io.h"
#include "core/lod.h"
#include "core/simplify.h"
#include "core/test_meshes.h"

namespace tetlod {
namespace {

std::string out_path(const std::string& name) {
  const std::string dir = std::string(TETLOD_TEST_OUTPUT_DIR) + "/history";
  std::filesystem::create_directories(dir);
  return dir + "/" + name;
}

// A small two-material history with every kind of entry (removed, rewired, moved).
const SimplifyResult& small_run() {
  static const SimplifyResult result = [] {
    const TetMesh mesh = test::make_grid_mesh(
        6, 3, 3, [](int i, int, int) { return i < 3 ? 1 : 2; }, 1.0 / 3);
    SimplifyParams p;
    p.sizing.uniform = 1.5;
    p.min_stretch = 0.05;
    p.max_valence = 40;
    p.tolerance = 1e-9;
    p.subdivide = false;
    SimplifyResult r;
    EXPECT_TRUE(simplify(mesh, p, &r).ok());
    return r;
  }();
  return result;
}

std::string read_bytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

// A history's bytes without its end block (the last 16 bytes): where the optional
// blocks of a longer file written from the same history start.
std::string body(const std::string& bytes) {
  return bytes.substr(0, bytes.size() - 16);
}

void write_bytes(const std::string& path, const std::string& bytes) {
  std::ofstream(path, std::ios::binary) << bytes;
}

// Writes `bytes` to `path` and reads it as a history, asking for everything a history
// can hold: "accepted", or the error.
std::string read_error(const std::string& path, const std::string& bytes) {
  write_bytes(path, bytes);
  TetMesh base;
  CollapseHistory history;
  std::optional<SimplifyParams> params;
  std::vector<MaterialName> names;
  SurfacePatches patches;
  const Status status = read_history(path, &base, &history, &params, &names, &patches);
  return status.ok() ? std::string("accepted") : status.message();
}

// Every level of `history` over `base` has only positive tets: each step's changed
// tets are checked right after it (the others keep their shape).
void expect_positive_levels(const TetMesh& base, const CollapseHistory& history) {
  for (const Tet& t : base.tets) ASSERT_GT(signed_volume6(base, t), 0);
  Lod lod(base, &history);
  LodDelta delta;
  for (size_t s = 1; s <= lod.step_count(); ++s) {
    lod.seek(s, &delta);
    for (uint32_t t : delta.changed) {
      const Tet& q = lod.tets()[t];
      ASSERT_GT(signed_volume6(lod.positions()[q[0]], lod.positions()[q[1]], lod.positions()[q[2]],
                               lod.positions()[q[3]]),
                0)
          << "step " << s;
    }
  }
}

TEST(HistoryFile, RoundTripIsExact) {
  const SimplifyResult& r = small_run();
  ASSERT_GT(r.history.step_count(), 20u);
  ASSERT_FALSE(r.history.moved.empty());
  const std::string path = out_path("round_trip.tlh");
  ASSERT_TRUE(write_history(path, r.base, r.history).ok());
  TetMesh base;
  CollapseHistory history;
  const Status s = read_history(path, &base, &history);
  ASSERT_TRUE(s.ok()) << s.message();
  EXPECT_EQ(base.tets, r.base.tets);
  EXPECT_EQ(base.materials, r.base.materials);
  ASSERT_EQ(base.positions.size(), r.base.positions.size());
  EXPECT_EQ(std::memcmp(base.positions.data(), r.base.positions.data(),
                        base.positions.size() * sizeof(Vec3)),
            0);
  ASSERT_EQ(history.step_count(), r.history.step_count());
  EXPECT_EQ(std::memcmp(history.steps.data(), r.history.steps.data(),
                        history.steps.size() * sizeof(CollapseHistory::Step)),
            0);
  EXPECT_EQ(history.removed_tets, r.history.removed_tets);
  EXPECT_EQ(history.rewired, r.history.rewired);
  EXPECT_EQ(history.moved, r.history.moved);
  Lod lod(base, &history);
  lod.seek(lod.step_count());
  const TetMesh level = lod.extract();
  EXPECT_EQ(level.tets, r.output.tets);
  EXPECT_EQ(level.materials, r.output.materials);
}

// The thresholds saved after the history (for `lod --improve` and the viewer): they
// come back as written, a file without them reads as before, and damaged ones are
// refused with what is wrong.
// A directory or a device given as a history says what it is.
TEST(HistoryFile, ADirectoryOrDeviceIsNamed) {
  TetMesh base;
  CollapseHistory history;
  const std::string dir = std::filesystem::temp_directory_path().string();
  Status s = read_history(dir, &base, &history);
  ASSERT_FALSE(s.ok());
  EXPECT_EQ(s.message(), dir + ": cannot read: it is a directory");
  // So does a mesh reader (without an extension it was "unknown mesh file extension ''").
  s = read_mesh(dir, &base);
  EXPECT_EQ(s.message(), dir + ": cannot read: it is a directory");
  s = read_history("/dev/null", &base, &history);
  ASSERT_FALSE(s.ok());
  EXPECT_EQ(s.message(), "/dev/null: cannot read: it is not a regular file (a history is one)");
}

TEST(HistoryFile, ThresholdsRoundTripAndAreChecked) {
  const SimplifyResult& r = small_run();
  SimplifyParams p;
  p.tolerance = 0.01;
  p.min_stretch = 0.2;
  p.max_valence = 30;
  p.subdivide = false;
  p.crease_angle_degrees = 35;
  p.sizing.uniform = 1.5;
  p.sizing.material_sizes = {{1, 0.7}, {2, 0.9}};
  p.sizing.radial.push_back({{0.5, 0.5, 0.5}, {0, 0, 1}, 0.3, 0.25});
  p.sizing.boxes.push_back({{0, 0, 0}, {1, 1, 1}, 0.4});
  const std::string plain = out_path("no_params.tlh");
  const std::string path = out_path("params.tlh");
  ASSERT_TRUE(write_history(plain, r.base, r.history).ok());
  ASSERT_TRUE(write_history(path, r.base, r.history, &p).ok());

  TetMesh base;
  CollapseHistory history;
  std::optional<SimplifyParams> read;
  Status s = read_history(path, &base, &history, &read);
  ASSERT_TRUE(s.ok()) << s.message();
  ASSERT_TRUE(read.has_value());
  EXPECT_EQ(read->tolerance, p.tolerance);
  EXPECT_EQ(read->min_stretch, p.min_stretch);
  EXPECT_EQ(read->max_valence, p.max_valence);
  EXPECT_EQ(read->subdivide, p.subdivide);
  EXPECT_EQ(read->crease_angle_degrees, p.crease_angle_degrees);
  EXPECT_EQ(read->sizing.uniform, p.sizing.uniform);
  EXPECT_EQ(read->sizing.material_sizes, p.sizing.material_sizes);
  ASSERT_EQ(read->sizing.radial.size(), 1u);
  EXPECT_EQ(std::memcmp(&read->sizing.radial[0], &p.sizing.radial[0], sizeof(p.sizing.radial[0])),
            0);
  ASSERT_EQ(read->sizing.boxes.size(), 1u);
  EXPECT_EQ(std::memcmp(&read->sizing.boxes[0], &p.sizing.boxes[0], sizeof(p.sizing.boxes[0])), 0);
  EXPECT_EQ(history.steps.size(), r.history.steps.size());
  EXPECT_TRUE(read_history(path, &base, &history).ok());  // without asking for them
  s = read_history(plain, &base, &history, &read);
  ASSERT_TRUE(s.ok()) << s.message();
  EXPECT_FALSE(read.has_value());
  // No limit at all is refused as --size would be; +inf is "no uniform size".
  SimplifyParams unlimited = p;
  unlimited.sizing = {};
  ASSERT_TRUE(write_history(out_path("unlimited.tlh"), r.base, r.history, &unlimited).ok());
  s = read_history(out_path("unlimited.tlh"), &base, &history, &read);
  EXPECT_NE(s.message().find("corrupt history: thresholds: no size limit"), std::string::npos)
      << s.message();

  const std::string whole = read_bytes(path);
  const size_t at = body(read_bytes(plain)).size();  // where the thresholds start
  ASSERT_EQ(whole.substr(at, 8), "TLPARAM1");
  const std::string damaged = out_path("damaged_params.tlh");
  auto error_with = [&](const std::string& bytes) { return read_error(damaged, bytes); };
  auto with_double = [&](size_t offset, double value) {
    std::string bytes = whole;
    std::memcpy(&bytes[at + offset], &value, sizeof value);
    return bytes;
  };
  EXPECT_NE(error_with(with_double(16, 1.5)).find("corrupt history: thresholds: stretch 1.5"),
            std::string::npos);
  EXPECT_NE(error_with(with_double(40, std::nan(""))).find("size is not a number"),
            std::string::npos);
  EXPECT_NE(error_with(with_double(8, -1)).find("thresholds: tolerance -1"), std::string::npos);
  EXPECT_NE(error_with(whole + "x").find("bytes after the end block"), std::string::npos);
  EXPECT_NE(error_with(body(whole) + "TLJUNK01")
                .find("after the thresholds, names or surface groups at byte " +
                      std::to_string(body(whole).size())),
            std::string::npos)
      << error_with(body(whole) + "TLJUNK01");
  // The first material size's id (after the 48 fixed bytes and the count): 1 -> 0.
  {
    std::string bytes = whole;
    const int32_t material = 0;
    std::memcpy(&bytes[at + 56], &material, sizeof material);
    EXPECT_NE(error_with(bytes).find(
                  "corrupt history: thresholds: material size 0 names material 0, which the "
                  "mesh does not have"),
              std::string::npos)
        << error_with(bytes);
  }
  // The radial rule's axis (its z at 48 fixed bytes + the material count and two
  // material sizes + the radial count + its centre + x, y) must be zero or a unit
  // vector, as parse_size_field() leaves it.
  EXPECT_NE(error_with(with_double(48 + 8 + 32 + 8 + 24 + 16, 2)).find("radial rule 0"),
            std::string::npos);
  EXPECT_NE(error_with(body(read_bytes(plain)) + "TLPARAM2").find("bytes after the last step"),
            std::string::npos);
  // Where a tag is cut, its byte is given (it was "unknown bytes", without one).
  EXPECT_NE(error_with(whole.substr(0, at + 3))
                .find("the file ends inside a block's 8-byte tag (3 bytes at byte " +
                      std::to_string(at) + ")"),
            std::string::npos)
      << error_with(whole.substr(0, at + 3));
  // Cut anywhere from where the thresholds start: refused, inside them as damage,
  // at their end (or start) for want of the end block.
  for (size_t n = at; n < whole.size(); ++n) {
    const std::string error = error_with(whole.substr(0, n));
    EXPECT_TRUE(error.find("corrupt history") != std::string::npos ||
                error.find("ends before its end block") != std::string::npos)
        << n << ": " << error;
  }
  // A count no file could hold.
  std::string huge = whole;
  const uint64_t count = uint64_t(1) << 60;
  std::memcpy(&huge[at + 48], &count, sizeof count);
  EXPECT_NE(error_with(huge).find("thresholds: a count of 1152921504606846976 (at byte " +
                                  std::to_string(at + 48) + "), more than the file can hold"),
            std::string::npos)
      << error_with(huge);
}

// The material names are saved last, with or without the thresholds: only those of
// materials the base has, in order and not empty; a damaged list is refused, naming it.
TEST(HistoryFile, MaterialNamesRoundTripAndAreChecked) {
  const SimplifyResult& r = small_run();  // materials 1 and 2
  SimplifyParams p;
  p.sizing.uniform = 1.5;
  const std::vector<MaterialName> names = {{0, "absent"}, {1, "iron"}, {1, "again"},
                                           {2, ""},       {5, "gone"}, {2, "late"}};
  const std::string with_params = out_path("names_params.tlh");
  const std::string names_only = out_path("names_only.tlh");
  const std::string plain = out_path("names_none.tlh");
  ASSERT_TRUE(write_history(with_params, r.base, r.history, &p, &names).ok());
  ASSERT_TRUE(write_history(names_only, r.base, r.history, nullptr, &names).ok());
  ASSERT_TRUE(write_history(plain, r.base, r.history).ok());
  TetMesh base;
  CollapseHistory history;
  std::optional<SimplifyParams> read_params;
  std::vector<MaterialName> read_names = {{9, "stale"}};
  Status s = read_history(with_params, &base, &history, &read_params, &read_names);
  ASSERT_TRUE(s.ok()) << s.message();
  EXPECT_TRUE(read_params.has_value());
  // 0 and 5 are absent, "again" repeats 1, "" is empty.
  ASSERT_EQ(read_names.size(), 2u);
  EXPECT_EQ(read_names[0].material, 1);
  EXPECT_EQ(read_names[0].name, "iron");
  EXPECT_EQ(read_names[1].material, 2);
  EXPECT_EQ(read_names[1].name, "late");
  s = read_history(names_only, &base, &history, &read_params, &read_names);
  ASSERT_TRUE(s.ok()) << s.message();
  EXPECT_FALSE(read_params.has_value());
  EXPECT_EQ(read_names.size(), 2u);
  s = read_history(plain, &base, &history, &read_params, &read_names);
  ASSERT_TRUE(s.ok()) << s.message();
  EXPECT_TRUE(read_names.empty());

  // Damage, after the 8-byte magic and the count: material (4), length (4), bytes.
  const std::string whole = read_bytes(names_only);
  const size_t at = body(read_bytes(plain)).size();
  ASSERT_EQ(whole.substr(at, 8), "TLNAMES1");
  const std::string damaged = out_path("damaged_names.tlh");
  auto error_with = [&](const std::string& bytes) { return read_error(damaged, bytes); };
  auto with_u32 = [&](size_t offset, uint32_t value) {
    std::string bytes = whole;
    std::memcpy(&bytes[at + offset], &value, sizeof value);
    return bytes;
  };
  // "iron" is 4 bytes: the second name's material is at 28.
  EXPECT_NE(error_with(with_u32(28, 7)).find("a name for material 7, which the mesh does not have"),
            std::string::npos);
  EXPECT_NE(error_with(with_u32(20, 0)).find("corrupt history: material name 0"),
            std::string::npos);
  EXPECT_NE(error_with(with_u32(20, 5000)).find("corrupt history: material name 0"),
            std::string::npos);
  EXPECT_NE(error_with(body(whole) + "TLNAMES1").find("a block out of order"), std::string::npos);
  // Thresholds after the names are out of order.
  const std::string params_block =
      body(read_bytes(with_params))
          .substr(at, body(read_bytes(with_params)).size() - body(whole).size());
  ASSERT_EQ(params_block.substr(0, 8), "TLPARAM1");
  EXPECT_NE(error_with(body(whole) + params_block).find("a block out of order"), std::string::npos);
  // The end block must hold the checksum of the bytes before it; a change of any one
  // of them is found.
  {
    std::string bytes = whole;
    bytes[bytes.size() - 8] ^= 1;
    EXPECT_NE(error_with(bytes).find("its checksum does not match"), std::string::npos)
        << error_with(bytes);
    for (size_t where : {size_t{8}, whole.size() / 2, whole.size() - 17}) {
      bytes = whole;
      bytes[where] ^= 0x40;
      EXPECT_NE(error_with(bytes), "accepted") << where;
    }
  }
  // A history of the second format (its end block gives its length) still reads.
  {
    std::string old = body(whole) + "TLENDOF1";
    old[7] = '2';
    const uint64_t length = old.size() + 8;
    old.append(reinterpret_cast<const char*>(&length), 8);
    EXPECT_EQ(error_with(old), "accepted");
    old[old.size() - 8] ^= 1;
    EXPECT_NE(error_with(old).find("the end block does not match the file's length"),
              std::string::npos);
    old = whole;
    old[7] = '4';
    EXPECT_NE(error_with(old).find("a history of a newer TetLOD (format 4)"), std::string::npos);
  }
  // Two names of one material: out of order.
  {
    const std::vector<MaterialName> two = {{1, "a"}, {2, "b"}};
    ASSERT_TRUE(write_history(damaged, r.base, r.history, nullptr, &two).ok());
    std::string bytes = read_bytes(damaged);
    const int32_t one = 1;
    std::memcpy(&bytes[at + 16 + 4 + 4 + 1], &one, sizeof one);  // the second name's material
    EXPECT_NE(error_with(bytes).find("material names out of order"), std::string::npos)
        << error_with(bytes);
  }
  for (size_t n = at; n < whole.size(); ++n)
    EXPECT_NE(error_with(whole.substr(0, n)), "accepted") << n;
  std::string huge = whole;
  const uint64_t count = uint64_t(1) << 60;
  std::memcpy(&huge[at + 8], &count, sizeof count);
  EXPECT_NE(error_with(huge).find("material names: a count of 1152921504606846976 (at byte " +
                                  std::to_string(at + 8) + "), more than the file can hold"),
            std::string::npos)
      << error_with(huge);
}

// The input's surface groups are saved last: read back, they group a level as before;
// damaged, out of range or out of order, the file is refused.
TEST(HistoryFile, SurfaceGroupsRoundTripAndAreChecked) {
  const SimplifyResult& r = small_run();
  // A group of the first few boundary triangles of the base.
  SurfaceGroups plain;
  ASSERT_TRUE(group_surface(r.base, &plain).ok());
  InputSurfaceGroup port;
  port.tag = 40;
  port.name = "port";
  for (size_t i = 0; i < 6; ++i) {
    const auto& v = plain.surface[plain.groups[0].triangles[i]].v;
    port.triangles.push_back(
        {r.base.positions[v[0]], r.base.positions[v[1]], r.base.positions[v[2]]});
  }
  const SurfacePatches patches(r.base, {port});
  ASSERT_TRUE(patches.any());
  const std::vector<MaterialName> names = {{1, "iron"}};
  const std::string path = out_path("groups.tlh");
  const std::string plain_path = out_path("groups_none.tlh");
  ASSERT_TRUE(write_history(path, r.base, r.history, nullptr, &names, &patches).ok());
  ASSERT_TRUE(write_history(plain_path, r.base, r.history, nullptr, &names).ok());
  TetMesh base;
  CollapseHistory history;
  std::vector<MaterialName> read_names;
  SurfacePatches read;
  Status s = read_history(path, &base, &history, nullptr, &read_names, &read);
  ASSERT_TRUE(s.ok()) << s.message();
  EXPECT_EQ(read_names.size(), 1u);
  ASSERT_EQ(read.groups().size(), 1u);
  EXPECT_EQ(read.groups()[0].tag, 40);
  EXPECT_EQ(read.groups()[0].name, "port");
  EXPECT_EQ(read.groups()[0].triangles, 6u);
  ASSERT_EQ(read.entries().size(), patches.entries().size());
  for (size_t i = 0; i < read.entries().size(); ++i) {
    const SurfacePatches::Entry &x = read.entries()[i], &y = patches.entries()[i];
    EXPECT_EQ(std::memcmp(x.p.data(), y.p.data(), sizeof x.p), 0) << i;
    EXPECT_EQ(x.inner, y.inner);
    EXPECT_EQ(x.outer, y.outer);
    EXPECT_EQ(x.group, y.group);
  }
  SurfaceGroups a, b;
  ASSERT_TRUE(group_surface(r.output, &a, patches).ok());
  ASSERT_TRUE(group_surface(r.output, &b, read).ok());
  ASSERT_EQ(a.groups.size(), b.groups.size());
  for (size_t g = 0; g < a.groups.size(); ++g) {
    EXPECT_EQ(a.groups[g].tag, b.groups[g].tag);
    EXPECT_EQ(a.groups[g].triangles, b.groups[g].triangles);
  }
  s = read_history(plain_path, &base, &history, nullptr, nullptr, &read);
  ASSERT_TRUE(s.ok()) << s.message();
  EXPECT_FALSE(read.any());

  const std::string whole = read_bytes(path);
  const size_t at = body(read_bytes(plain_path)).size();
  ASSERT_EQ(whole.substr(at, 8), "TLGROUP1");
  const std::string damaged = out_path("damaged_groups.tlh");
  auto error_with = [&](const std::string& bytes) { return read_error(damaged, bytes); };
  // After the magic, the count and the group (4 + 4 + 4 "port" + 8 + 8): the entry
  // count, then the first entry's corners (72 bytes), inner, outer and group.
  const size_t first_entry = at + 8 + 8 + 28 + 8;
  auto with = [&](size_t offset, const void* value, size_t n) {
    std::string bytes = whole;
    std::memcpy(&bytes[offset], value, n);
    return bytes;
  };
  const uint32_t bad_group = 5;
  EXPECT_NE(error_with(with(first_entry + 80, &bad_group, 4)).find("surface group triangle 0"),
            std::string::npos);
  const double inf = INFINITY;
  EXPECT_NE(error_with(with(first_entry, &inf, 8)).find("surface group triangle 0"),
            std::string::npos);
  const int32_t outer = -7;
  EXPECT_NE(error_with(with(first_entry + 76, &outer, 4)).find("surface group triangle 0"),
            std::string::npos);
  EXPECT_NE(error_with(body(whole) + "TLNAMES1").find("a block out of order"), std::string::npos);
  const int32_t tag0 = 0;  // the group's tag, after the magic and the count
  EXPECT_NE(error_with(with(at + 16, &tag0, 4))
                .find("corrupt history: surface group 0: tag 0 (at byte " +
                      std::to_string(at + 16) + "), not a tag >= 1"),
            std::string::npos)
      << error_with(with(at + 16, &tag0, 4));
  for (size_t n = at; n < whole.size(); n += n + 17 < whole.size() ? 29 : 1)
    EXPECT_NE(error_with(whole.substr(0, n)), "accepted") << n;
  // A cut inside a triangle's corners says where the file ends.
  const std::string cut = error_with(whole.substr(0, first_entry + 44));
  EXPECT_NE(cut.find("truncated surface groups (the file ends at byte " +
                     std::to_string(first_entry + 44) + ")"),
            std::string::npos)
      << cut;
  EXPECT_EQ(error_with(whole), "accepted");
}

// A forged history: one field changed, each caught by the check that names it.
TEST(HistoryFile, ForgedStepsAreNamed) {
  const SimplifyResult& r = small_run();
  const size_t middle = r.history.step_count() / 2;
  const CollapseHistory::Step step = r.history.steps[middle];
  ASSERT_LT(step.moved_begin, r.history.moved_end(middle));
  ASSERT_LT(step.rewired_begin, r.history.rewired_end(middle));
  struct Forgery {
    const char* expected;
    void (*forge)(TetMesh* base, CollapseHistory* h, size_t s);
  };
  const Forgery forgeries[] = {
      {"negative material", [](TetMesh* b, CollapseHistory*, size_t) { b->materials[3] = -1; }},
      {"flat or inverted",
       [](TetMesh* b, CollapseHistory*, size_t) { std::swap(b->tets[5][0], b->tets[5][1]); }},
      {"not where the step starts",
       [](TetMesh*, CollapseHistory* h, size_t s) { h->steps[s].old_position.x += 1e-9; }},
      {"flat or inverted",
       [](TetMesh* b, CollapseHistory* h, size_t s) {
         // Move the kept vertex through its star: far beyond the opposite side.
         const Vec3 k = h->steps[s].new_position;
         const Vec3 far_away = b->positions[h->steps[s].removed];
         h->steps[s].new_position = k + (far_away - k) * 50.0;
       }},
      {"vertex out of range",
       [](TetMesh*, CollapseHistory* h, size_t s) { h->steps[s].removed = h->steps[s].kept; }},
      {"moved tet mismatch",
       [](TetMesh*, CollapseHistory* h, size_t s) {
         h->moved[h->steps[s].moved_begin] = h->removed_tets[h->steps[s].removed_begin];
       }},
      {"listed twice",
       [](TetMesh*, CollapseHistory* h, size_t s) {
         // One moved tet twice and another not at all: the count alone would pass.
         ASSERT_GE(h->moved_end(s) - h->steps[s].moved_begin, 2u);
         h->moved[h->steps[s].moved_begin + 1] = h->moved[h->steps[s].moved_begin];
       }},
      {"rewired corner mismatch",
       [](TetMesh*, CollapseHistory* h, size_t s) { h->rewired[h->steps[s].rewired_begin] ^= 1; }},
      {"not around the edge",
       [](TetMesh*, CollapseHistory* h, size_t s) {
         h->removed_tets[h->steps[s].removed_begin] = h->moved[h->steps[s].moved_begin];
       }},
  };
  for (const Forgery& f : forgeries) {
    TetMesh base = r.base;
    CollapseHistory history = r.history;
    f.forge(&base, &history, middle);
    const std::string path = out_path("forged.tlh");
    ASSERT_TRUE(write_history(path, base, history).ok());
    TetMesh read_base;
    CollapseHistory read;
    const Status status = read_history(path, &read_base, &read);
    EXPECT_FALSE(status.ok()) << f.expected;
    EXPECT_NE(status.message().find(f.expected), std::string::npos)
        << f.expected << ": " << status.message();
    EXPECT_NE(status.message().find("forged.tlh"), std::string::npos) << status.message();
  }
}

// Every cut of the file is an error (the file ends inside an array, or an array is
// missing); random byte damage is an error or a history whose levels are all valid.
TEST(HistoryFile, TruncatedAndDamagedFilesNeverReplayBadly) {
  const SimplifyResult& r = small_run();
  const std::string path = out_path("whole.tlh");
  ASSERT_TRUE(write_history(path, r.base, r.history).ok());
  const std::string whole = read_bytes(path);
  const std::string cut_path = out_path("cut.tlh");
  for (size_t n = 0; n < whole.size(); n += n < 64 || n + 64 > whole.size() ? 1 : 37) {
    write_bytes(cut_path, whole.substr(0, n));
    TetMesh base;
    CollapseHistory history;
    const Status s = read_history(cut_path, &base, &history);
    EXPECT_FALSE(s.ok()) << "cut at " << n;
    // Past the magic, the error says the file was cut (it lacks its end block).
    if (n >= 8) {
      EXPECT_NE(s.message().find("end block"), std::string::npos) << s.message();
    }
  }
  // A changed byte that a check before the checksum finds: the error says what, and
  // that the checksum does not match. The first tet's first vertex, past the base's.
  {
    std::string bytes = whole;
    const size_t first_tet = 8 + 8 + r.base.positions.size() * sizeof(Vec3) + 8;
    bytes[first_tet + 3] ^= 0x40;
    const std::string error = read_error(cut_path, bytes);
    EXPECT_NE(error.find("corrupt history: tet 0: vertex out of range ("), std::string::npos)
        << error;
    EXPECT_NE(error.find("; and its checksum does not match"), std::string::npos) << error;
    // A file cut inside an array says which, and where it starts.
    const std::string cut = read_error(cut_path, whole.substr(0, first_tet + 20));
    EXPECT_NE(cut.find("its tets (from byte " + std::to_string(first_tet - 8) + ") do not fit in"),
              std::string::npos)
        << cut;
  }
  // With every optional block, each cut between or inside them is refused too, even
  // by a caller that asks for none of them.
  {
    SimplifyParams p;
    p.sizing.uniform = 1.5;
    const std::vector<MaterialName> names = {{1, "iron"}, {2, "air"}};
    SurfaceGroups plain;
    ASSERT_TRUE(group_surface(r.base, &plain).ok());
    InputSurfaceGroup port;
    port.tag = 40;
    const auto& v = plain.surface[plain.groups[0].triangles[0]].v;
    port.triangles.push_back(
        {r.base.positions[v[0]], r.base.positions[v[1]], r.base.positions[v[2]]});
    const SurfacePatches patches(r.base, {port});
    const std::string full_path = out_path("full.tlh");
    ASSERT_TRUE(write_history(full_path, r.base, r.history, &p, &names, &patches).ok());
    const std::string full = read_bytes(full_path);
    ASSERT_EQ(read_error(cut_path, full), "accepted");
    const size_t blocks = whole.size() - 16;
    ASSERT_EQ(full.substr(blocks, 8), "TLPARAM1");
    for (size_t n = blocks; n < full.size(); ++n) {
      write_bytes(cut_path, full.substr(0, n));
      TetMesh base;
      CollapseHistory history;
      EXPECT_FALSE(read_history(cut_path, &base, &history).ok()) << "cut at " << n;
    }
    // A history written before the end block existed ("TETLODH1", none) still reads.
    std::string old = body(full);
    old[7] = '1';
    EXPECT_EQ(read_error(cut_path, old), "accepted");
    EXPECT_NE(
        read_error(cut_path, old + full.substr(full.size() - 16)).find("a block out of order"),
        std::string::npos);
    EXPECT_NE(read_error(cut_path, body(full)).find("ends before its end block"),
              std::string::npos);
  }
  // Random flips: the checksum refuses every damaged file; sealed again (as a forger
  // would), the replay's checks still keep every level positive.
  std::mt19937 random(7);
  size_t accepted = 0, accepted_sealed = 0;
  for (int trial = 0; trial < 300; ++trial) {
    std::string damaged = whole;
    const int flips = 1 + static_cast<int>(random() % 4);
    for (int k = 0; k < flips; ++k) damaged[random() % damaged.size()] ^= 1 << (random() % 8);
    if (damaged == whole) continue;
    TetMesh base;
    CollapseHistory history;
    write_bytes(cut_path, damaged);
    accepted += read_history(cut_path, &base, &history).ok();
    const uint64_t sum = history_checksum(std::string_view(damaged).substr(0, damaged.size() - 8));
    std::memcpy(&damaged[damaged.size() - 8], &sum, 8);
    write_bytes(cut_path, damaged);
    if (!read_history(cut_path, &base, &history).ok()) continue;
    ++accepted_sealed;
    expect_positive_levels(base, history);
    if (testing::Test::HasFatalFailure()) return;
  }
  EXPECT_EQ(accepted, 0u);
  // Flips in low mantissa bits of positions pass every other check.
  EXPECT_GT(accepted_sealed, 0u);
}

}  // namespace
}  // namespace tetlod
