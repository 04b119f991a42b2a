// Level of detail (paper, section IV.B): the recorded collapse history and an Lod
// object that moves a mesh to any step of it by edge collapses and vertex splits.
//
// Vertex and tet ids are those of the base mesh (the mesh the simplifier started
// from, after subdivision) at every step: a collapse (i, j) -> k keeps vertex i at
// k's position, retires vertex j, retires the tets around edge (i, j) and rewires
// the corners of j's other tets to i. A vertex split does the reverse. Applying
// then undoing steps gives a bit-identical mesh.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "core/io/output_files.h"
#include "core/status.h"
#include "core/surface.h"
#include "core/tet_mesh.h"

namespace tetlod {

struct SimplifyParams;  // simplify.h

struct CollapseHistory {
  struct Step {
    uint32_t kept = 0;     // vertex i, moved to new_position
    uint32_t removed = 0;  // vertex j, retired
    Vec3 old_position;     // i's position before the collapse
    Vec3 new_position;     // k
    // Ranges [begin of this step, begin of the next step) in the flat arrays below.
    uint32_t removed_begin = 0;
    uint32_t rewired_begin = 0;
    uint32_t moved_begin = 0;
    uint32_t reserved = 0;  // keeps the struct free of padding (it is written to files raw)
  };
  std::vector<Step> steps;
  std::vector<uint32_t> removed_tets;  // tets around edge (i, j)
  std::vector<uint32_t> rewired;       // 4 * tet + corner: the corner held j, now holds i
  std::vector<uint32_t> moved;         // surviving tets that held i (their shape changed)

  size_t step_count() const { return steps.size(); }
  // Ends of the ranges of step s.
  uint32_t removed_end(size_t s) const;
  uint32_t rewired_end(size_t s) const;
  uint32_t moved_end(size_t s) const;
  // Appends a step; the arrays' current sizes are its range begins.
  void begin_step(uint32_t kept, uint32_t removed, const Vec3& old_position,
                  const Vec3& new_position);
};

// What a move between steps changed, for incremental rendering. Lists are sorted
// and unique; a tet is in at most one of them.
struct LodDelta {
  std::vector<uint32_t> appeared;  // alive now, not before
  std::vector<uint32_t> vanished;  // alive before, not now
  std::vector<uint32_t> changed;   // alive before and now, with other corners or positions
};

class Lod {
 public:
  // `base` is the mesh at step 0; `history` must outlive the Lod and belong to it.
  Lod(TetMesh base, const CollapseHistory* history);

  size_t step() const { return step_; }
  size_t step_count() const { return history_->step_count(); }
  size_t alive_tet_count() const { return alive_tet_count_; }
  // Number of tets alive after `step` collapses (O(1)).
  size_t tet_count_at(size_t step) const { return tets_at_step_[step]; }
  // The step whose tet count is nearest to `elements` (the earliest on ties).
  size_t step_for_elements(size_t elements) const;

  // Moves to `step` (clamped to [0, step_count()]) by collapses or splits. If `delta`
  // is given it receives what changed relative to the step before the call.
  void seek(size_t step, LodDelta* delta = nullptr);

  // The mesh at the current step, compacted: alive tets and the vertices they use,
  // in id order.
  TetMesh extract() const;

  // The current step as the uncompacted base arrays (retired tets keep their last
  // corners and are flagged in alive()).
  const std::vector<Vec3>& positions() const { return mesh_.positions; }
  const std::vector<Tet>& tets() const { return mesh_.tets; }
  const std::vector<int32_t>& materials() const { return mesh_.materials; }
  const std::vector<uint8_t>& alive() const { return alive_; }

 private:
  void apply(size_t s);
  void undo(size_t s);

  TetMesh mesh_;
  const CollapseHistory* history_;
  std::vector<uint8_t> alive_;
  std::vector<size_t> tets_at_step_;
  size_t alive_tet_count_ = 0;
  size_t step_ = 0;
  // Scratch for seek() with a delta.
  std::vector<uint32_t> touched_stamp_;
  std::vector<uint8_t> alive_before_;
  std::vector<uint32_t> touched_;
  uint32_t stamp_ = 0;
};

// The alive tets and the vertices they use, compacted in id order.
TetMesh extract_alive(const std::vector<Vec3>& positions, const std::vector<Tet>& tets,
                      const std::vector<int32_t>& materials, const std::vector<uint8_t>& alive);

// A saved simplification: the base mesh and its history, so that any level can be
// written later without simplifying again. Binary, little-endian, versioned; the
// reader checks every count and index (a hostile file gives an error, never a crash),
// and replays the steps once to check that they are collapses of the base mesh that
// leave every tet positive, so every level of an accepted history is made of
// positive tets (not that they never overlap: a forged file can still do that). The
// file ends with a block holding the checksum of every byte before it
// (history_checksum()), so a file cut or changed anywhere is refused (files written
// before 2026-11-29 end with their length instead, those before 2026-11-24 with
// nothing; both still read).
// `params`, if given: the thresholds the history was made with (all but
// target_elements, which is about a level), saved after it so that a level can be
// improved later within them (improve.h) without the user giving them again; a size
// map among them (sizing.h) is saved as what it was built from (SizeMap::source(),
// sizes()), from which the reader builds the same map.
// `names`, if given and not empty: the input file's names of the materials (sorted,
// each of a material the base has), saved next, so that levels written later
// carry them. `patches`, if given and any() (or with inside_entries()): the input
// file's surface groups the run kept (simplify()), saved last, so that levels written
// later can be grouped as the input was.
Status write_history(const std::string& path, const TetMesh& base, const CollapseHistory& history,
                     const SimplifyParams* params = nullptr,
                     const std::vector<MaterialName>* names = nullptr,
                     const SurfacePatches* patches = nullptr);
// The same, staged in `files` to be committed with the other outputs of a command.
Status stage_history(OutputFiles* files, const std::string& path, const TetMesh& base,
                     const CollapseHistory& history, const SimplifyParams* params = nullptr,
                     const std::vector<MaterialName>* names = nullptr,
                     const SurfacePatches* patches = nullptr);
// `params`, if given, receives the saved thresholds, or nullopt for a history saved
// without them (as every one before 2026-11-24 was); saved thresholds that
// check_params() refuses, a saved size map that SizeMap::build() refuses (or, as
// saved before 2026-11-28, not a size > 0 at each of the base's vertices), or any
// byte after them, make the file corrupt. `names`, if
// given, receives the saved material names (empty if none); a name list out of
// order, of a material the base does not have, or with an empty or over-long name
// makes the file corrupt. `patches`, if given, receives the saved surface groups (none:
// !any()); a damaged block of them makes the file corrupt. An error for a file of
// format 2 or 3 also says whether it ends with its end block and (3) whether its
// checksum matches. `format`, if given, receives the file's format (1 to 3; 0 if it is
// none): formats 1 and 2 have no checksum.
Status read_history(const std::string& path, TetMesh* base, CollapseHistory* history,
                    std::optional<SimplifyParams>* params = nullptr,
                    std::vector<MaterialName>* names = nullptr, SurfacePatches* patches = nullptr,
                    int* format = nullptr);
// The checksum a history file's end block holds: of `bytes`, the file up to it (for
// tests and fuzzers that forge histories: a file changed by hand must be sealed again).
// A 64-bit hash, one to one on each 8-byte word, so a change of one word is always
// found; not a defence against a forger, only against damage.
uint64_t history_checksum(std::string_view bytes);
// What to tell the user of a history read with `format` < 3 (no checksum), "a history
// of format 1 ..."; empty for format 3.
std::string unchecked_history_note(int format);

}  // namespace tetlod
