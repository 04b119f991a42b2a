// The drawn surface of an LOD mesh, kept up to date from LodDelta: after a seek only
// the appeared, vanished and changed tets are touched, and only the slots of the
// vertex buffer they affect are marked for upload.
//
// A face is drawn when exactly one visible tet has it (the same rule as
// build_surface(): boundary faces, and faces whose other side is hidden, cut away
// or retired). Faces are counted in a hash table keyed by their sorted vertex ids
// (base-mesh ids, stable across LOD steps), so no face-neighbour array is needed;
// the table is flat (open addressing, linear probing, backward-shift deletion).
// Drawn faces occupy dense slots of 3 vertices; a removed face's slot is filled by
// the last one (swap-remove), so the buffer stays dense.
#pragma once

#include <array>
#include <cstdint>
#include <limits>
#include <vector>

#include "core/lod.h"
#include "render/camera.h"
#include "render/surface_builder.h"

namespace tetlod::render {

// The arrays of one LOD state (Lod::positions(), tets(), materials(), alive()).
struct LodState {
  const std::vector<Vec3>* positions = nullptr;
  const std::vector<Tet>* tets = nullptr;
  const std::vector<int32_t>* materials = nullptr;
  const std::vector<uint8_t>* alive = nullptr;
};

inline LodState lod_state(const Lod& lod) {
  return {&lod.positions(), &lod.tets(), &lod.materials(), &lod.alive()};
}

class LodSurface {
 public:
  // Rebuilds everything for `state` under `filter` (also after a filter change).
  void reset(const LodState& state, const SurfaceFilter& filter);
  // Updates after Lod::seek(step, &delta); `state` is the state after the seek.
  void update(const LodState& state, const LodDelta& delta);

  // 3 vertices per drawn face, 12 per highlighted tet (all four faces).
  const std::vector<SurfaceVertex>& triangles() const { return triangles_; }
  const std::vector<SurfaceVertex>& highlight() const { return highlight_; }
  size_t highlighted_tets() const { return highlight_.size() / 12; }
  size_t visible_tets() const { return visible_count_; }

  // Colours the drawn faces by `values` (one per tet id of the state last given,
  // e.g. |E| of an electrostatic solve of that state) instead of by stretch: every
  // drawn slot is rewritten and marked dirty. The values belong to that state, so
  // update() and reset() drop them (back to stretch) before they change anything;
  // clear_tet_values() does so at once. Highlighting keeps following stretch.
  // Precondition: values.size() is the state's tet count.
  void set_tet_values(std::vector<float> values);
  void clear_tet_values();
  bool has_tet_values() const { return !values_.empty(); }
  // Colours the drawn faces by their tet's size (its longest edge) instead of its
  // stretch, where no tet values are set: every drawn slot is rewritten and marked
  // dirty. Kept through update() and reset().
  void set_color_by_size(bool by_size);
  bool color_by_size() const { return by_size_; }

  // The shown tet whose drawn face the ray meets first (the tet under the pointer:
  // camera.h pixel_ray()), and how far along the ray; tet kInvalidIndex if the ray
  // meets none. O(drawn faces).
  struct Pick {
    uint32_t tet = kInvalidIndex;
    double distance = std::numeric_limits<double>::infinity();
  };
  Pick pick(const Ray& ray) const;

  // The vertex ranges written since the last call, sorted and merged (the arrays may
  // also have shrunk; ranges are clamped to the current size). reset() marks all.
  std::vector<DirtyRange> take_triangle_dirty();
  std::vector<DirtyRange> take_highlight_dirty();

 private:
  struct FaceKey {
    uint32_t v[3];  // sorted
    bool operator==(const FaceKey& o) const {
      return v[0] == o.v[0] && v[1] == o.v[1] && v[2] == o.v[2];
    }
  };
  struct FaceEntry {
    uint32_t owners[2] = {kInvalidIndex, kInvalidIndex};  // 4 * tet + corner
    uint32_t slot = kInvalidIndex;                        // drawn slot, if drawn
  };
  // Face key -> entry. Entry pointers stay valid until the next insert or erase.
  class FaceTable {
   public:
    // `vertex_count` bounds the vertex ids: homes follow the smallest vertex id, so
    // faces of nearby vertices (the simplifier numbers them in Morton order) share
    // cache lines.
    void clear(size_t expected_faces, size_t vertex_count);
    const FaceEntry* find(const FaceKey& key) const;
    FaceEntry* find(const FaceKey& key) {
      return const_cast<FaceEntry*>(static_cast<const FaceTable*>(this)->find(key));
    }
    FaceEntry* insert(const FaceKey& key);  // finds, or adds an empty entry
    void erase(const FaceKey& key);
    // Splits the buckets into parts of at most `part_bytes` (at least 16 buckets
    // each), in order; their number. part() is then the part a key's home is in (until
    // the table grows).
    size_t parts(size_t part_bytes);
    size_t part(const FaceKey& key) const { return home(key) >> part_shift_; }
    // How many more entries it takes before it grows (at 70 % full); grow() makes room.
    size_t room() const {
      const size_t most = buckets_.size() * 7 / 10;
      return most > size_ ? most - size_ : 0;
    }
    void grow();

   private:
    struct Bucket {
      FaceKey key{{kInvalidIndex, kInvalidIndex, kInvalidIndex}};  // v[0] unset: empty
      FaceEntry entry;
    };
    size_t home(const FaceKey& k) const;
    std::vector<Bucket> buckets_;
    size_t mask_ = 0;
    size_t size_ = 0;
    uint64_t scale_ = 0;  // 2^32 * buckets / vertex_count
    int part_shift_ = 0;  // log2 of the buckets of a part
  };

  bool tet_visible(const LodState& state, uint32_t tet) const;
  void add_tet(const LodState& state, uint32_t tet);
  void remove_tet(uint32_t tet);
  void add_face(const FaceKey& key, uint32_t owner);
  void remove_face(const FaceKey& key, uint32_t owner);
  // Makes the face's drawn slot match its owner count.
  void refresh_face(const FaceKey& key, FaceEntry* entry);
  void write_face_slot(uint32_t slot, uint32_t owner);
  // Rewrites the scalar of every drawn slot from values_ (or stretch_ or size_ if empty).
  void rewrite_scalars();
  float scalar(uint32_t tet) const {
    return !values_.empty() ? values_[tet] : by_size_ ? size_[tet] : stretch_[tet];
  }
  void add_highlight(uint32_t tet);
  void remove_highlight(uint32_t tet);
  FaceKey face_key(uint32_t tet, int corner) const;
  // Dirty slots are collected and merged into ranges when taken.
  static std::vector<DirtyRange> take_ranges(std::vector<uint32_t>* slots, size_t slot_vertices,
                                             size_t vertex_count);

  SurfaceFilter filter_;
  MaterialSet hidden_;
  const LodState* state_ = nullptr;  // valid during reset()/update()

  // Per tet: whether it is in (visible), and the corners, stretch and material it
  // had when it was added (to remove its old faces after its corners change).
  std::vector<uint8_t> in_;
  std::vector<Tet> corners_;
  std::vector<float> stretch_;
  std::vector<float> size_;  // of each tet shown (in_): its longest edge
  bool by_size_ = false;
  std::vector<float> values_;  // set_tet_values(); empty: colour by stretch_
  std::vector<uint32_t> highlight_slot_;
  size_t visible_count_ = 0;

  FaceTable faces_;
  std::vector<SurfaceVertex> triangles_;
  std::vector<FaceKey> slot_keys_;                          // the face in each drawn slot
  std::vector<SurfaceVertex> highlight_;                    // 12 vertices per highlighted tet
  std::vector<uint32_t> highlight_tets_;                    // the tet in each highlight slot
  std::vector<uint32_t> triangle_dirty_, highlight_dirty_;  // slots
};

}  // namespace tetlod::render
