// Nastran bulk data (.bdf, .nas): GRID and CTETRA entries, after the MSC Nastran Quick
// Reference Guide, "Format of Bulk Data Entries": small field (8 characters), large
// field (16, the entry name ending in '*') and free field (commas), with continuation
// lines. The material of a tet is its property id (PID); CTRIA3/CTRIA6/CTRIAR are
// surface groups by their PID. Other entries are skipped.
#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <cstring>
#include <limits>
#include <map>
#include <string>

#include "core/io/mesh_formats.h"
#include "core/io/text_lines.h"
#include "core/io/text_scanner.h"
#include "core/io/text_writer.h"

namespace tetlod::io {
namespace {

// The comment that keeps material 0, which cannot be a Nastran PID, through a file.
constexpr std::string_view kMaterialZeroComment = "$ TetLOD material 0 = PID ";
// The comments that keep the names of materials and surface groups (Nastran has no
// place for a name): "$ material: the CTETRA with PID 3 are copper".
constexpr std::string_view kMaterialNameComment = "$ material: the CTETRA with PID ";
constexpr std::string_view kGroupNameComment = "$ surface group: the CTRIA3 with PID ";
constexpr std::string_view kNameSeparator = " are ";

bool equals_upper(std::string_view s, std::string_view upper) {
  if (s.size() != upper.size()) return false;
  for (size_t i = 0; i < s.size(); ++i) {
    const char c = s[i] >= 'a' && s[i] <= 'z' ? char(s[i] - 'a' + 'A') : s[i];
    if (c != upper[i]) return false;
  }
  return true;
}

bool starts_with_upper(std::string_view s, std::string_view upper) {
  return s.size() >= upper.size() && equals_upper(s.substr(0, upper.size()), upper);
}

struct PendingTet {
  int64_t element = 0;
  int64_t property = 0;
  int64_t grids[4] = {};
  int64_t mid_grids[6] = {};  // G5..G10 of a 10-node CTETRA (0: blank), checked only
  size_t line = 0;
};

// A CTRIA3, CTRIA6 or CTRIAR: its corners, and its PID, the surface group it is in.
struct PendingTriangle {
  int64_t element = 0;
  int64_t property = 0;
  int64_t grids[3] = {};
  size_t line = 0;
  std::string card;
};

class NastranParser {
 public:
  NastranParser(std::string_view text, const std::string& name, ParsedMesh* out)
      : text_(text), name_(name), out_(out) {}

  Status parse() {
    // Executive and case control come before BEGIN BULK; a file of bulk data alone
    // has none.
    bool in_bulk = !has_begin_bulk();
    bool ended = false;
    std::string_view line;
    while (!ended && next_line(&line)) {
      const std::string_view content = trim_blanks(line);
      if (content.empty()) continue;
      last_line_ = line_;
      if (content.front() == '$') {
        if (!read_comment(content)) return error_;
        continue;
      }
      if (!in_bulk) {
        in_bulk = starts_with_upper(content, "BEGIN BULK");
        continue;
      }
      expand_tabs(strip_comment(line), &expanded_);
      const std::string& expanded = expanded_;
      if (trim_blanks(expanded).empty()) continue;
      if (is_continuation(expanded)) {
        if (!card_open_) {
          fail(line_, "a continuation line without an entry before it");
          return error_;
        }
        add_fields(expanded, true);
        continue;
      }
      if (card_open_ && !finish_card()) return error_;
      if (equals_upper(trim_blanks(expanded), "ENDDATA")) {
        ended = true;
        break;
      }
      start_card(expanded);
    }
    if (card_open_ && !finish_card()) return error_;
    if (!ended) {
      return Status::error(name_ + ":" + std::to_string(last_line_) +
                           ": no ENDDATA entry (truncated file?); a complete file of bulk data "
                           "ends with ENDDATA");
    }
    if (!resolve()) return error_;
    if (blank_pids_ > 0)
      out_->notes.push_back(
          std::to_string(blank_pids_) + (blank_pids_ == 1 ? " CTETRA has" : " CTETRAs have") +
          " a blank or zero PID, not a property of Nastran's: read as material 0 (Nastran "
          "takes a blank PID as the element's id, which would make every such tet a material "
          "of its own)");
    if (quadratic_tets_ > 0) {
      out_->notes.push_back(std::to_string(quadratic_tets_) +
                            " 10-node CTETRAs were read as 4-node ones (by their corners; "
                            "their mid-side GRIDs are dropped)");
    }
    if (renamed_ > 0) {
      out_->notes.push_back((renamed_ == 1
                                 ? std::string("a comment gives a PID a second name")
                                 : std::to_string(renamed_) + " comments give PIDs second names") +
                            ", the last is taken (" + first_renamed_ + ")");
    }
    if (!skipped_solids_.empty()) {
      out_->notes.push_back("skipped the solid elements " + count_list(skipped_solids_) +
                            ": TetLOD reads CTETRA only, so a region meshed with other elements "
                            "is not in the mesh");
    }
    if (!skipped_others_.empty()) {
      out_->notes.push_back("skipped the elements " + count_list(skipped_others_) +
                            ": TetLOD keeps the CTETRAs, and the CTRIA3s of a PID as a surface "
                            "group");
    }
    return Status();
  }

 private:
  bool has_begin_bulk() const {
    size_t at = 0;
    while (at < text_.size()) {
      const size_t end = std::min(text_.find('\n', at), text_.size());
      if (starts_with_upper(trim_blanks(text_.substr(at, end - at)), "BEGIN BULK")) return true;
      at = end + 1;
    }
    return false;
  }

  bool next_line(std::string_view* line) { return next_text_line(text_, &pos_, &line_, line); }

  bool read_comment(std::string_view comment) {
    for (const bool material : {true, false}) {
      const std::string_view start = material ? kMaterialNameComment : kGroupNameComment;
      if (comment.substr(0, start.size()) != start) continue;
      // "$ ... PID 3 are copper": a comment that does not read so is only a comment.
      const std::string_view rest = comment.substr(start.size());
      const size_t separator = rest.find(kNameSeparator);
      int64_t pid = 0;
      if (separator == std::string_view::npos ||
          !parse_integer(trim_blanks(rest.substr(0, separator)), &pid) || pid < 1 ||
          pid > std::numeric_limits<int32_t>::max())
        return true;
      const std::string_view name = trim_blanks(rest.substr(separator + kNameSeparator.size()));
      if (!name.empty() && !(!material && name == "unnamed")) {
        std::string& kept = (material ? material_names_ : group_names_)[pid];
        if (!kept.empty() && kept != name && renamed_++ == 0) {
          first_renamed_ = "line " + std::to_string(line_) + " names " +
                           (material ? "material" : "surface group") + " PID " +
                           std::to_string(pid) + " '" + std::string(name) + "', named '" + kept +
                           "' before";
        }
        kept = std::string(name);
      }
      return true;
    }
    if (comment.substr(0, kMaterialZeroComment.size()) != kMaterialZeroComment) return true;
    const std::string_view value = trim_blanks(comment.substr(kMaterialZeroComment.size()));
    int64_t pid = 0;
    if (!parse_integer(value, &pid) || pid < 1) {
      return fail(line_, "the material 0 comment gives PID '" + std::string(value) +
                             "', not a positive integer");
    }
    zero_pid_ = pid;
    return true;
  }

  static std::string_view strip_comment(std::string_view line) {
    const size_t dollar = line.find('$');
    return dollar == std::string_view::npos ? line : line.substr(0, dollar);
  }

  // Tabs to the next multiple of 8 columns, as fixed-field entries are laid out.
  static void expand_tabs(std::string_view line, std::string* result) {
    result->clear();
    for (char c : line) {
      if (c == '\t') {
        result->append(8 - result->size() % 8, ' ');
      } else if (c != '\r') {
        result->push_back(c);
      }
    }
  }

  // '+' or '*' in column 1, or a blank first field (fixed: columns 1-8; free: a
  // leading comma).
  static bool is_continuation(const std::string& line) {
    if (line[0] == '+' || line[0] == '*' || line[0] == ',') return true;
    if (line.find(',') != std::string::npos)
      return trim_blanks(line.substr(0, line.find(','))).empty();
    return trim_blanks(std::string_view(line).substr(0, std::min<size_t>(8, line.size()))).empty();
  }

  void start_card(const std::string& line) {
    card_open_ = true;
    card_line_ = line_;
    field_count_ = 0;
    const bool free = line.find(',') != std::string::npos;
    std::string name(
        trim_blanks(free ? std::string_view(line).substr(0, line.find(','))
                         : std::string_view(line).substr(0, std::min<size_t>(8, line.size()))));
    large_ = !name.empty() && name.back() == '*';
    if (large_) name.pop_back();
    for (char& c : name) c = c >= 'a' && c <= 'z' ? char(c - 'a' + 'A') : c;
    card_name_ = name;
    add_fields(line, false);
  }

  // Appends the data fields of a line of the current entry. A line of a fixed-field
  // entry holds 8 fields (large field: 4); a free-field line as many as it has
  // commas, padded to 8 (4) when a continuation follows.
  void add_fields(const std::string& line, bool continuation) {
    const size_t per_line = large_ ? 4 : 8;
    while (continuation && field_count_ % per_line != 0) push_field({});
    if (line.find(',') != std::string::npos) {
      size_t at = line.find(',') + 1;
      while (true) {
        const size_t comma = line.find(',', at);
        const size_t end = comma == std::string::npos ? line.size() : comma;
        push_field(trim_blanks(std::string_view(line).substr(at, end - at)));
        if (comma == std::string::npos) break;
        at = comma + 1;
      }
      // A free-field line ending in a comma has no further field.
      if (field_count_ > 0 && fields_[field_count_ - 1].empty() && line.back() == ',') {
        --field_count_;
      }
      return;
    }
    const size_t width = large_ ? 16 : 8;
    for (size_t k = 0; k < per_line; ++k) {
      const size_t start = 8 + k * width;
      push_field(start < line.size() ? trim_blanks(std::string_view(line).substr(start, width))
                                     : std::string_view());
    }
  }

  void push_field(std::string_view text) {
    if (field_count_ == fields_.size()) fields_.emplace_back();
    fields_[field_count_++].assign(text.data(), text.size());
  }

  const std::string& field(size_t k) const {
    static const std::string empty;
    return k < field_count_ ? fields_[k] : empty;
  }

  static bool parse_integer(std::string_view s, int64_t* value) {
    if (!s.empty() && s.front() == '+') s.remove_prefix(1);
    const auto r = std::from_chars(s.data(), s.data() + s.size(), *value);
    return !s.empty() && r.ec == std::errc() && r.ptr == s.data() + s.size();
  }

  // A Nastran real: "1.5", "1.", ".5", "-2.E3", "1.5D-3" and the short forms
  // without the E, "1.5-3" (1.5e-3) and "1.5+3".
  static bool parse_real(std::string_view s, double* value) {
    if (s.empty() || s.size() > 40) return false;
    char buffer[2 * 40];  // an 'E' may go before every sign
    size_t n = 0;
    for (size_t i = 0; i < s.size(); ++i) {
      char c = s[i];
      if (c == 'd' || c == 'D' || c == 'e') c = 'E';
      if ((c == '+' || c == '-') && i > 0 && buffer[n - 1] != 'E') buffer[n++] = 'E';
      buffer[n++] = c;
    }
    const char* begin = buffer[0] == '+' ? buffer + 1 : buffer;
    const auto r = std::from_chars(begin, buffer + n, *value);
    return r.ec == std::errc() && r.ptr == buffer + n && std::isfinite(*value);
  }

  bool integer_field(size_t k, const char* what, int64_t min_value, int64_t* value) {
    if (!parse_integer(field(k), value) || *value < min_value) {
      return fail(card_line_, card_name_ + " " + field(0) + ": " + what + " '" + field(k) +
                                  "' is not an integer >= " + std::to_string(min_value));
    }
    return true;
  }

  bool finish_card() {
    card_open_ = false;
    if (card_name_ == "GRID") return grid();
    if (card_name_ == "CTETRA") return ctetra();
    if (card_name_ == "CTRIA3" || card_name_ == "CTRIA6" || card_name_ == "CTRIAR") return ctria();
    if (card_name_ == "CQUAD4" || card_name_ == "CQUAD8" || card_name_ == "CQUADR") {
      ++quads_;
      return true;
    }
    if (card_name_ == "CHEXA" || card_name_ == "CPENTA" || card_name_ == "CPYRAM" ||
        card_name_ == "CPYRA") {
      ++skipped_solids_[card_name_];
      return true;
    }
    // Line, point, spring, mass and rigid elements: not kept, said in a note.
    for (const char* card :
         {"CBAR",   "CBEAM",  "CBEND",  "CROD",  "CONROD", "CTUBE",   "CBUSH",  "CBUSH1D", "CGAP",
          "CVISC",  "CSHEAR", "CWELD",  "CFAST", "CELAS1", "CELAS2",  "CELAS3", "CELAS4",  "CDAMP1",
          "CDAMP2", "CDAMP3", "CDAMP4", "CONM1", "CONM2",  "CMASS1",  "CMASS2", "CMASS3",  "CMASS4",
          "RBE1",   "RBE2",   "RBE3",   "RBAR",  "RROD",   "RSPLINE", "RTRPLT", "PLOTEL"}) {
      if (card_name_ == card) {
        ++skipped_others_[card_name_];
        return true;
      }
    }
    if (card_name_ == "INCLUDE") {
      return fail(card_line_,
                  "INCLUDE is not followed: read the included file instead, or "
                  "paste it in");
    }
    return true;
  }

  bool grid() {
    int64_t id = 0, system = 0;
    if (!integer_field(0, "id", 1, &id)) return false;
    if (!field(1).empty() && (!parse_integer(field(1), &system) || system != 0)) {
      return fail(card_line_, "GRID " + field(0) + ": coordinate system '" + field(1) +
                                  "' is not supported (only the basic system, 0 or blank)");
    }
    Vec3 p;
    const char* names[3] = {"x", "y", "z"};
    for (int k = 0; k < 3; ++k) {
      double& value = k == 0 ? p.x : k == 1 ? p.y : p.z;
      if (field(2 + k).empty()) continue;  // blank: 0.0
      if (!parse_real(field(2 + k), &value)) {
        return fail(card_line_, "GRID " + field(0) + ": " + names[k] + " coordinate '" +
                                    field(2 + k) + "' is not a finite number");
      }
    }
    if (out_->mesh.positions.size() + 1 >= kInvalidIndex) return fail(card_line_, "too many GRIDs");
    out_->mesh.positions.push_back(p);
    grid_ids_.push_back(id);
    grid_lines_.push_back(line_number(card_line_));
    return true;
  }

  // The GRID id lookup; fails on an id defined twice.
  bool index_grids() {
    const size_t count = grid_ids_.size();
    std::vector<uint32_t> order(count);
    for (uint32_t i = 0; i < count; ++i) order[i] = i;
    std::stable_sort(order.begin(), order.end(),
                     [&](uint32_t a, uint32_t b) { return grid_ids_[a] < grid_ids_[b]; });
    for (size_t i = 1; i < count; ++i) {
      if (grid_ids_[order[i]] == grid_ids_[order[i - 1]]) {
        return fail(grid_lines_[order[i]],
                    "GRID " + std::to_string(grid_ids_[order[i]]) + " is defined twice");
      }
    }
    if (count == 0) return true;
    first_id_ = grid_ids_[order.front()];
    const uint64_t span = uint64_t(grid_ids_[order.back()] - first_id_);
    if (span < 4 * uint64_t(count) + 1024) {
      dense_index_.assign(span + 1, kInvalidIndex);
      for (uint32_t v = 0; v < count; ++v) dense_index_[grid_ids_[v] - first_id_] = v;
    } else {
      sorted_.resize(count);
      for (size_t i = 0; i < count; ++i) sorted_[i] = {grid_ids_[order[i]], order[i]};
    }
    return true;
  }

  // Fails on a CTETRA id given twice, as on a GRID's.
  bool unique_elements() {
    std::vector<uint32_t> order(tets_.size());
    for (uint32_t i = 0; i < order.size(); ++i) order[i] = i;
    std::stable_sort(order.begin(), order.end(),
                     [&](uint32_t a, uint32_t b) { return tets_[a].element < tets_[b].element; });
    for (size_t i = 1; i < order.size(); ++i)
      if (tets_[order[i]].element == tets_[order[i - 1]].element)
        return fail(tets_[order[i]].line,
                    "CTETRA " + std::to_string(tets_[order[i]].element) + " is defined twice");
    return true;
  }

  uint32_t find_grid(int64_t id) const {
    if (!dense_index_.empty()) {
      const uint64_t key = uint64_t(id - first_id_);
      return id >= first_id_ && key < dense_index_.size() ? dense_index_[key] : kInvalidIndex;
    }
    const auto it =
        std::lower_bound(sorted_.begin(), sorted_.end(), std::make_pair(id, uint32_t(0)));
    return it != sorted_.end() && it->first == id ? it->second : kInvalidIndex;
  }

  bool ctetra() {
    PendingTet t;
    t.line = card_line_;
    if (!integer_field(0, "element id", 1, &t.element)) return false;
    // A blank PID is material 0. (Nastran would take the element id, which would
    // give every tet a material of its own; writers such as meshio leave it blank
    // when a mesh has no properties.)
    if (!field(1).empty() && !integer_field(1, "property id (PID)", 0, &t.property)) return false;
    if (t.property > std::numeric_limits<int32_t>::max()) {
      return fail(card_line_,
                  "CTETRA " + field(0) + ": PID " + field(1) + " is too large for a material id");
    }
    for (int k = 0; k < 4; ++k) {
      if (!integer_field(2 + k, "grid", 1, &t.grids[k])) return false;
    }
    // G5..G10, the mid-side grids (any may be blank): read by the corners, but each
    // given must be a GRID, as a corner must.
    bool quadratic = false;
    for (int k = 0; k < 6; ++k) {
      if (field(6 + k).empty()) continue;
      if (!integer_field(6 + k, "grid", 1, &t.mid_grids[k])) return false;
      quadratic = true;
    }
    if (tets_.size() + 1 >= kInvalidIndex) return fail(card_line_, "too many CTETRAs");
    tets_.push_back(t);
    quadratic_tets_ += quadratic;
    blank_pids_ += t.property == 0;
    return true;
  }

  // A surface element: kept in the surface group of its PID when that is >= 1 (as a
  // group tag must be; blank is 0: in none).
  bool ctria() {
    PendingTriangle t;
    t.line = card_line_;
    t.card = card_name_;
    if (!integer_field(0, "element id", 1, &t.element)) return false;
    if (!field(1).empty() && !integer_field(1, "property id (PID)", 0, &t.property)) return false;
    for (int k = 0; k < 3; ++k) {
      if (!integer_field(2 + k, "grid", 1, &t.grids[k])) return false;
    }
    if (triangles_.size() + 1 >= kInvalidIndex) return fail(card_line_, "too many " + t.card + "s");
    triangles_.push_back(std::move(t));
    return true;
  }

  // GRIDs may come after the CTETRAs that use them: corners are resolved at the end.
  bool resolve() {
    if (!index_grids() || !unique_elements()) return false;
    out_->mesh.tets.reserve(tets_.size());
    out_->mesh.materials.reserve(tets_.size());
    out_->tet_lines.reserve(tets_.size());
    for (const PendingTet& t : tets_) {
      Tet tet;
      for (int k = 0; k < 4; ++k) {
        tet[k] = find_grid(t.grids[k]);
        if (tet[k] == kInvalidIndex) {
          return fail(t.line, "CTETRA " + std::to_string(t.element) + " uses GRID " +
                                  std::to_string(t.grids[k]) + ", which is not defined");
        }
      }
      for (const int64_t g : t.mid_grids)
        if (g != 0 && find_grid(g) == kInvalidIndex)
          return fail(t.line, "CTETRA " + std::to_string(t.element) + " uses GRID " +
                                  std::to_string(g) + " (a mid-side node), which is not defined");
      out_->mesh.tets.push_back(tet);
      out_->mesh.materials.push_back(t.property == zero_pid_ ? 0 : int32_t(t.property));
      out_->tet_lines.push_back(line_number(t.line));
    }
    // The surface elements, kept only as groups (the CLI says so).
    SurfaceElements surface;
    surface.count(quads_);
    for (const PendingTriangle& t : triangles_) {
      surface.count();
      std::array<Vec3, 3> corners;
      for (int k = 0; k < 3; ++k) {
        const uint32_t v = find_grid(t.grids[k]);
        if (v == kInvalidIndex) {
          return fail(t.line, t.card + " " + std::to_string(t.element) + " uses GRID " +
                                  std::to_string(t.grids[k]) + ", which is not defined");
        }
        corners[size_t(k)] = out_->mesh.positions[v];
      }
      if (t.property >= 1 && t.property <= std::numeric_limits<int32_t>::max())
        surface.add_triangle(int32_t(t.property), corners[0], corners[1], corners[2]);
    }
    surface.finish(out_);
    // The names the comments gave (of materials present; material 0 by its PID).
    for (InputSurfaceGroup& group : out_->surface_groups) {
      if (auto it = group_names_.find(group.tag); it != group_names_.end()) group.name = it->second;
    }
    if (!material_names_.empty()) {
      std::vector<int32_t> present = out_->mesh.materials;
      std::sort(present.begin(), present.end());
      present.erase(std::unique(present.begin(), present.end()), present.end());
      for (const int32_t m : present) {
        auto it = material_names_.find(m == 0 ? zero_pid_ : m);
        if (it != material_names_.end()) out_->material_names.push_back({m, it->second});
      }
    }
    return true;
  }

  bool fail(size_t line, const std::string& message) {
    if (!failed_) {
      failed_ = true;
      error_ = Status::error(name_ + ":" + std::to_string(line) + ": " + message);
    }
    return false;
  }

  std::string_view text_;
  const std::string& name_;
  ParsedMesh* out_;
  size_t pos_ = 0;
  size_t line_ = 0;
  size_t last_line_ = 0;  // the last line that is not blank
  bool failed_ = false;
  Status error_;
  // The entry being read.
  bool card_open_ = false;
  bool large_ = false;
  size_t card_line_ = 0;
  std::string card_name_;
  std::vector<std::string> fields_;  // the first field_count_ are the entry's (reused)
  size_t field_count_ = 0;
  std::string expanded_;  // the current line, tabs expanded
  std::vector<PendingTriangle> triangles_;
  uint64_t quads_ = 0;                // CQUAD4, CQUAD8, CQUADR entries
  uint64_t quadratic_tets_ = 0;       // 10-node CTETRAs, read by their corners
  uint64_t blank_pids_ = 0;           // CTETRAs with a blank or zero PID (material 0)
  std::vector<int64_t> grid_ids_;     // per vertex, in file order
  std::vector<uint32_t> grid_lines_;  // per vertex
  int64_t first_id_ = 0;
  std::vector<uint32_t> dense_index_;                 // id - first_id_ -> vertex, when compact
  std::vector<std::pair<int64_t, uint32_t>> sorted_;  // (id, vertex), else
  std::vector<PendingTet> tets_;
  int64_t zero_pid_ = -1;
  std::map<int64_t, std::string> material_names_, group_names_;  // by PID, from comments
  size_t renamed_ = 0;                            // comments naming a PID named otherwise before
  std::string first_renamed_;                     // the first of them, for the note
  std::map<std::string, size_t> skipped_solids_;  // CHEXA, CPENTA, CPYRAM entries
  std::map<std::string, size_t> skipped_others_;  // CBAR, CONM2, RBE2 ... entries
};

// `value` in at most 16 characters as a Nastran real (with a decimal point): exact
// when the shortest exact form fits, else with as many digits as fit.
std::string nastran_real(double value) {
  for (int precision = 0; precision <= 17; ++precision) {
    char buffer[40];
    const auto r = precision == 0 ? std::to_chars(buffer, buffer + sizeof buffer, value)
                                  : std::to_chars(buffer, buffer + sizeof buffer, value,
                                                  std::chars_format::general, 17 - precision + 1);
    std::string s(buffer, r.ptr);
    // Upper-case exponent without leading zeros; a decimal point in the mantissa.
    size_t e = s.find('e');
    std::string exponent;
    if (e != std::string::npos) {
      std::string digits = s.substr(e + 2);
      digits.erase(0, std::min(digits.find_first_not_of('0'), digits.size() - 1));
      exponent = std::string("E") + s[e + 1] + digits;
      s.resize(e);
    }
    if (s.find('.') == std::string::npos) s += '.';
    s += exponent;
    if (s.size() <= 16) return s;
  }
  return "0.";  // not reached: 9 significant digits always fit
}

void append_field(std::string* out, std::string_view text, size_t width) {
  out->append(text);
  if (text.size() < width) out->append(width - text.size(), ' ');
}

}  // namespace

Status parse_nastran(std::string_view text, const std::string& name, ParsedMesh* out) {
  NastranParser parser(text, name, out);
  return parser.parse();
}

void write_nastran(const TetMesh& mesh, const SurfaceGroups* surfaces,
                   const std::vector<MaterialName>* names, std::string* out) {
  // Material m > 0 is PID m; material 0 (no PID can be 0) the smallest unused PID,
  // named in a comment that TetLOD reads back.
  std::vector<int32_t> materials = mesh.materials;
  std::sort(materials.begin(), materials.end());
  materials.erase(std::unique(materials.begin(), materials.end()), materials.end());
  int64_t zero_pid = 1;
  for (int32_t m : materials)
    if (m == zero_pid) ++zero_pid;
  const bool has_zero = !materials.empty() && materials.front() == 0;
  size_t triangle_count = 0;
  int64_t largest_tag = 0;
  if (surfaces) {
    for (const SurfaceGroup& group : surfaces->groups) {
      triangle_count += group.triangles.size();
      largest_tag = std::max<int64_t>(largest_tag, group.tag);
    }
  }

  out->reserve(out->size() + mesh.vertex_count() * 82 + mesh.tet_count() * 50 +
               triangle_count * 42);
  out->append("$ Nastran bulk data written by TetLOD: ");
  append_number(out, mesh.vertex_count());
  out->append(" GRID, ");
  append_number(out, mesh.tet_count());
  out->append(" CTETRA");
  if (surfaces) {
    out->append(", ");
    append_number(out, triangle_count);
    out->append(" CTRIA3");
  }
  out->append("; the PID of a CTETRA is its material");
  if (surfaces) out->append(", of a CTRIA3 its surface group");
  out->push_back('\n');
  if (has_zero) {
    out->append(kMaterialZeroComment);
    append_number(out, zero_pid);
    out->push_back('\n');
  }
  // A name on one line of a comment: control characters become '_'.
  const auto append_name = [out](const std::string& name) {
    for (const char c : name) out->push_back(static_cast<unsigned char>(c) < 0x20 ? '_' : c);
    out->push_back('\n');
  };
  // The materials' names in comments, read back by TetLOD.
  if (names) {
    for (const MaterialName& n : *names) {
      if (!std::binary_search(materials.begin(), materials.end(), n.material)) continue;
      out->append(kMaterialNameComment);
      append_number(out, n.material == 0 ? zero_pid : int64_t{n.material});
      out->append(kNameSeparator);
      append_name(n.name);
    }
  }
  // The surface groups, as Gmsh's Nastran export writes physical surfaces: a CTRIA3
  // per triangle, after the CTETRAs, with the group's tag as its PID (which no
  // material's PID reaches: first_surface_tag()). The names go in comments.
  if (surfaces) {
    for (const SurfaceGroup& group : surfaces->groups) {
      out->append(kGroupNameComment);
      append_number(out, group.tag);
      out->append(kNameSeparator);
      append_name(group.name.empty() ? "unnamed" : group.name);
    }
  }
  // The bulk data section's opening line: a file of bulk data alone does not need it,
  // but meshio (5.0) reads nothing without it, and Gmsh and TetLOD skip it.
  out->append("BEGIN BULK\n");
  // GRID* (large field): ID, CP, X1, X2, then X3 on the continuation line.
  for (size_t v = 0; v < mesh.vertex_count(); ++v) {
    const Vec3& p = mesh.positions[v];
    out->append("GRID*   ");
    append_field(out, std::to_string(v + 1), 16);
    append_field(out, "", 16);
    append_field(out, nastran_real(p.x), 16);
    out->append(nastran_real(p.y));
    out->append("\n*       ");
    out->append(nastran_real(p.z));
    out->push_back('\n');
  }
  // Elements in small field when every id fits in 8 characters, else large field.
  const bool small = mesh.vertex_count() < 100000000 &&
                     mesh.tet_count() + triangle_count < 100000000 &&
                     (materials.empty() || materials.back() < 100000000) && zero_pid < 100000000 &&
                     largest_tag < 100000000;
  // An element: its name, then its ids (EID, PID, grids; 5 or 6). In large field,
  // four to a line, the rest on a continuation line.
  auto element = [&](const char* name, const std::string* ids, int count) {
    out->append(name);
    if (small) {
      out->append(8 - std::strlen(name), ' ');
      for (int k = 0; k + 1 < count; ++k) append_field(out, ids[k], 8);
    } else {
      out->push_back('*');
      out->append(7 - std::strlen(name), ' ');
      for (int k = 0; k < 3; ++k) append_field(out, ids[k], 16);
      out->append(ids[3]);
      out->append("\n*       ");
      for (int k = 4; k + 1 < count; ++k) append_field(out, ids[k], 16);
    }
    out->append(ids[count - 1]);
    out->push_back('\n');
  };
  for (size_t t = 0; t < mesh.tet_count(); ++t) {
    const Tet& tet = mesh.tets[t];
    const int64_t pid = mesh.materials[t] == 0 ? zero_pid : mesh.materials[t];
    const std::string ids[6] = {std::to_string(t + 1),      std::to_string(pid),
                                std::to_string(tet[0] + 1), std::to_string(tet[1] + 1),
                                std::to_string(tet[2] + 1), std::to_string(tet[3] + 1)};
    element("CTETRA", ids, 6);
  }
  if (surfaces) {
    size_t eid = mesh.tet_count();
    for (const SurfaceGroup& group : surfaces->groups) {
      for (uint32_t i : group.triangles) {
        const auto& v = surfaces->surface[i].v;
        const std::string ids[5] = {std::to_string(++eid), std::to_string(group.tag),
                                    std::to_string(v[0] + 1), std::to_string(v[1] + 1),
                                    std::to_string(v[2] + 1)};
        element("CTRIA3", ids, 5);
      }
    }
  }
  out->append("ENDDATA\n");
}

}  // namespace tetlod::io
