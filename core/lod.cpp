#include "core/lod.h"

#include <sys/stat.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <memory>
#include <set>
#include <string>
#include <utility>

#include "core/simplify.h"

namespace tetlod {

uint32_t CollapseHistory::removed_end(size_t s) const {
  return s + 1 < steps.size() ? steps[s + 1].removed_begin
                              : static_cast<uint32_t>(removed_tets.size());
}
uint32_t CollapseHistory::rewired_end(size_t s) const {
  return s + 1 < steps.size() ? steps[s + 1].rewired_begin : static_cast<uint32_t>(rewired.size());
}
uint32_t CollapseHistory::moved_end(size_t s) const {
  return s + 1 < steps.size() ? steps[s + 1].moved_begin : static_cast<uint32_t>(moved.size());
}

void CollapseHistory::begin_step(uint32_t kept, uint32_t removed, const Vec3& old_position,
                                 const Vec3& new_position) {
  Step s;
  s.kept = kept;
  s.removed = removed;
  s.old_position = old_position;
  s.new_position = new_position;
  s.removed_begin = static_cast<uint32_t>(removed_tets.size());
  s.rewired_begin = static_cast<uint32_t>(rewired.size());
  s.moved_begin = static_cast<uint32_t>(moved.size());
  steps.push_back(s);
}

Lod::Lod(TetMesh base, const CollapseHistory* history) : mesh_(std::move(base)), history_(history) {
  alive_.assign(mesh_.tet_count(), 1);
  alive_tet_count_ = mesh_.tet_count();
  tets_at_step_.resize(history_->step_count() + 1);
  tets_at_step_[0] = alive_tet_count_;
  for (size_t s = 0; s < history_->step_count(); ++s) {
    tets_at_step_[s + 1] =
        tets_at_step_[s] - (history_->removed_end(s) - history_->steps[s].removed_begin);
  }
}

size_t Lod::step_for_elements(size_t elements) const {
  // tets_at_step_ is non-increasing.
  size_t best = 0;
  size_t best_distance = static_cast<size_t>(-1);
  size_t lo = 0, hi = tets_at_step_.size();
  while (lo < hi) {  // first step with count <= elements
    const size_t mid = (lo + hi) / 2;
    if (tets_at_step_[mid] <= elements) {
      hi = mid;
    } else {
      lo = mid + 1;
    }
  }
  for (size_t s : {lo == 0 ? size_t{0} : lo - 1, lo}) {
    if (s >= tets_at_step_.size()) continue;
    const size_t c = tets_at_step_[s];
    const size_t distance = c > elements ? c - elements : elements - c;
    if (distance < best_distance) {
      best_distance = distance;
      best = s;
    }
  }
  return best;
}

void Lod::apply(size_t s) {
  const CollapseHistory& h = *history_;
  const CollapseHistory::Step& step = h.steps[s];
  mesh_.positions[step.kept] = step.new_position;
  for (uint32_t k = step.removed_begin; k < h.removed_end(s); ++k) alive_[h.removed_tets[k]] = 0;
  for (uint32_t k = step.rewired_begin; k < h.rewired_end(s); ++k) {
    const uint32_t code = h.rewired[k];
    mesh_.tets[code >> 2][code & 3] = step.kept;
  }
  alive_tet_count_ -= h.removed_end(s) - step.removed_begin;
}

void Lod::undo(size_t s) {
  const CollapseHistory& h = *history_;
  const CollapseHistory::Step& step = h.steps[s];
  mesh_.positions[step.kept] = step.old_position;
  for (uint32_t k = step.removed_begin; k < h.removed_end(s); ++k) alive_[h.removed_tets[k]] = 1;
  for (uint32_t k = step.rewired_begin; k < h.rewired_end(s); ++k) {
    const uint32_t code = h.rewired[k];
    mesh_.tets[code >> 2][code & 3] = step.removed;
  }
  alive_tet_count_ += h.removed_end(s) - step.removed_begin;
}

void Lod::seek(size_t target, LodDelta* delta) {
  target = std::min(target, step_count());
  if (!delta) {
    while (step_ < target) apply(step_++);
    while (step_ > target) undo(--step_);
    return;
  }
  // Record every tet touched on the way, once, with its aliveness before the move.
  if (touched_stamp_.size() != mesh_.tet_count()) {
    touched_stamp_.assign(mesh_.tet_count(), 0);
    alive_before_.assign(mesh_.tet_count(), 0);
    stamp_ = 0;
  }
  if (++stamp_ == 0) {
    std::fill(touched_stamp_.begin(), touched_stamp_.end(), 0);
    stamp_ = 1;
  }
  touched_.clear();
  const CollapseHistory& h = *history_;
  auto touch = [&](uint32_t t) {
    if (touched_stamp_[t] != stamp_) {
      touched_stamp_[t] = stamp_;
      alive_before_[t] = alive_[t];
      touched_.push_back(t);
    }
  };
  auto touch_step = [&](size_t s) {
    for (uint32_t k = h.steps[s].removed_begin; k < h.removed_end(s); ++k) touch(h.removed_tets[k]);
    for (uint32_t k = h.steps[s].rewired_begin; k < h.rewired_end(s); ++k) touch(h.rewired[k] >> 2);
    for (uint32_t k = h.steps[s].moved_begin; k < h.moved_end(s); ++k) touch(h.moved[k]);
  };
  while (step_ < target) {
    touch_step(step_);
    apply(step_++);
  }
  while (step_ > target) {
    touch_step(--step_);
    undo(step_);
  }
  std::sort(touched_.begin(), touched_.end());
  delta->appeared.clear();
  delta->vanished.clear();
  delta->changed.clear();
  for (const uint32_t t : touched_) {
    const bool before = alive_before_[t] != 0;
    const bool now = alive_[t] != 0;
    if (before && now) {
      delta->changed.push_back(t);
    } else if (now) {
      delta->appeared.push_back(t);
    } else if (before) {
      delta->vanished.push_back(t);
    }
  }
}

TetMesh extract_alive(const std::vector<Vec3>& positions, const std::vector<Tet>& tets,
                      const std::vector<int32_t>& materials, const std::vector<uint8_t>& alive) {
  TetMesh out;
  std::vector<uint32_t> remap(positions.size(), kInvalidIndex);
  size_t alive_count = 0;
  for (size_t t = 0; t < tets.size(); ++t) {
    if (!alive[t]) continue;
    ++alive_count;
    for (uint32_t v : tets[t]) remap[v] = 0;
  }
  uint32_t next = 0;
  for (size_t v = 0; v < remap.size(); ++v) {
    if (remap[v] == 0) {
      remap[v] = next++;
      out.positions.push_back(positions[v]);
    }
  }
  out.tets.reserve(alive_count);
  out.materials.reserve(alive_count);
  for (size_t t = 0; t < tets.size(); ++t) {
    if (!alive[t]) continue;
    const Tet& tet = tets[t];
    out.tets.push_back({remap[tet[0]], remap[tet[1]], remap[tet[2]], remap[tet[3]]});
    out.materials.push_back(materials[t]);
  }
  return out;
}

TetMesh Lod::extract() const {
  return extract_alive(mesh_.positions, mesh_.tets, mesh_.materials, alive_);
}

// ---------------------------------------------------------------------------------
// History files: "TETLODH3", then counts and raw little-endian arrays; then,
// optionally, "TLPARAM1" and the thresholds (write_params()); then, optionally,
// "TLNAMES1" and the material names (write_names()); then, optionally, "TLGROUP1" and
// the input's surface groups (write_patches()); then "TLENDOF2" and the checksum
// (history_checksum()) of every byte before it, so that a file cut anywhere, even
// between two blocks, or changed anywhere, is an error. "TETLODH2" files (before
// 2026-11-29) end with "TLENDOF1" and the file's length in bytes (u64) instead;
// "TETLODH1" files (before 2026-11-24) have no end block.

namespace {

constexpr char kHistoryMagic[8] = {'T', 'E', 'T', 'L', 'O', 'D', 'H', '3'};
constexpr char kHistoryMagicV2[8] = {'T', 'E', 'T', 'L', 'O', 'D', 'H', '2'};
constexpr char kHistoryMagicV1[8] = {'T', 'E', 'T', 'L', 'O', 'D', 'H', '1'};
constexpr char kEndMagic[8] = {'T', 'L', 'E', 'N', 'D', 'O', 'F', '2'};
constexpr char kEndMagicV1[8] = {'T', 'L', 'E', 'N', 'D', 'O', 'F', '1'};

// history_checksum() of a stream given in pieces of any size.
class Checksum {
 public:
  void add(const unsigned char* data, size_t n) {
    length_ += n;
    size_t i = 0;
    for (; i < n && fill_ > 0; ++i) take(data[i]);
    for (; i + 8 <= n; i += 8) {
      uint64_t word;
      std::memcpy(&word, data + i, 8);
      mix(word);
    }
    for (; i < n; ++i) take(data[i]);
  }
  uint64_t finish() {
    mix(word_ ^ (uint64_t{fill_} << 56) ^ length_);
    uint64_t h = hash_;
    h ^= h >> 33;
    h *= 0xc4ceb9fe1a85ec53ull;
    h ^= h >> 33;
    return h;
  }

 private:
  // Each word changes the state one to one (an odd multiplier, then a shift-xor), so
  // a file that differs from another in one word always has another checksum.
  void mix(uint64_t word) {
    hash_ = (hash_ ^ word) * 0x9e3779b97f4a7c15ull;
    hash_ ^= hash_ >> 29;
  }
  void take(unsigned char byte) {
    word_ |= uint64_t{byte} << (8 * fill_);
    if (++fill_ == 8) {
      mix(word_);
      word_ = 0;
      fill_ = 0;
    }
  }
  uint64_t hash_ = 0x243f6a8885a308d3ull, word_ = 0, length_ = 0;
  unsigned fill_ = 0;
};

// The checksum of the first `length` bytes of `f` (read from its start).
bool checksum_of_file(std::FILE* f, uint64_t length, uint64_t* sum) {
  if (std::fseek(f, 0, SEEK_SET) != 0) return false;
  Checksum checksum;
  std::vector<unsigned char> buffer(1 << 20);
  while (length > 0) {
    const size_t n = static_cast<size_t>(std::min<uint64_t>(length, buffer.size()));
    if (std::fread(buffer.data(), 1, n, f) != n) return false;
    checksum.add(buffer.data(), n);
    length -= n;
  }
  *sum = checksum.finish();
  return true;
}

// The end block: its magic, then the checksum of every byte before it, magic
// included (read back from the file, which is open for update).
bool write_end(std::FILE* f) {
  if (std::fwrite(kEndMagic, 1, 8, f) != 8 || std::fflush(f) != 0) return false;
  const long at = std::ftell(f);
  uint64_t sum = 0;
  return at >= 0 && checksum_of_file(f, static_cast<uint64_t>(at), &sum) &&
         std::fseek(f, 0, SEEK_END) == 0 && std::fwrite(&sum, sizeof sum, 1, f) == 1;
}

struct FileCloser {
  void operator()(std::FILE* f) const {
    if (f) std::fclose(f);
  }
};

template <class T>
bool write_array(std::FILE* f, const std::vector<T>& v) {
  const uint64_t n = v.size();
  return std::fwrite(&n, sizeof n, 1, f) == 1 &&
         (n == 0 || std::fwrite(v.data(), sizeof(T), v.size(), f) == v.size());
}

template <class T>
bool read_array(std::FILE* f, uint64_t remaining_bytes, std::vector<T>* v) {
  uint64_t n = 0;
  if (std::fread(&n, sizeof n, 1, f) != 1) return false;
  if (n > remaining_bytes / sizeof(T)) return false;  // cannot be in the file
  v->resize(n);
  return n == 0 || std::fread(v->data(), sizeof(T), n, f) == n;
}

constexpr char kParamsMagic[8] = {'T', 'L', 'P', 'A', 'R', 'A', 'M', '1'};

// The thresholds as fixed-width little-endian fields: tolerance, stretch (f64),
// valence, subdivide (u32), crease angle, uniform size (f64, +inf: none), then
// counted lists: material sizes (i32 material, i32 0, f64 size), radial rules (8 f64:
// centre, axis, size0, growth), boxes (7 f64: low, high, size).
struct ParamsWriter {
  std::FILE* f;
  bool ok = true;
  template <class T>
  void put(T value) {
    ok = ok && std::fwrite(&value, sizeof value, 1, f) == 1;
  }
  void put(const Vec3& p) {
    put(p.x);
    put(p.y);
    put(p.z);
  }
};

bool write_params(std::FILE* f, const SimplifyParams& p) {
  if (std::fwrite(kParamsMagic, 1, 8, f) != 8) return false;
  ParamsWriter w{f};
  w.put(p.tolerance);
  w.put(p.min_stretch);
  w.put(uint32_t(p.max_valence));
  w.put(uint32_t(p.subdivide ? 1 : 0));
  w.put(p.crease_angle_degrees);
  const SizingField& s = p.sizing;
  w.put(s.uniform);
  w.put(uint64_t(s.material_sizes.size()));
  for (const auto& [material, size] : s.material_sizes) {
    w.put(int32_t(material));
    w.put(int32_t(0));
    w.put(size);
  }
  w.put(uint64_t(s.radial.size()));
  for (const SizingField::Radial& r : s.radial) {
    w.put(r.center);
    w.put(r.axis);
    w.put(r.size0);
    w.put(r.growth);
  }
  w.put(uint64_t(s.boxes.size()));
  for (const SizingField::Box& b : s.boxes) {
    w.put(b.low);
    w.put(b.high);
    w.put(b.size);
  }
  return w.ok;
}

struct ParamsReader {
  std::FILE* f;
  bool ok = true;
  uint64_t long_count = 0;  // a count the file cannot hold (get_count()), else 0
  long at = -1;             // where the reading failed: the file's end, or that count's byte
  template <class T>
  T get() {
    T value{};
    if (ok && std::fread(&value, sizeof value, 1, f) != 1) {
      ok = false;
      at = std::ftell(f);
    }
    return value;
  }
  void get_bytes(char* bytes, size_t count) {
    if (ok && count > 0 && std::fread(bytes, 1, count, f) != count) {
      ok = false;
      at = std::ftell(f);
    }
  }
  Vec3 get_vec3() {
    Vec3 p;
    p.x = get<double>();
    p.y = get<double>();
    p.z = get<double>();
    return p;
  }
  // A list count that the rest of the file (`remaining` bytes) can hold.
  uint64_t get_count(uint64_t remaining, uint64_t entry_bytes) {
    const uint64_t n = get<uint64_t>();
    if (ok && n > remaining / entry_bytes) {
      ok = false;
      long_count = n;
      at = std::ftell(f) - 8;
    }
    return ok ? n : 0;
  }
  // The error once !ok, of the block `what` ("material names").
  std::string failure(const std::string& what) const {
    if (long_count > 0)
      return what + ": a count of " + std::to_string(long_count) + " (at byte " +
             std::to_string(at) + "), more than the file can hold";
    return "truncated " + what + " (the file ends at byte " + std::to_string(at) + ")";
  }
};

constexpr char kNamesMagic[8] = {'T', 'L', 'N', 'A', 'M', 'E', 'S', '1'};
constexpr size_t kMaxSavedNameBytes = 1024;

// The material names: a u64 count, then per name i32 material, u32 byte length and
// the bytes.
bool write_names(std::FILE* f, const std::vector<MaterialName>& names) {
  if (std::fwrite(kNamesMagic, 1, 8, f) != 8) return false;
  ParamsWriter w{f};
  w.put(uint64_t(names.size()));
  for (const MaterialName& n : names) {
    w.put(int32_t(n.material));
    const std::string name = n.name.substr(0, kMaxSavedNameBytes);
    w.put(uint32_t(name.size()));
    w.ok = w.ok && (name.empty() || std::fwrite(name.data(), 1, name.size(), f) == name.size());
  }
  return w.ok;
}

// Reads the names after "TLNAMES1"; an error message, or "" on success.
std::string read_names(std::FILE* f, uint64_t bytes, std::vector<MaterialName>* names) {
  ParamsReader r{f};
  const uint64_t count = r.get_count(bytes, 8);
  for (uint64_t i = 0; i < count && r.ok; ++i) {
    MaterialName n;
    n.material = r.get<int32_t>();
    const uint32_t length = r.get<uint32_t>();
    if (!r.ok) break;
    if (length == 0 || length > kMaxSavedNameBytes)
      return "material name " + std::to_string(i) + ": a length of " + std::to_string(length) +
             " bytes (at byte " + std::to_string(std::ftell(f) - 4) + "), not 1 to " +
             std::to_string(kMaxSavedNameBytes);
    n.name.resize(length);
    r.get_bytes(n.name.data(), length);
    if (r.ok && !names->empty() && n.material <= names->back().material)
      return "material names out of order";
    names->push_back(std::move(n));
  }
  if (!r.ok) return r.failure("material names");
  return "";
}

constexpr char kGroupsMagic[8] = {'T', 'L', 'G', 'R', 'O', 'U', 'P', '1'};

// The surface groups: a u64 count, per group i32 tag, u32 name length, the name, u64
// triangles, u64 missing; then a u64 count of entries, each 9 f64 (the corners), i32
// inner, i32 outer, u32 group (inner == outer: a triangle inside a material, in a group).
bool write_patches(std::FILE* f, const SurfacePatches& patches) {
  if (std::fwrite(kGroupsMagic, 1, 8, f) != 8) return false;
  ParamsWriter w{f};
  w.put(uint64_t(patches.groups().size()));
  for (const SurfacePatches::Group& g : patches.groups()) {
    w.put(int32_t(g.tag));
    const std::string name = g.name.substr(0, kMaxSavedNameBytes);
    w.put(uint32_t(name.size()));
    w.ok = w.ok && (name.empty() || std::fwrite(name.data(), 1, name.size(), f) == name.size());
    w.put(uint64_t(g.triangles));
    w.put(uint64_t(g.missing));
  }
  // The triangles inside a material after the surface's (inner == outer).
  w.put(uint64_t(patches.entries().size() + patches.inside_entries().size()));
  for (const auto* list : {&patches.entries(), &patches.inside_entries()}) {
    for (const SurfacePatches::Entry& e : *list) {
      for (const Vec3& p : e.p) w.put(p);
      w.put(int32_t(e.inner));
      w.put(int32_t(e.outer));
      w.put(uint32_t(e.group));
    }
  }
  return w.ok;
}

// Reads the groups after "TLGROUP1"; an error message, or "" on success.
std::string read_patches(std::FILE* f, uint64_t bytes, SurfacePatches* patches) {
  ParamsReader r{f};
  const uint64_t group_count = r.get_count(bytes, 24);
  std::vector<SurfacePatches::Group> groups;
  std::set<int32_t> tags;
  for (uint64_t i = 0; i < group_count && r.ok; ++i) {
    SurfacePatches::Group g;
    const long start = std::ftell(f);  // for the errors: where each field is
    const auto field = [&](const char* what, auto value, long at) {
      return "surface group " + std::to_string(i) + ": " + what + " " + std::to_string(value) +
             " (at byte " + std::to_string(start + at) + ")";
    };
    g.tag = r.get<int32_t>();
    const uint32_t length = r.get<uint32_t>();
    if (!r.ok) break;
    if (length > kMaxSavedNameBytes)
      return field("a name length of", length, 4) + ", more than " +
             std::to_string(kMaxSavedNameBytes);
    g.name.resize(length);
    r.get_bytes(g.name.data(), length);
    g.triangles = r.get<uint64_t>();
    g.missing = r.get<uint64_t>();
    if (!r.ok) break;
    if (g.tag < 1) return field("tag", g.tag, 0) + ", not a tag >= 1";
    if (g.triangles > bytes)
      return field("a triangle count of", g.triangles, 8 + long(length)) +
             ", more than the file can hold";
    if (g.missing > bytes)
      return field("a missing count of", g.missing, 16 + long(length)) +
             ", more than the file can hold";
    if (!tags.insert(g.tag).second) return "surface groups with one tag, " + std::to_string(g.tag);
    groups.push_back(std::move(g));
  }
  const uint64_t entry_count = r.get_count(bytes, 84);
  std::vector<SurfacePatches::Entry> entries;
  for (uint64_t i = 0; i < entry_count && r.ok; ++i) {
    SurfacePatches::Entry e;
    for (Vec3& p : e.p) p = r.get_vec3();
    e.inner = r.get<int32_t>();
    e.outer = r.get<int32_t>();
    e.group = r.get<uint32_t>();
    if (!r.ok) break;
    const bool inside = e.outer == e.inner && e.group != SurfacePatches::kNone;
    if (!is_finite(e.p[0]) || !is_finite(e.p[1]) || !is_finite(e.p[2]) || e.inner < 0 ||
        (e.outer != kOutsideMaterial && e.outer <= e.inner && !inside) ||
        (e.group != SurfacePatches::kNone && e.group >= groups.size()))
      return "surface group triangle " + std::to_string(i);
    entries.push_back(e);
  }
  if (!r.ok) return r.failure("surface groups");
  *patches = SurfacePatches(std::move(groups), std::move(entries));
  return "";
}

// Reads the thresholds after "TLPARAM1"; an error message, or "" on success.
std::string read_params(std::FILE* f, uint64_t bytes, SimplifyParams* p) {
  ParamsReader r{f};
  p->tolerance = r.get<double>();
  p->min_stretch = r.get<double>();
  p->max_valence = r.get<uint32_t>();
  const uint32_t subdivide = r.get<uint32_t>();
  p->subdivide = subdivide != 0;
  p->crease_angle_degrees = r.get<double>();
  SizingField& s = p->sizing;
  s.uniform = r.get<double>();
  const uint64_t materials = r.get_count(bytes, 16);
  for (uint64_t i = 0; i < materials && r.ok; ++i) {
    const int32_t material = r.get<int32_t>();
    r.get<int32_t>();
    s.material_sizes.emplace_back(material, r.get<double>());
  }
  const uint64_t radial = r.get_count(bytes, 64);
  for (uint64_t i = 0; i < radial && r.ok; ++i) {
    SizingField::Radial rule;
    rule.center = r.get_vec3();
    rule.axis = r.get_vec3();
    rule.size0 = r.get<double>();
    rule.growth = r.get<double>();
    s.radial.push_back(rule);
  }
  const uint64_t boxes = r.get_count(bytes, 56);
  for (uint64_t i = 0; i < boxes && r.ok; ++i) {
    SizingField::Box box;
    box.low = r.get_vec3();
    box.high = r.get_vec3();
    box.size = r.get<double>();
    s.boxes.push_back(box);
  }
  if (!r.ok) return r.failure("thresholds");
  // What the command line's parsers accept (sizing.h), then check_params().
  if (subdivide > 1) return "thresholds: subdivide flag " + std::to_string(subdivide);
  if (std::isnan(s.uniform)) return "thresholds: size is not a number";
  for (size_t i = 0; i < s.material_sizes.size(); ++i) {
    const auto& [material, size] = s.material_sizes[i];
    if (material < 0 || (i > 0 && material <= s.material_sizes[i - 1].first) ||
        !std::isfinite(size) || !(size > 0))
      return "thresholds: material size " + std::to_string(i);
  }
  for (size_t i = 0; i < s.radial.size(); ++i) {
    const SizingField::Radial& rule = s.radial[i];
    const bool axis_ok = rule.axis == Vec3{} || std::abs(length(rule.axis) - 1) < 1e-9;
    if (!is_finite(rule.center) || !is_finite(rule.axis) || !axis_ok ||
        !std::isfinite(rule.size0) || !(rule.size0 > 0) || !std::isfinite(rule.growth) ||
        !(rule.growth >= 0))
      return "thresholds: radial rule " + std::to_string(i);
  }
  for (size_t i = 0; i < s.boxes.size(); ++i) {
    const SizingField::Box& box = s.boxes[i];
    if (!is_finite(box.low) || !is_finite(box.high) || !std::isfinite(box.size) || !(box.size > 0))
      return "thresholds: box rule " + std::to_string(i);
  }
  return "";  // check_params() once the size map, if any, is read too
}

// The size map (sizing.h). TLSZMAP2 (since 2026-11-28): what it was built from, so
// that the reader builds the same map, value for value: a u64 vertex count, the
// vertices (3 f64 each), a u64 tet count, the tets (4 u32 each), the sizes (an f64 a
// vertex). TLSZMAP1 (read only): its values at the base's vertices, over which the
// reader builds a map, which is the run's only where the base's tets lie inside those
// the map was built on: not where edge removals or flips made them (a run past the
// valence), nor for a map over another mesh (--size-map-mesh).
constexpr char kSizeMapMagicV1[8] = {'T', 'L', 'S', 'Z', 'M', 'A', 'P', '1'};
constexpr char kSizeMapMagic[8] = {'T', 'L', 'S', 'Z', 'M', 'A', 'P', '2'};

bool write_size_map(std::FILE* f, const SizeMap& map) {
  if (std::fwrite(kSizeMapMagic, 1, 8, f) != 8) return false;
  const TetMesh& source = map.source();
  ParamsWriter w{f};
  w.put(uint64_t(source.positions.size()));
  for (const Vec3& p : source.positions) w.put(p.x), w.put(p.y), w.put(p.z);
  w.put(uint64_t(source.tets.size()));
  for (const Tet& t : source.tets)
    for (uint32_t v : t) w.put(v);
  for (double size : map.sizes()) w.put(size);
  return w.ok;
}

// Reads the block after its magic (`v1`: TLSZMAP1, values only); an error message, or
// "" on success.
std::string read_size_map(std::FILE* f, uint64_t bytes, bool v1, TetMesh* mesh,
                          std::vector<double>* values) {
  ParamsReader r{f};
  if (!v1) {
    const uint64_t vertices = r.get_count(bytes, 32);  // a position and a size
    mesh->positions.resize(vertices);
    for (uint64_t i = 0; i < vertices && r.ok; ++i) mesh->positions[i] = r.get_vec3();
    const uint64_t tets = r.get_count(bytes, 16);
    mesh->tets.resize(tets);
    for (uint64_t i = 0; i < tets && r.ok; ++i)
      for (uint32_t& v : mesh->tets[i]) v = r.get<uint32_t>();
    mesh->materials.assign(mesh->tets.size(), 0);
    values->resize(vertices);
    for (uint64_t i = 0; i < vertices && r.ok; ++i) (*values)[i] = r.get<double>();
    if (!r.ok) return r.failure("size map");
    for (const Vec3& p : mesh->positions)
      if (!is_finite(p)) return "size map: a vertex that is not finite";
    for (const Tet& t : mesh->tets)
      for (uint32_t v : t)
        if (v >= vertices) return "size map: a tet's vertex out of range";
    return "";
  }
  const uint64_t count = r.get_count(bytes, 8);
  values->resize(count);
  for (uint64_t i = 0; i < count && r.ok; ++i) (*values)[i] = r.get<double>();
  if (!r.ok) return r.failure("size map");
  return "";
}

}  // namespace

Status stage_history(OutputFiles* files, const std::string& path, const TetMesh& base,
                     const CollapseHistory& history, const SimplifyParams* params,
                     const std::vector<MaterialName>* names, const SurfacePatches* patches) {
  // Only the names of the base's materials, in order, each once and not empty: what
  // the reader accepts.
  std::vector<MaterialName> kept;
  if (names && !names->empty()) {
    std::vector<int32_t> materials = base.materials;
    std::sort(materials.begin(), materials.end());
    for (const MaterialName& n : *names) {
      if (!n.name.empty() && std::binary_search(materials.begin(), materials.end(), n.material) &&
          (kept.empty() || n.material > kept.back().material))
        kept.push_back(n);
    }
  }
  return files->stage(path, [&](std::FILE* f) {
    return std::fwrite(kHistoryMagic, 1, 8, f) == 8 && write_array(f, base.positions) &&
           write_array(f, base.tets) && write_array(f, base.materials) &&
           write_array(f, history.steps) && write_array(f, history.removed_tets) &&
           write_array(f, history.rewired) && write_array(f, history.moved) &&
           (!params || write_params(f, *params)) &&
           (!params || !params->sizing.map || write_size_map(f, *params->sizing.map)) &&
           (kept.empty() || write_names(f, kept)) &&
           (!patches || (!patches->any() && patches->inside_entries().empty()) ||
            write_patches(f, *patches)) &&
           write_end(f);
  });
}

Status write_history(const std::string& path, const TetMesh& base, const CollapseHistory& history,
                     const SimplifyParams* params, const std::vector<MaterialName>* names,
                     const SurfacePatches* patches) {
  OutputFiles files;
  if (Status s = stage_history(&files, path, base, history, params, names, patches); !s) return s;
  return files.commit();
}

namespace {

Status read_history_file(const std::string& path, TetMesh* base, CollapseHistory* history,
                         std::optional<SimplifyParams>* params, std::vector<MaterialName>* names,
                         SurfacePatches* patches, int* format) {
  // A regular file, checked before opening: opening a named pipe would wait for a
  // writer without end.
  struct stat info;
  if (stat(path.c_str(), &info) == 0 && !S_ISREG(info.st_mode)) {
    return Status::error(path + ": cannot read: " +
                         (S_ISDIR(info.st_mode) ? "it is a directory"
                                                : "it is not a regular file (a history is one)"));
  }
  std::unique_ptr<std::FILE, FileCloser> file(std::fopen(path.c_str(), "rb"));
  std::FILE* f = file.get();
  if (!f) return Status::error(path + ": cannot open: " + std::strerror(errno));
  std::fseek(f, 0, SEEK_END);
  const long size = std::ftell(f);
  std::fseek(f, 0, SEEK_SET);
  const uint64_t bytes = size > 0 ? static_cast<uint64_t>(size) : 0;
  char magic[8] = {};
  const bool read_magic = std::fread(magic, 1, 8, f) == 8;
  const int version = !read_magic                                   ? 0
                      : std::memcmp(magic, kHistoryMagic, 8) == 0   ? 3
                      : std::memcmp(magic, kHistoryMagicV2, 8) == 0 ? 2
                      : std::memcmp(magic, kHistoryMagicV1, 8) == 0 ? 1
                                                                    : 0;
  if (version == 0) {
    if (read_magic && std::memcmp(magic, kHistoryMagic, 7) == 0 && magic[7] > '3' &&
        magic[7] <= '9')
      return Status::error(path + ": a history of a newer TetLOD (format " +
                           std::string(1, magic[7]) + "); this one reads formats 1 to 3");
    return Status::error(path + ": not a TetLOD history file");
  }
  *format = version;
  const bool has_end = version >= 2;
  const char* const end_magic = version == 3 ? kEndMagic : kEndMagicV1;
  uint64_t saved_checksum = 0, checksum_at = 0;  // version 3: the checksum, and where it is
  const char* short_array = nullptr;             // the first array the file cannot hold, and where
  long short_at = 0;
  const auto array = [&](auto* v, const char* what) {
    if (short_array) return;
    short_at = std::ftell(f);
    if (!read_array(f, bytes, v)) short_array = what;
  };
  array(&base->positions, "vertex positions");
  array(&base->tets, "tets");
  array(&base->materials, "tet materials");
  array(&history->steps, "steps");
  array(&history->removed_tets, "removed tets");
  array(&history->rewired, "rewired corners");
  array(&history->moved, "moved tets");
  if (short_array) {
    return Status::error(path + ": truncated or corrupt history file: its " + short_array +
                         " (from byte " + std::to_string(short_at) + ") do not fit in its " +
                         std::to_string(bytes) + " bytes");
  }
  // The thresholds, the material names and the surface groups, if saved (after the
  // arrays, in this order, each at most once).
  std::optional<SimplifyParams> saved_params;
  std::vector<MaterialName> saved_names;
  SurfacePatches saved_patches;
  std::vector<double> saved_sizes;
  TetMesh size_map_mesh;  // TLSZMAP2's (TLSZMAP1: none, the map is over the base)
  bool has_size_map = false, size_map_v1 = false;
  int last_block = 0;  // 1 thresholds, 2 size map, 3 names, 4 surface groups, 5 the end
  for (;;) {
    char block_magic[8] = {};
    const size_t magic_bytes = std::fread(block_magic, 1, 8, f);
    if (magic_bytes == 0) {
      if (has_end && last_block != 5)
        return Status::error(path + ": truncated history file (it ends before its end block)");
      break;
    }
    const int block = magic_bytes != 8                                 ? 0
                      : std::memcmp(block_magic, kParamsMagic, 8) == 0 ? 1
                      : std::memcmp(block_magic, kSizeMapMagic, 8) == 0 ||
                              std::memcmp(block_magic, kSizeMapMagicV1, 8) == 0
                          ? 2
                      : std::memcmp(block_magic, kNamesMagic, 8) == 0  ? 3
                      : std::memcmp(block_magic, kGroupsMagic, 8) == 0 ? 4
                      : std::memcmp(block_magic, end_magic, 8) == 0    ? (has_end ? 5 : 0)
                                                                       : 0;
    const long after_tag = std::ftell(f);
    const std::string tag_at =
        " at byte " +
        std::to_string(after_tag < 0 ? 0 : after_tag - static_cast<long>(magic_bytes));
    std::string error;
    if (magic_bytes != 8 && last_block != 5) {
      error = "the file ends inside a block's 8-byte tag (" + std::to_string(magic_bytes) +
              (magic_bytes == 1 ? " byte" : " bytes") + tag_at + ")";
    } else if (block <= last_block || (block == 2 && last_block != 1)) {
      error = (last_block == 5                 ? "bytes after the end block"
               : block == 2 && last_block == 0 ? "a size map without thresholds"
               : last_block > 0 ? "a block out of order, or unknown bytes, after the thresholds, "
                                  "names or surface groups"
                                : "bytes after the last step") +
              tag_at;
    } else if (block == 5 && version == 3) {
      const long at = std::ftell(f);
      if (at < 0 || std::fread(&saved_checksum, sizeof saved_checksum, 1, f) != 1)
        error = "truncated end block";
      checksum_at = at < 0 ? 0 : static_cast<uint64_t>(at);
    } else if (block == 5) {
      uint64_t length = 0;
      const bool read = std::fread(&length, sizeof length, 1, f) == 1;
      const long at = std::ftell(f);
      if (!read || at < 0 || length != static_cast<uint64_t>(at))
        error = "the end block does not match the file's length";
    } else if (block == 1) {
      saved_params.emplace();
      error = read_params(f, bytes, &*saved_params);
    } else if (block == 2) {
      has_size_map = true;
      size_map_v1 = std::memcmp(block_magic, kSizeMapMagicV1, 8) == 0;
      error = read_size_map(f, bytes, size_map_v1, &size_map_mesh, &saved_sizes);
    } else if (block == 3) {
      error = read_names(f, bytes, &saved_names);
    } else {
      error = read_patches(f, bytes, &saved_patches);
    }
    if (!error.empty()) return Status::error(path + ": corrupt history: " + error);
    last_block = block;
  }
  // Every index in range and every range well formed, so replay cannot go astray.
  const size_t vertex_count = base->positions.size();
  const size_t tet_count = base->tets.size();
  auto bad = [&](const std::string& what) {
    return Status::error(path + ": corrupt history: " + what);
  };
  if (base->materials.size() != tet_count) return bad("material count");
  for (const Vec3& p : base->positions)
    if (!is_finite(p)) return bad("non-finite position");
  const std::string vertices_there = "; the base has " + std::to_string(vertex_count) + ")";
  const std::string tets_there = "; the base has " + std::to_string(tet_count) + ")";
  for (size_t t = 0; t < tet_count; ++t)
    for (uint32_t v : base->tets[t])
      if (v >= vertex_count)
        return bad("tet " + std::to_string(t) + ": vertex out of range (" + std::to_string(v) +
                   vertices_there);
  uint32_t removed_at = 0, rewired_at = 0, moved_at = 0;
  for (size_t s = 0; s < history->steps.size(); ++s) {
    const CollapseHistory::Step& st = history->steps[s];
    if (st.kept >= vertex_count || st.removed >= vertex_count || st.kept == st.removed)
      return bad("step " + std::to_string(s) + ": vertex out of range (kept " +
                 std::to_string(st.kept) + ", removed " + std::to_string(st.removed) +
                 vertices_there);
    if (!is_finite(st.old_position) || !is_finite(st.new_position))
      return bad("step " + std::to_string(s) + ": a position is not finite");
    if (st.removed_begin != removed_at || st.rewired_begin != rewired_at ||
        st.moved_begin != moved_at)
      return bad("step " + std::to_string(s) +
                 ": its lists of removed, rewired and moved tets do not start where the "
                 "previous step's end");
    removed_at = history->removed_end(s);
    rewired_at = history->rewired_end(s);
    moved_at = history->moved_end(s);
    if (removed_at < st.removed_begin || removed_at > history->removed_tets.size() ||
        rewired_at < st.rewired_begin || rewired_at > history->rewired.size() ||
        moved_at < st.moved_begin || moved_at > history->moved.size())
      return bad("step " + std::to_string(s) +
                 ": its lists of removed, rewired or moved tets run past the file's");
  }
  if (!history->steps.empty() &&
      (removed_at != history->removed_tets.size() || rewired_at != history->rewired.size() ||
       moved_at != history->moved.size()))
    return bad("trailing entries");
  const auto out_of_range = [&](const char* list, size_t k, uint32_t t) {
    return bad(std::string(list) + " " + std::to_string(k) + ": tet out of range (" +
               std::to_string(t) + tets_there);
  };
  for (size_t k = 0; k < history->removed_tets.size(); ++k)
    if (history->removed_tets[k] >= tet_count)
      return out_of_range("removed tet", k, history->removed_tets[k]);
  for (size_t k = 0; k < history->rewired.size(); ++k)
    if ((history->rewired[k] >> 2) >= tet_count)
      return out_of_range("rewired corner", k, history->rewired[k] >> 2);
  for (size_t k = 0; k < history->moved.size(); ++k)
    if (history->moved[k] >= tet_count) return out_of_range("moved tet", k, history->moved[k]);
  // The base: what the simplifier writes is a validated mesh, so every tet is
  // positive and every material >= 0.
  for (size_t t = 0; t < tet_count; ++t) {
    if (base->materials[t] < 0) return bad("tet " + std::to_string(t) + " has a negative material");
    if (!(signed_volume6(*base, base->tets[t]) > 0))
      return bad("tet " + std::to_string(t) + " is flat or inverted");
  }
  // Replay once to check that the steps are collapses of this mesh: each step
  // retires alive tets around the edge (kept, removed), rewires every other use of
  // the removed vertex to the kept one, lists as moved exactly the other tets of
  // the kept vertex, starts from the kept vertex's current position, and leaves
  // every tet it changed positive. Then every level is a mesh of positive tets.
  std::vector<uint8_t> alive(tet_count, 1);
  std::vector<Tet> tets = base->tets;
  std::vector<Vec3> positions = base->positions;
  std::vector<uint32_t> uses(vertex_count, 0);  // alive tet corners holding each vertex
  for (const Tet& t : tets)
    for (uint32_t v : t) ++uses[v];
  auto positive = [&](uint32_t t) {
    const Tet& q = tets[t];
    return signed_volume6(positions[q[0]], positions[q[1]], positions[q[2]], positions[q[3]]) > 0;
  };
  std::vector<uint32_t> listed_at(tet_count, 0);  // 1 + the last step listing a tet as moved
  for (size_t s = 0; s < history->steps.size(); ++s) {
    const CollapseHistory::Step& st = history->steps[s];
    auto at = [s](const char* what) { return "step " + std::to_string(s) + ": " + what; };
    if (uses[st.kept] == 0 || uses[st.removed] == 0) return bad(at("a vertex no tet uses"));
    if (std::memcmp(&positions[st.kept], &st.old_position, sizeof(Vec3)) != 0)
      return bad(at("the kept vertex is not where the step starts"));
    for (uint32_t k = st.removed_begin; k < history->removed_end(s); ++k) {
      const uint32_t t = history->removed_tets[k];
      if (!alive[t]) return bad(at("tet retired twice"));
      if (!tet_has(tets[t], st.kept) || !tet_has(tets[t], st.removed))
        return bad(at("a retired tet is not around the edge"));
      alive[t] = 0;
      for (uint32_t v : tets[t]) --uses[v];
    }
    positions[st.kept] = st.new_position;
    for (uint32_t k = st.rewired_begin; k < history->rewired_end(s); ++k) {
      const uint32_t c = history->rewired[k];
      if (!alive[c >> 2] || tets[c >> 2][c & 3] != st.removed)
        return bad(at("rewired corner mismatch"));
      tets[c >> 2][c & 3] = st.kept;
      --uses[st.removed];
      ++uses[st.kept];
      if (!positive(c >> 2)) return bad(at("makes a flat or inverted tet"));
    }
    if (uses[st.removed] != 0) return bad(at("the removed vertex is still used"));
    for (uint32_t k = st.moved_begin; k < history->moved_end(s); ++k) {
      const uint32_t t = history->moved[k];
      if (!alive[t] || !tet_has(tets[t], st.kept)) return bad(at("moved tet mismatch"));
      if (listed_at[t] == s + 1) return bad(at("a moved tet listed twice"));
      listed_at[t] = static_cast<uint32_t>(s + 1);
      if (!positive(t)) return bad(at("makes a flat or inverted tet"));
    }
    if (uses[st.kept] !=
        (history->rewired_end(s) - st.rewired_begin) + (history->moved_end(s) - st.moved_begin))
      return bad(at("moved tets missing"));
  }
  // The saved size map, over the mesh it was built on (or, TLSZMAP1, the base: a mesh
  // of positive tets, checked above; SizeMap::build() checks any), then the
  // thresholds as a whole.
  if (saved_params) {
    if (has_size_map) {
      std::shared_ptr<const SizeMap> map;
      if (Status s =
              SizeMap::build(size_map_v1 ? *base : size_map_mesh, std::move(saved_sizes), &map);
          !s)
        return bad("size map: " + s.message());
      saved_params->sizing.map = std::move(map);
    }
    if (Status status = check_params(*saved_params); !status)
      return bad("thresholds: " + status.message());
  }
  // A saved material size names a material of the mesh (as --material-size must).
  if (saved_params) {
    std::vector<int32_t> materials = base->materials;
    std::sort(materials.begin(), materials.end());
    const auto& sizes = saved_params->sizing.material_sizes;
    for (size_t i = 0; i < sizes.size(); ++i) {
      if (!std::binary_search(materials.begin(), materials.end(), sizes[i].first))
        return bad("thresholds: material size " + std::to_string(i) + " names material " +
                   std::to_string(sizes[i].first) + ", which the mesh does not have");
    }
  }
  // A saved name is of a material of the mesh.
  if (!saved_names.empty()) {
    std::vector<int32_t> materials = base->materials;
    std::sort(materials.begin(), materials.end());
    for (const MaterialName& n : saved_names) {
      if (!std::binary_search(materials.begin(), materials.end(), n.material))
        return bad("a name for material " + std::to_string(n.material) +
                   ", which the mesh does not have");
    }
  }
  // Last, what every check above can miss: a byte changed where any value would do
  // (a position's low bits made a level of flat tets).
  if (version == 3) {
    uint64_t sum = 0;
    if (!checksum_of_file(f, checksum_at, &sum))
      return Status::error(path + ": cannot read: " + std::strerror(errno));
    if (sum != saved_checksum)
      return bad(
          "its checksum does not match: the file was changed or damaged after it was "
          "written");
  }
  if (params) *params = std::move(saved_params);
  if (names) *names = std::move(saved_names);
  if (patches) *patches = std::move(saved_patches);
  return Status();
}

// What the end of a history file of `format` >= 2 says about a file the reader refused:
// that it does not end with its end block (cut short, or bytes added), or (format 3)
// that its checksum does not match (changed after it was written); "" if neither.
std::string end_of_refused_file(const std::string& path, int format) {
  std::unique_ptr<std::FILE, FileCloser> file(std::fopen(path.c_str(), "rb"));
  std::FILE* f = file.get();
  if (!f || std::fseek(f, 0, SEEK_END) != 0) return "";
  const long size = std::ftell(f);
  char magic[8] = {};
  uint64_t value = 0;
  const bool ended = size >= 8 + 16 && std::fseek(f, size - 16, SEEK_SET) == 0 &&
                     std::fread(magic, 1, 8, f) == 8 && std::fread(&value, 8, 1, f) == 1 &&
                     std::memcmp(magic, format == 3 ? kEndMagic : kEndMagicV1, 8) == 0 &&
                     (format == 3 || value == static_cast<uint64_t>(size));
  if (!ended)
    return "; it does not end with its end block: it was cut short, or bytes were added after it";
  uint64_t sum = 0;
  if (format == 3 && checksum_of_file(f, static_cast<uint64_t>(size - 8), &sum) && sum != value)
    return "; and its checksum does not match: the file was changed or damaged after it was "
           "written";
  return "";
}

}  // namespace

std::string unchecked_history_note(int format) {
  if (format >= 3) return "";
  return "a history of format " + std::to_string(format) +
         " (written before 2026-11-29), without a checksum: a change to it that every other "
         "check passes cannot be found";
}

Status read_history(const std::string& path, TetMesh* base, CollapseHistory* history,
                    std::optional<SimplifyParams>* params, std::vector<MaterialName>* names,
                    SurfacePatches* patches, int* format) {
  int version = 0;
  Status s = read_history_file(path, base, history, params, names, patches, &version);
  if (format) *format = version;
  // A damaged file is refused by the first check it fails; say also why it may be
  // damaged, as its end block can tell (unless the message already says so).
  if (!s && version >= 2 && s.message().find("end block") == std::string::npos &&
      s.message().find("checksum") == std::string::npos &&
      (s.message().find(": corrupt history: ") != std::string::npos ||
       s.message().find(": truncated") != std::string::npos))
    s = Status::error(s.message() + end_of_refused_file(path, version));
  return s;
}

uint64_t history_checksum(std::string_view bytes) {
  Checksum checksum;
  checksum.add(reinterpret_cast<const unsigned char*>(bytes.data()), bytes.size());
  return checksum.finish();
}

}  // namespace tetlod
