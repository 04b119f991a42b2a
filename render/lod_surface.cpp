#include "render/lod_surface.h"

#include <algorithm>
#include <cstddef>

#include "core/metrics.h"

namespace tetlod::render {

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

bool LodSurface::tet_visible(const LodState& state, uint32_t tet) const {
  if (!(*state.alive)[tet]) return false;
  const int32_t material = (*state.materials)[tet];
  if (material >= 0 && size_t(material) < hidden_.size() && hidden_[size_t(material)]) return false;
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
        {float(p.x), float(p.y), float(p.z)}, stretch_[tet], material};
  }
  triangle_dirty_.push_back(slot);
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
    faces_.find(slot_keys_[slot])->second.slot = slot;
    triangle_dirty_.push_back(slot);
  }
  slot_keys_.pop_back();
  triangles_.resize(triangles_.size() - 3);
  entry->slot = kInvalidIndex;
}

void LodSurface::add_face(const FaceKey& key, uint32_t owner) {
  FaceEntry& entry = faces_[key];
  // A manifold mesh has at most two tets on a face; removals run before additions.
  (entry.owners[0] == kInvalidIndex ? entry.owners[0] : entry.owners[1]) = owner;
  refresh_face(key, &entry);
}

void LodSurface::remove_face(const FaceKey& key, uint32_t owner) {
  const auto it = faces_.find(key);
  if (it == faces_.end()) return;
  FaceEntry& entry = it->second;
  if (entry.owners[0] == owner) entry.owners[0] = kInvalidIndex;
  if (entry.owners[1] == owner) entry.owners[1] = kInvalidIndex;
  refresh_face(key, &entry);
  if (entry.owners[0] == kInvalidIndex && entry.owners[1] == kInvalidIndex) faces_.erase(it);
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
  stretch_[tet] = static_cast<float>(tet_shape(p[t[0]], p[t[1]], p[t[2]], p[t[3]]).stretch);
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
  hidden_.clear();
  for (const int32_t m : filter.hidden_materials) {
    if (m < 0) continue;
    if (size_t(m) >= hidden_.size()) hidden_.resize(size_t(m) + 1, 0);
    hidden_[size_t(m)] = 1;
  }
  const size_t n = state.tets->size();
  in_.assign(n, 0);
  corners_.resize(n);
  stretch_.assign(n, 0);
  highlight_slot_.assign(n, kInvalidIndex);
  visible_count_ = 0;
  faces_.clear();
  faces_.reserve(2 * n + 16);
  triangles_.clear();
  slot_keys_.clear();
  highlight_.clear();
  highlight_tets_.clear();
  for (uint32_t t = 0; t < n; ++t)
    if (tet_visible(state, t)) add_tet(state, t);
  // Everything is new: one range each.
  triangle_dirty_.clear();
  highlight_dirty_.clear();
  for (uint32_t slot = 0; slot < slot_keys_.size(); ++slot) triangle_dirty_.push_back(slot);
  for (uint32_t slot = 0; slot < highlight_tets_.size(); ++slot) highlight_dirty_.push_back(slot);
  state_ = nullptr;
}

void LodSurface::update(const LodState& state, const LodDelta& delta) {
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

}  // namespace tetlod::render
