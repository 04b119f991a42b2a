#include "render/lod_surface.h"

#include <algorithm>
#include <cassert>
#include <cstddef>

#include "core/metrics.h"

namespace tetlod::render {
namespace {

// The face table's part a bulk insertion (LodSurface::reset()) fills at a time: about
// what a core's second-level cache holds.
constexpr size_t kPartBytes = size_t(1) << 20;
// Faces a bulk insertion sorts at a time (20 bytes each, twice).
constexpr size_t kBatchFaces = size_t(1) << 19;

}  // namespace

std::vector<DirtyRange> LodSurface::take_ranges(std::vector<uint32_t>* slots, size_t slot_vertices,
                                                size_t vertex_count) {
  std::sort(slots->begin(), slots->end());
  std::vector<DirtyRange> ranges;
  for (const uint32_t slot : *slots) {
    const size_t begin = size_t(slot) * slot_vertices;
    const size_t end = std::min(begin + slot_vertices, vertex_count);
    if (begin >= end) continue;
    if (!ranges.empty() && ranges.back().end >= begin) {
      ranges.back().end = std::max(ranges.back().end, end);
    } else {
      ranges.push_back({begin, end});
    }
  }
  slots->clear();
  return ranges;
}

std::vector<DirtyRange> LodSurface::take_triangle_dirty() {
  return take_ranges(&triangle_dirty_, 3, triangles_.size());
}

std::vector<DirtyRange> LodSurface::take_highlight_dirty() {
  return take_ranges(&highlight_dirty_, 12, highlight_.size());
}

size_t LodSurface::FaceTable::home(const FaceKey& k) const {
  // The sum of the three ids picks the region (wrapping around the table), a hash of
  // two of them spreads within a few cache lines of it. With spatially coherent ids
  // (the simplifier's Morton order) nearby faces share cache lines; with any other
  // order the sum modulo the table is still uniform. (Homes that followed the smallest
  // id alone piled up in TetGen's order, where the smallest of three ids is skewed
  // towards 0: linear probing then took 90 s for the first surface of a 580k-tet mesh.)
  const uint64_t spread = (uint64_t(k.v[1]) * 0x9e3779b1u ^ uint64_t(k.v[2]) * 0x85ebca6bu) >> 7;
  const uint64_t sum = uint64_t(k.v[0]) + k.v[1] + k.v[2];
  return static_cast<size_t>(((sum * scale_) >> 32) + (spread & 15)) & mask_;
}

size_t LodSurface::FaceTable::parts(size_t part_bytes) {
  // Buckets (a power of two) per part: halved until a part fits part_bytes.
  part_shift_ = 0;
  while ((size_t(1) << part_shift_) < buckets_.size()) ++part_shift_;
  while (part_shift_ > 4 && (size_t(1) << part_shift_) * sizeof(Bucket) > part_bytes) --part_shift_;
  return buckets_.size() >> part_shift_;
}

void LodSurface::FaceTable::clear(size_t expected_faces, size_t vertex_count) {
  size_t capacity = 64;
  while (capacity < expected_faces + expected_faces / 2) capacity *= 2;
  buckets_.assign(capacity, Bucket());
  mask_ = capacity - 1;
  size_ = 0;
  scale_ = (uint64_t(capacity) << 32) / std::max<uint64_t>(vertex_count, 1);
}

const LodSurface::FaceEntry* LodSurface::FaceTable::find(const FaceKey& key) const {
  for (size_t i = home(key);; i = (i + 1) & mask_) {
    const Bucket& b = buckets_[i];
    if (b.key == key) return &b.entry;
    if (b.key.v[0] == kInvalidIndex) return nullptr;
  }
}

LodSurface::FaceEntry* LodSurface::FaceTable::insert(const FaceKey& key) {
  if ((size_ + 1) * 10 > buckets_.size() * 7) grow();
  for (size_t i = home(key);; i = (i + 1) & mask_) {
    Bucket& b = buckets_[i];
    if (b.key == key) return &b.entry;
    if (b.key.v[0] == kInvalidIndex) {
      b.key = key;
      b.entry = FaceEntry();
      ++size_;
      return &b.entry;
    }
  }
}

void LodSurface::FaceTable::erase(const FaceKey& key) {
  size_t i = home(key);
  while (!(buckets_[i].key == key)) {
    if (buckets_[i].key.v[0] == kInvalidIndex) return;
    i = (i + 1) & mask_;
  }
  // Backward-shift deletion: pull later entries of the probe run into the hole
  // unless their home lies cyclically in (hole, their position].
  for (size_t j = (i + 1) & mask_; buckets_[j].key.v[0] != kInvalidIndex; j = (j + 1) & mask_) {
    const size_t k = home(buckets_[j].key);
    const bool stays = i <= j ? (i < k && k <= j) : (i < k || k <= j);
    if (stays) continue;
    buckets_[i] = buckets_[j];
    i = j;
  }
  buckets_[i] = Bucket();
  --size_;
}

void LodSurface::FaceTable::grow() {
  std::vector<Bucket> old = std::move(buckets_);
  buckets_.assign(old.size() * 2, Bucket());
  mask_ = buckets_.size() - 1;
  scale_ *= 2;
  for (const Bucket& b : old) {
    if (b.key.v[0] == kInvalidIndex) continue;
    size_t i = home(b.key);
    while (buckets_[i].key.v[0] != kInvalidIndex) i = (i + 1) & mask_;
    buckets_[i] = b;
  }
}

bool LodSurface::tet_visible(const LodState& state, uint32_t tet) const {
  if (!(*state.alive)[tet]) return false;
  const int32_t material = (*state.materials)[tet];
  if (hidden_.contains(material)) return false;
  if (!filter_.cut) return true;
  const Tet& t = (*state.tets)[tet];
  const std::vector<Vec3>& p = *state.positions;
  const Vec3 sum = p[t[0]] + p[t[1]] + p[t[2]] + p[t[3]];
  return dot(filter_.cut_plane.normal, sum) <= 4 * filter_.cut_plane.offset;
}

LodSurface::FaceKey LodSurface::face_key(uint32_t tet, int corner) const {
  const Tet& t = corners_[tet];
  FaceKey key{{t[kTetFace[corner][0]], t[kTetFace[corner][1]], t[kTetFace[corner][2]]}};
  std::sort(key.v, key.v + 3);
  return key;
}

void LodSurface::write_face_slot(uint32_t slot, uint32_t owner) {
  const uint32_t tet = owner / 4;
  const int corner = static_cast<int>(owner % 4);
  const Tet& t = corners_[tet];
  const std::vector<Vec3>& positions = *state_->positions;
  const auto material = static_cast<uint32_t>((*state_->materials)[tet]);
  for (int k = 0; k < 3; ++k) {
    const Vec3& p = positions[t[kTetFace[corner][k]]];
    triangles_[size_t(slot) * 3 + size_t(k)] = {
        {float(p.x), float(p.y), float(p.z)}, scalar(tet), material};
  }
  triangle_dirty_.push_back(slot);
}

void LodSurface::rewrite_scalars() {
  for (uint32_t slot = 0; slot < slot_keys_.size(); ++slot) {
    const FaceEntry& entry = *faces_.find(slot_keys_[slot]);
    const uint32_t owner = entry.owners[0] != kInvalidIndex ? entry.owners[0] : entry.owners[1];
    const float value = scalar(owner / 4);
    for (size_t k = 0; k < 3; ++k) triangles_[size_t(slot) * 3 + k].stretch = value;
    triangle_dirty_.push_back(slot);
  }
}

void LodSurface::set_tet_values(std::vector<float> values) {
  assert(values.size() == in_.size());
  values_ = std::move(values);
  rewrite_scalars();
}

void LodSurface::set_color_by_size(bool by_size) {
  if (by_size == by_size_) return;
  by_size_ = by_size;
  if (values_.empty()) rewrite_scalars();
}

void LodSurface::clear_tet_values() {
  if (values_.empty()) return;
  values_.clear();
  rewrite_scalars();
}

void LodSurface::refresh_face(const FaceKey& key, FaceEntry* entry) {
  const int owners = (entry->owners[0] != kInvalidIndex) + (entry->owners[1] != kInvalidIndex);
  if (owners == 1) {
    if (entry->slot == kInvalidIndex) {
      entry->slot = static_cast<uint32_t>(slot_keys_.size());
      slot_keys_.push_back(key);
      triangles_.resize(triangles_.size() + 3);
    }
    write_face_slot(entry->slot,
                    entry->owners[0] != kInvalidIndex ? entry->owners[0] : entry->owners[1]);
    return;
  }
  if (entry->slot == kInvalidIndex) return;
  // Swap-remove: the last drawn face moves into this slot.
  const uint32_t slot = entry->slot;
  const auto last = static_cast<uint32_t>(slot_keys_.size() - 1);
  if (slot != last) {
    std::copy_n(triangles_.begin() + std::ptrdiff_t(last) * 3, 3,
                triangles_.begin() + std::ptrdiff_t(slot) * 3);
    slot_keys_[slot] = slot_keys_[last];
    faces_.find(slot_keys_[slot])->slot = slot;
    triangle_dirty_.push_back(slot);
  }
  slot_keys_.pop_back();
  triangles_.resize(triangles_.size() - 3);
  entry->slot = kInvalidIndex;
}

void LodSurface::add_face(const FaceKey& key, uint32_t owner) {
  FaceEntry& entry = *faces_.insert(key);
  // A manifold mesh has at most two tets on a face; removals run before additions.
  (entry.owners[0] == kInvalidIndex ? entry.owners[0] : entry.owners[1]) = owner;
  refresh_face(key, &entry);
}

void LodSurface::remove_face(const FaceKey& key, uint32_t owner) {
  FaceEntry* found = faces_.find(key);
  if (!found) return;
  FaceEntry& entry = *found;
  if (entry.owners[0] == owner) entry.owners[0] = kInvalidIndex;
  if (entry.owners[1] == owner) entry.owners[1] = kInvalidIndex;
  refresh_face(key, &entry);
  if (entry.owners[0] == kInvalidIndex && entry.owners[1] == kInvalidIndex) faces_.erase(key);
}

void LodSurface::add_highlight(uint32_t tet) {
  highlight_slot_[tet] = static_cast<uint32_t>(highlight_tets_.size());
  highlight_tets_.push_back(tet);
  const Tet& t = corners_[tet];
  const std::vector<Vec3>& positions = *state_->positions;
  const auto material = static_cast<uint32_t>((*state_->materials)[tet]);
  for (int corner = 0; corner < 4; ++corner)
    for (int k = 0; k < 3; ++k) {
      const Vec3& p = positions[t[kTetFace[corner][k]]];
      highlight_.push_back({{float(p.x), float(p.y), float(p.z)}, stretch_[tet], material});
    }
  highlight_dirty_.push_back(highlight_slot_[tet]);
}

void LodSurface::remove_highlight(uint32_t tet) {
  const uint32_t slot = highlight_slot_[tet];
  const auto last = static_cast<uint32_t>(highlight_tets_.size() - 1);
  if (slot != last) {
    std::copy_n(highlight_.begin() + std::ptrdiff_t(last) * 12, 12,
                highlight_.begin() + std::ptrdiff_t(slot) * 12);
    highlight_tets_[slot] = highlight_tets_[last];
    highlight_slot_[highlight_tets_[slot]] = slot;
    highlight_dirty_.push_back(slot);
  }
  highlight_tets_.pop_back();
  highlight_.resize(highlight_.size() - 12);
  highlight_slot_[tet] = kInvalidIndex;
}

void LodSurface::add_tet(const LodState& state, uint32_t tet) {
  const Tet& t = (*state.tets)[tet];
  const std::vector<Vec3>& p = *state.positions;
  corners_[tet] = t;
  const TetShape shape = tet_shape(p[t[0]], p[t[1]], p[t[2]], p[t[3]]);
  stretch_[tet] = static_cast<float>(shape.stretch);
  size_[tet] = static_cast<float>(shape.size);
  in_[tet] = 1;
  ++visible_count_;
  for (int corner = 0; corner < 4; ++corner) add_face(face_key(tet, corner), 4 * tet + corner);
  if (filter_.highlight && stretch_[tet] < filter_.highlight_below) add_highlight(tet);
}

void LodSurface::remove_tet(uint32_t tet) {
  for (int corner = 0; corner < 4; ++corner)
    remove_face(face_key(tet, corner), 4 * tet + uint32_t(corner));
  if (highlight_slot_[tet] != kInvalidIndex) remove_highlight(tet);
  in_[tet] = 0;
  --visible_count_;
}

void LodSurface::reset(const LodState& state, const SurfaceFilter& filter) {
  state_ = &state;
  filter_ = filter;
  values_.clear();
  hidden_ = MaterialSet(filter.hidden_materials);
  const size_t n = state.tets->size();
  in_.assign(n, 0);
  corners_.resize(n);
  stretch_.assign(n, 0);
  size_.assign(n, 0);
  highlight_slot_.assign(n, kInvalidIndex);
  visible_count_ = 0;
  // About two distinct faces per tet (interior faces are shared); grows if needed.
  faces_.clear(2 * n + n / 4, state.positions->size());
  triangles_.clear();
  slot_keys_.clear();
  highlight_.clear();
  highlight_tets_.clear();
  triangle_dirty_.clear();  // every slot written below is marked again
  highlight_dirty_.clear();
  // Interior faces are never drawn and then removed: every face is counted first, and
  // the faces one visible tet has get their slots after. The faces go into the table in
  // batches, each sorted by the part of the table its homes fall in and put in part by
  // part, so that a part's buckets (kPartBytes) stay in cache while it fills (in tet
  // order, nearly every insertion missed the cache: 2.3 us a tet on a 1.1M-tet motor).
  const std::vector<Vec3>& p = *state.positions;
  for (uint32_t t = 0; t < n; ++t) {
    if (!tet_visible(state, t)) continue;
    const Tet& corners = (*state.tets)[t];
    corners_[t] = corners;
    const TetShape shape = tet_shape(p[corners[0]], p[corners[1]], p[corners[2]], p[corners[3]]);
    stretch_[t] = static_cast<float>(shape.stretch);
    size_[t] = static_cast<float>(shape.size);
    in_[t] = 1;
    ++visible_count_;
  }
  struct Staged {
    FaceKey key;
    uint32_t owner;  // 4 * tet + corner
    uint32_t part;
  };
  std::vector<Staged> batch, sorted;
  batch.reserve(std::min(kBatchFaces, 4 * visible_count_));
  std::vector<uint32_t> part_begin;
  std::vector<uint8_t> drawn(4 * size_t(n), 0);  // per owner: its face has one visible tet
  for (uint32_t t = 0; t < n;) {
    // A batch never grows the table (it holds no more faces than the table has room
    // for): in part order, the first parts would fill past the 70 % at which it grows,
    // where a mesh of few shared faces (4 a tet, the table sized for 2.25) overflows
    // them into long probe runs. So the parts, found again after a growth, hold.
    if (faces_.room() < 4) faces_.grow();
    const size_t limit = std::min(kBatchFaces, faces_.room());
    const size_t parts = faces_.parts(kPartBytes);
    part_begin.assign(parts + 1, 0);
    batch.clear();
    for (; t < n && batch.size() + 4 <= limit; ++t) {
      if (!in_[t]) continue;
      for (uint32_t corner = 0; corner < 4; ++corner) {
        const FaceKey key = face_key(t, int(corner));
        batch.push_back({key, 4 * t + corner, uint32_t(faces_.part(key))});
      }
    }
    for (const Staged& f : batch) ++part_begin[f.part + 1];
    for (size_t k = 0; k < parts; ++k) part_begin[k + 1] += part_begin[k];
    sorted.resize(batch.size());
    for (const Staged& f : batch) sorted[part_begin[f.part]++] = f;
    for (const Staged& f : sorted) {
      FaceEntry& entry = *faces_.insert(f.key);
      if (entry.owners[0] == kInvalidIndex) {
        entry.owners[0] = f.owner;
        drawn[f.owner] = 1;
      } else {
        entry.owners[1] = f.owner;
        drawn[entry.owners[0]] = 0;
      }
    }
  }
  batch = {};
  sorted = {};
  for (uint32_t t = 0; t < n; ++t) {
    if (!in_[t]) continue;
    for (int corner = 0; corner < 4; ++corner) {
      if (!drawn[4 * size_t(t) + size_t(corner)]) continue;
      const FaceKey key = face_key(t, corner);
      refresh_face(key, faces_.find(key));
    }
    if (filter_.highlight && stretch_[t] < filter_.highlight_below) add_highlight(t);
  }
  state_ = nullptr;
}

void LodSurface::update(const LodState& state, const LodDelta& delta) {
  clear_tet_values();
  state_ = &state;
  // Removals first, so that no face ever has more than its two tets.
  for (const uint32_t t : delta.vanished)
    if (in_[t]) remove_tet(t);
  for (const uint32_t t : delta.changed)
    if (in_[t]) remove_tet(t);
  for (const uint32_t t : delta.changed)
    if (tet_visible(state, t)) add_tet(state, t);
  for (const uint32_t t : delta.appeared)
    if (tet_visible(state, t)) add_tet(state, t);
  state_ = nullptr;
}

LodSurface::Pick LodSurface::pick(const Ray& ray) const {
  // Every drawn face, Moller-Trumbore in double (faces seen from either side: a cut
  // shows inner ones); the nearest hit in front of the eye.
  Pick best;
  const Vec3 o = ray.origin, d = ray.direction;
  for (size_t slot = 0; slot < slot_keys_.size(); ++slot) {
    const SurfaceVertex* v = &triangles_[slot * 3];
    const Vec3 a{v[0].position[0], v[0].position[1], v[0].position[2]};
    const Vec3 e1 = Vec3{v[1].position[0], v[1].position[1], v[1].position[2]} - a;
    const Vec3 e2 = Vec3{v[2].position[0], v[2].position[1], v[2].position[2]} - a;
    const Vec3 p = cross(d, e2);
    const double det = dot(e1, p);
    if (det == 0) continue;
    const double inv = 1 / det;
    const Vec3 s = o - a;
    const double u = dot(s, p) * inv;
    if (u < 0 || u > 1) continue;
    const Vec3 q = cross(s, e1);
    const double w = dot(d, q) * inv;
    if (w < 0 || u + w > 1) continue;
    const double t = dot(e2, q) * inv;
    if (t > 0 && t < best.distance) {
      const FaceEntry& entry = *faces_.find(slot_keys_[slot]);
      const uint32_t owner = entry.owners[0] != kInvalidIndex ? entry.owners[0] : entry.owners[1];
      best.tet = owner / 4;
      best.distance = t;
    }
  }
  return best;
}

}  // namespace tetlod::render
