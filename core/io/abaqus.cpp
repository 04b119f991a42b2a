// Abaqus / CalculiX input (.inp): *NODE and *ELEMENT of the tetrahedral types
// (C3D4, C3D10 and their variants: DC3D4, C3D10M, EMC3D4 ...), element sets
// (*ELEMENT's ELSET, *ELSET with or without GENERATE) and *SOLID SECTION, after the
// Abaqus Keywords Reference. A flat input or one with a single *PART. The material
// of a tet: the section that covers it (by material name), else the first *ELSET
// holding it (Gmsh writes its physical groups so; not an INTERNAL one, which Abaqus/CAE
// makes for surfaces), else its *ELEMENT's ELSET, else 0; a set holding every tet
// ("Eall") comes last, after the *ELEMENT's ELSET, when other sets tell tets apart;
// a name ending in digits is that number ("material_7", "Volume2") unless an earlier
// name has it ("Rotor1" then "Stator1"), other names get the next free numbers in
// order of appearance.
//
// Surface groups (ParsedMesh::surface_groups): each element-based *SURFACE
// (TYPE=ELEMENT, the default) whose data lines read "element or element set, Sn"
// is a group named after the surface, tagged in the order of the file from the
// largest material number on (M + 1, M + 2, ...: GetDP, which reads the .msh files made
// from them, numbers volume and surface regions alike; a name given again adds to the
// first). Tet faces, as the Abaqus and CalculiX manuals
// number them: S1 = nodes 1-2-3, S2 = 1-4-2, S3 = 2-4-3, S4 = 3-4-1 (C3D10: the
// same corners). A "** TetLOD surface <X>_FACES <tag> <name>" comment (written by
// TetLOD) gives the group of *SURFACE <X>_FACES its tag (even a material's number)
// and name back (an earlier group's tag is replaced, with a note); else a
// surface <X>_FACES is named X when the file has a node set X and
// no surface X: TetLOD writes each group as *NSET X and *SURFACE X_FACES, so that a
// file written from one read back keeps the names. Faces of elements that are not
// tetrahedra are dropped with a note; node surfaces (TYPE=NODE), COMBINE and CROP
// surfaces, a data line without a face (all exposed faces), and a reference to an
// element or set that is not there (or a face a tet does not have) skip their surface
// with a note. Then each *ELSET holding triangle elements (CPS3, S3, ...: Gmsh's .inp
// export writes a physical surface so) is a group named after it, or, without such
// sets, each triangle *ELEMENT block's ELSET.
#include <algorithm>
#include <array>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstring>
#include <limits>
#include <map>
#include <set>
#include <unordered_map>
#include <unordered_set>

#include "core/io/mesh_formats.h"
#include "core/io/text_lines.h"
#include "core/io/text_writer.h"

namespace tetlod::io {
namespace {

std::string upper(std::string_view s) {
  std::string u(s);
  for (char& c : u) c = c >= 'a' && c <= 'z' ? char(c - 'a' + 'A') : c;
  return u;
}

// The corners (0-based) of the faces S1 to S4 of a C3D4 (and of a C3D10's corners),
// after the Abaqus and CalculiX manuals: S1 = nodes 1-2-3, S2 = 1-4-2, S3 = 2-4-3,
// S4 = 3-4-1.
constexpr int kAbaqusTetFace[4][3] = {{0, 1, 2}, {0, 3, 1}, {1, 3, 2}, {2, 3, 0}};

std::vector<std::string_view> split_commas(std::string_view line) {
  std::vector<std::string_view> parts;
  size_t at = 0;
  while (true) {
    const size_t comma = line.find(',', at);
    parts.push_back(trim_blanks(
        line.substr(at, comma == std::string_view::npos ? std::string_view::npos : comma - at)));
    if (comma == std::string_view::npos) break;
    at = comma + 1;
  }
  return parts;
}

// The nodes of a tet element type (4 or 10), 0 for any other type.
int tet_nodes(const std::string& type) {
  const size_t at = type.find("3D");
  if (at == std::string::npos || at == 0) return 0;
  const std::string_view rest = std::string_view(type).substr(at + 2);
  if (rest.substr(0, 2) == "10") return 10;
  if (rest.substr(0, 1) == "4" && (rest.size() == 1 || !std::isdigit(uint8_t(rest[1])))) return 4;
  return 0;
}

// Whether an element type is a triangle (plane, shell, membrane, surface or rigid
// elements of 3 or 6 nodes: Gmsh writes a physical surface's triangles as CPS3 or
// CPS6 in an *ELSET named after it): its first three nodes are its corners.
bool is_triangle_type(const std::string& type) {
  for (const char* t :
       {"CPS3",  "CPE3", "CAX3", "S3",   "S3R",   "STRI3",  "M3D3", "SFM3D3", "R3D3",
        "DS3",   "CPS6", "CPE6", "CAX6", "S6",    "STRI65", "M3D6", "SFM3D6", "DC2D3",
        "DC2D6", "S3RS", "S3T",  "S3RT", "CPS3T", "CPE3T",  "DS6"})
    if (type == t) return true;
  return false;
}

struct Keyword {
  std::string name;                            // upper case, without '*'
  std::map<std::string, std::string> options;  // upper-case keys; values as written
  bool has(const char* key) const { return options.count(key) > 0; }
  std::string get(const char* key) const {
    const auto it = options.find(key);
    return it == options.end() ? std::string() : it->second;
  }
};

// The comment line TetLOD writes for each named material: "** TetLOD material
// <set> <id> <name>", its name as given, which the set's label may not spell.
constexpr const char* kMaterialNameComment = "** TetLOD material ";
// And for each surface group: "** TetLOD surface <surface> <tag> <name>", its tag and
// its name as given (Abaqus labels hold no blanks, and have no tags).
constexpr const char* kSurfaceNameComment = "** TetLOD surface ";

class AbaqusParser {
 public:
  AbaqusParser(std::string_view text, const std::string& name, ParsedMesh* out)
      : text_(text), name_(name), out_(out) {}

  Status parse() {
    std::string_view line;
    Keyword keyword;
    bool have_keyword = false;
    while (next_line(&line)) {
      const std::string_view content = trim_blanks(line);
      if (content.substr(0, 2) == "**") {
        read_name_comment(content);
        continue;
      }
      if (content.empty()) continue;
      if (content.front() == '*') {
        read_keyword(content, &keyword);
        have_keyword = true;
        if (!start(keyword)) return error_;
        continue;
      }
      if (!have_keyword) {
        fail(line_, "data before the first keyword line: not an Abaqus input");
        return error_;
      }
      // A data line ending in a comma goes on to the next line.
      std::string record(content);
      const size_t first_line = line_;
      // (Gmsh ends every line of a set with a comma: never into a keyword line. A
      // node's line and a surface's line are one record each; CalculiX takes a node
      // line's trailing comma.)
      while (!record.empty() && record.back() == ',' && mode_ != Mode::kSkip &&
             mode_ != Mode::kSurface && mode_ != Mode::kNodes) {
        const size_t saved_pos = pos_, saved_line = line_;
        std::string_view more;
        if (!next_line(&more)) break;
        more = trim_blanks(more);
        if (!more.empty() && more.front() == '*') {
          pos_ = saved_pos, line_ = saved_line;
          break;
        }
        record += std::string(more);
      }
      if (!data(record, first_line)) return error_;
    }
    if (!resolve() || !resolve_surfaces()) return error_;
    ignored_comments_note();
    if (quadratic_tets_ > 0) {
      out_->notes.push_back(std::to_string(quadratic_tets_) +
                            " 10-node tetrahedra (C3D10 and variants) were read as 4-node ones "
                            "(by their corners; their mid-edge nodes are dropped)");
    }
    if (!skipped_solids_.empty()) {
      out_->notes.push_back("skipped the elements " + count_list(skipped_solids_) +
                            ": TetLOD reads tetrahedra only, so a region meshed with other "
                            "elements is not in the mesh");
    }
    if (!skipped_others_.empty()) {
      out_->notes.push_back("skipped the elements " + count_list(skipped_others_) +
                            ", and their element sets: TetLOD keeps the tetrahedra, and the "
                            "triangles of element sets as surface groups");
    }
    return Status();
  }

 private:
  enum class Mode {
    kSkip,
    kNodes,
    kElements,
    kElset,
    kElsetGenerate,
    kInstance,
    kSystem,
    kSurface
  };

  bool next_line(std::string_view* line) { return next_text_line(text_, &pos_, &line_, line); }

  // "*NAME, KEY=value, FLAG" (continued on the next line after a trailing comma).
  void read_keyword(std::string_view content, Keyword* keyword) {
    std::string text(content);
    while (!text.empty() && text.back() == ',') {
      std::string_view more;
      if (!next_line(&more)) break;
      text += std::string(trim_blanks(more));
    }
    const std::vector<std::string_view> parts = split_commas(std::string_view(text).substr(1));
    keyword->name = upper(parts[0]);
    keyword->options.clear();
    for (size_t i = 1; i < parts.size(); ++i) {
      if (parts[i].empty()) continue;
      const size_t equals = parts[i].find('=');
      const std::string key = upper(trim_blanks(parts[i].substr(0, equals)));
      const std::string value = equals == std::string_view::npos
                                    ? std::string()
                                    : std::string(trim_blanks(parts[i].substr(equals + 1)));
      keyword->options[key] = value;
    }
  }

  bool start(const Keyword& k) {
    mode_ = Mode::kSkip;
    if (k.name == "INCLUDE") {
      return fail(line_,
                  "*INCLUDE is not followed: read the included file instead, or paste it "
                  "in");
    }
    if (k.name == "PART") {
      if (++parts_ > 1) {
        return fail(line_,
                    "an input with several parts is not supported; write it flat "
                    "(Abaqus/CAE: the input file of the meshed part, or one part)");
      }
    } else if (k.name == "INSTANCE") {
      instance_line_ = line_;
      mode_ = Mode::kInstance;
    } else if (k.name == "SYSTEM") {
      // Its data line moves the nodes that follow (without one, it is the global system).
      system_line_ = line_;
      mode_ = Mode::kSystem;
    } else if ((k.name == "NODE" || k.name == "ELEMENT") && k.has("INPUT")) {
      return fail(line_, "*" + k.name + ", INPUT=" + k.get("INPUT") +
                             " is not followed: paste that file's lines in instead");
    } else if (k.name == "NODE") {
      const std::string system = upper(k.get("SYSTEM"));
      if (!system.empty() && system != "R") {
        return fail(line_, "*NODE, SYSTEM=" + k.get("SYSTEM") +
                               " (cylindrical or spherical coordinates) is not supported: "
                               "write the nodes in rectangular coordinates");
      }
      if (!k.get("NSET").empty()) node_sets_.insert(upper(k.get("NSET")));
      mode_ = Mode::kNodes;
    } else if (k.name == "NSET") {
      if (!k.get("NSET").empty()) node_sets_.insert(upper(k.get("NSET")));
    } else if (k.name == "SURFACE") {
      return start_surface(k);
    } else if (k.name == "ELEMENT") {
      const std::string type = upper(k.get("TYPE"));
      if (type.empty()) return fail(line_, "*ELEMENT needs TYPE=");
      element_nodes_ = tet_nodes(type);
      // Solid elements other than tets (C3D8, C3D6, ...) are skipped: counted for a note;
      // so are other elements that are not triangles (lines, quadrangles, springs ...).
      const bool solid = type.rfind("C3D", 0) == 0 || type.rfind("DC3D", 0) == 0;
      skipped_type_ = element_nodes_ == 0 && solid ? type : std::string();
      skipped_other_type_ =
          element_nodes_ == 0 && !solid && !is_triangle_type(type) ? type : std::string();
      element_set_ = k.has("ELSET") ? key_of(k.get("ELSET")) : -1;
      element_set_name_ = upper(k.get("ELSET"));
      triangle_block_ = is_triangle_type(type);
      if (triangle_block_ && !element_set_name_.empty() &&
          std::find(triangle_sets_.begin(), triangle_sets_.end(), k.get("ELSET")) ==
              triangle_sets_.end())
        triangle_sets_.push_back(k.get("ELSET"));
      mode_ = Mode::kElements;
    } else if (k.name == "ELSET") {
      const std::string set = k.get("ELSET");
      if (set.empty()) return fail(line_, "*ELSET needs ELSET=");
      current_set_ = upper(set);
      set_spellings_.try_emplace(current_set_, set);  // a material's name, as first written
      // An INTERNAL set is one Abaqus/CAE makes for a surface or a load
      // ("_Surf-1_S2"): never a material.
      if (sets_.find(current_set_) == sets_.end() && !k.has("INTERNAL"))
        set_order_.push_back(current_set_);
      sets_[current_set_];  // defined, even if empty
      mode_ = k.has("GENERATE") ? Mode::kElsetGenerate : Mode::kElset;
    } else if (k.name == "SOLID SECTION") {
      const std::string set = k.get("ELSET"), material = k.get("MATERIAL");
      if (set.empty() || material.empty()) {
        return fail(line_, "*SOLID SECTION needs ELSET= and MATERIAL=");
      }
      sections_.push_back({upper(set), key_of(material), line_});
    }
    return true;
  }

  bool data(const std::string& record, size_t line) {
    switch (mode_) {
      case Mode::kSkip:
        return true;
      case Mode::kNodes:
        return node(record, line);
      case Mode::kElements:
        return element(record, line);
      case Mode::kElset:
      case Mode::kElsetGenerate:
        return elset(record, line);
      case Mode::kInstance:
        return fail(line, "*INSTANCE with a translation or rotation is not supported");
      case Mode::kSystem: {
        // "0, 0, 0": the global system's origin, no move.
        std::vector<std::string_view> f = split_commas(record);
        if (!f.empty() && f.back().empty()) f.pop_back();
        bool origin = f.size() <= 3;
        for (std::string_view field : f) {
          double value = 1;
          origin = origin && real(trim_blanks(field), &value) && value == 0;
        }
        if (origin) return true;
        return fail(line, "*SYSTEM (line " + std::to_string(system_line_) +
                              ") with a translation or rotation is not supported: write the "
                              "nodes in the global system");
      }
      case Mode::kSurface:
        return surface_face(record, line);
    }
    return true;
  }

  // *SURFACE: an element-based one is read (data lines "element or set, Sn"), others
  // are skipped with a note.
  bool start_surface(const Keyword& k) {
    const std::string name = k.get("NAME");
    if (name.empty()) return fail(line_, "*SURFACE needs NAME=");
    const std::string type = upper(k.get("TYPE"));
    std::string form;  // why it is not read
    if (!type.empty() && type != "ELEMENT") {
      form = "TYPE=" + type;
    } else if (k.has("COMBINE")) {
      form = "COMBINE=" + upper(k.get("COMBINE"));
    } else if (k.has("CROP")) {
      form = "CROP";
    }
    if (!form.empty()) {
      unread_surfaces_.push_back(name + " (" + form + ")");
      return true;
    }
    const auto [it, added] = surface_index_.try_emplace(upper(name), surfaces_.size());
    if (added) surfaces_.push_back({name, {}, false});
    current_surface_ = it->second;
    mode_ = Mode::kSurface;
    return true;
  }

  bool surface_face(const std::string& record, size_t line) {
    Surface& surface = surfaces_[current_surface_];
    std::vector<std::string_view> f = split_commas(record);
    if (f.size() > 1 && f.back().empty()) f.pop_back();  // a trailing comma
    // All exposed faces of the elements (or, blank, of the model); "12 S1", a face
    // without its comma, is not that.
    if (f.size() == 1 && f[0].find_first_of(" \t") == std::string_view::npos) {
      if (!surface.skipped) {
        unread_surfaces_.push_back(surface.name + " (line " + std::to_string(line) +
                                   ": an element or set without a face, for all its exposed "
                                   "faces)");
      }
      surface.skipped = true;
      return true;
    }
    if (f.size() != 2 || f[0].empty() || f[1].empty()) {
      return fail(line, "*SURFACE " + surface.name +
                            ": expected 'element or element set, face' such as '12, S3', found '" +
                            record + "'");
    }
    const std::string face = upper(f[1]);
    SurfaceFace entry;
    entry.label = std::string(f[0]);
    entry.face =
        face.size() == 2 && face[0] == 'S' && face[1] >= '1' && face[1] <= '4' ? face[1] - '0' : 0;
    entry.face_text = std::string(f[1]);
    entry.line = line;
    surface.faces.push_back(std::move(entry));
    return true;
  }

  // An element number, plain or qualified by the (one) instance: "12", "Part-1-1.12".
  bool element_label(std::string_view s, int64_t* value) const {
    if (integer(s, value)) return true;
    const size_t dot = s.rfind('.');
    return dot != std::string_view::npos && dot > 0 && integer(s.substr(dot + 1), value);
  }

  bool integer(std::string_view s, int64_t* value) const {
    const auto r = std::from_chars(s.data(), s.data() + s.size(), *value);
    return !s.empty() && r.ec == std::errc() && r.ptr == s.data() + s.size();
  }

  bool real(std::string_view s, double* value) const {
    if (s.empty()) {
      *value = 0;  // a blank coordinate is 0
      return true;
    }
    if (s.front() == '+') s.remove_prefix(1);
    const auto r = std::from_chars(s.data(), s.data() + s.size(), *value);
    return r.ec == std::errc() && r.ptr == s.data() + s.size() && std::isfinite(*value);
  }

  bool node(const std::string& record, size_t line) {
    const std::vector<std::string_view> f = split_commas(record);
    int64_t id = 0;
    if (!integer(f[0], &id) || id < 1) {
      return fail(line, "node id '" + std::string(f[0]) + "' is not an integer >= 1");
    }
    Vec3 p;
    for (int k = 0; k < 3; ++k) {
      if (size_t(k + 1) < f.size() && !real(f[size_t(k + 1)], &p[k])) {
        return fail(line, "node " + std::to_string(id) + ": coordinate '" +
                              std::string(f[size_t(k + 1)]) + "' is not a finite number");
      }
    }
    if (f.size() < 3)
      return fail(line, "node " + std::to_string(id) + " has fewer than 2 coordinates");
    if (out_->mesh.positions.size() + 1 >= kInvalidIndex) return fail(line, "too many nodes");
    const auto inserted = node_index_.emplace(id, uint32_t(out_->mesh.positions.size()));
    if (!inserted.second) return fail(line, "node " + std::to_string(id) + " is defined twice");
    out_->mesh.positions.push_back(p);
    return true;
  }

  bool element(const std::string& record, size_t line) {
    std::vector<std::string_view> f = split_commas(record);
    if (!f.empty() && f.back().empty()) f.pop_back();  // a trailing comma
    int64_t id = 0;
    if (!integer(f[0], &id) || id < 1) {
      return fail(line, "element id '" + std::string(f[0]) + "' is not an integer >= 1");
    }
    if (element_nodes_ == 0) {  // not a tet
      if (!skipped_type_.empty() && skipped_solids_.size() < 100) ++skipped_solids_[skipped_type_];
      if (!skipped_other_type_.empty() && skipped_others_.size() < 100)
        ++skipped_others_[skipped_other_type_];
      other_elements_.insert(id);  // for the faces of surfaces, which are dropped
      // A triangle's corners, for the surface groups of the sets that hold it.
      std::array<int64_t, 3> corners{};
      if (triangle_block_ && f.size() >= 4 && integer(f[1], &corners[0]) &&
          integer(f[2], &corners[1]) && integer(f[3], &corners[2]))
        triangles_.emplace(id, corners);
      if (!element_set_name_.empty()) element_sets_[element_set_name_].push_back(id);
      return true;
    }
    if (f.size() != size_t(element_nodes_) + 1) {
      return fail(line, "element " + std::to_string(id) + " has " + std::to_string(f.size() - 1) +
                            " nodes, its type " + std::to_string(element_nodes_));
    }
    PendingTet t;
    t.element = id;
    t.line = line;
    t.element_set = element_set_;
    for (int k = 0; k < element_nodes_; ++k) {
      int64_t& node = k < 4 ? t.nodes[k] : t.mid_nodes[k - 4];
      if (!integer(f[size_t(k + 1)], &node)) {
        return fail(line, "element " + std::to_string(id) + ": node '" +
                              std::string(f[size_t(k + 1)]) + "' is not an integer");
      }
    }
    if (tets_.size() + 1 >= kInvalidIndex) return fail(line, "too many elements");
    if (!tet_of_element_.emplace(id, uint32_t(tets_.size())).second) {
      return fail(line, "element " + std::to_string(id) + " is defined twice");
    }
    tets_.push_back(t);
    quadratic_tets_ += element_nodes_ == 10;
    if (!element_set_name_.empty()) element_sets_[element_set_name_].push_back(id);
    return true;
  }

  bool elset(const std::string& record, size_t line) {
    std::vector<int64_t>& members = sets_[current_set_];
    std::vector<std::string_view> f = split_commas(record);
    if (!f.empty() && f.back().empty()) f.pop_back();
    if (mode_ == Mode::kElsetGenerate) {
      int64_t first = 0, last = 0, step = 1;
      if (f.size() < 2 || f.size() > 3 || !integer(f[0], &first) || !integer(f[1], &last) ||
          (f.size() == 3 && !integer(f[2], &step)) || step < 1 || first < 1 || last < first) {
        return fail(line,
                    "*ELSET, GENERATE needs 'first, last[, step]' with 1 <= first <= last "
                    "and step >= 1");
      }
      const uint64_t count = uint64_t(last - first) / uint64_t(step) + 1;
      if (!room_for(count, line)) return false;
      for (uint64_t i = 0; i < count; ++i) members.push_back(first + int64_t(i) * step);
      return true;
    }
    for (std::string_view item : f) {
      int64_t e = 0;
      if (element_label(item, &e)) {
        if (!room_for(1, line)) return false;
        members.push_back(e);
      } else {
        // Another set's name: its members so far.
        const std::vector<int64_t>* other = members_of(upper(item));
        if (other == nullptr) {
          return fail(line, "*ELSET " + current_set_ + ": '" + std::string(item) +
                                "' is neither an element id nor a set defined before");
        }
        if (other != &members) {
          if (!room_for(other->size(), line)) return false;
          const std::vector<int64_t> copy = *other;
          members.insert(members.end(), copy.begin(), copy.end());
        }
      }
    }
    return true;
  }

  // Sets may name sets and generate ranges: their members together stay within a
  // bound proportional to the input, so that no file can exhaust memory.
  bool room_for(uint64_t more, size_t line) {
    const uint64_t limit = 16 * uint64_t(text_.size()) + (uint64_t(1) << 20);
    if (more > limit - set_members_) {
      return fail(line, "the element sets hold more members than an input of this size can (" +
                            std::to_string(limit) + ")");
    }
    set_members_ += more;
    return true;
  }

  // The index of a material or set name in keys_.
  int key_of(const std::string& name) {
    const std::string u = upper(name);
    const auto it = key_index_.find(u);
    if (it != key_index_.end()) return it->second;
    key_index_.emplace(u, int(keys_.size()));
    keys_.push_back(u);
    spellings_.push_back(name);
    return int(keys_.size()) - 1;
  }

  bool resolve() {
    if (instance_line_ != 0 && parts_ == 0) {
      return fail(instance_line_, "*INSTANCE of a part that is not in the file");
    }
    // Material key per tet: sections, then *ELSET membership, then *ELEMENT's ELSET.
    std::vector<int> key(tets_.size(), -1);
    for (const Section& s : sections_) {
      const std::vector<int64_t>* members = members_of(s.set);
      if (members == nullptr) {
        return fail(s.line, "*SOLID SECTION: element set " + s.set + " is not defined");
      }
      for (int64_t e : *members) {
        const auto it = tet_of_element_.find(e);
        if (it != tet_of_element_.end() && key[it->second] < 0) key[it->second] = s.material;
      }
    }
    // A set that holds every tet ("EALL", as CalculiX decks have) says nothing of
    // materials when other sets tell the tets apart: it only gives the tets no other
    // set holds their material, last.
    std::vector<std::string> all_sets;
    if (sections_.empty()) {
      all_sets = sets_holding_every_tet();
      // Tets in two sets take the first: said in a note, naming the sets passed over.
      uint64_t overlapping = 0;  // tets
      std::vector<uint8_t> in_two(tets_.size(), 0);
      std::vector<std::string> passed_over;
      for (const std::string& set_name : set_order_) {  // in the order they were defined
        if (std::find(all_sets.begin(), all_sets.end(), set_name) != all_sets.end()) continue;
        const int k = key_of(set_spellings_.at(set_name));
        bool passed = false;
        for (int64_t e : sets_.at(set_name)) {
          const auto it = tet_of_element_.find(e);
          if (it == tet_of_element_.end()) continue;
          int& tet_key = key[it->second];
          if (tet_key < 0) {
            tet_key = k;
          } else if (tet_key != k) {
            if (!in_two[it->second]) in_two[it->second] = 1, ++overlapping;
            passed = true;
          }
        }
        if (passed && passed_over.size() < 10) passed_over.push_back(set_spellings_.at(set_name));
      }
      if (overlapping > 0) {
        std::string list;
        for (const std::string& s : passed_over) list += (list.empty() ? "" : ", ") + s;
        out_->notes.push_back(
            std::to_string(overlapping) +
            " tetrahedra are in more than one *ELSET, and no *SOLID SECTION says which is "
            "their material: each takes the first set in the file that holds it, not " +
            list);
      }
    }
    for (size_t t = 0; t < tets_.size(); ++t) {
      if (key[t] < 0) key[t] = tets_[t].element_set;
      if (key[t] < 0 && !all_sets.empty()) key[t] = key_of(set_spellings_.at(all_sets[0]));
    }
    // Key -> material id, for the keys in use: the trailing number of the name, else
    // the next free numbers after the largest such, in order of appearance. Two names
    // with the same number ("Rotor1", "Stator1") are two materials: the first keeps
    // the number, the later one gets a free one.
    std::vector<int64_t> id(keys_.size(), -1);
    std::vector<char> used(keys_.size(), 0);
    for (int k : key)
      if (k >= 0) used[size_t(k)] = 1;
    int64_t largest = 0;
    std::vector<int64_t> taken;
    for (size_t k = 0; k < keys_.size(); ++k) {
      const std::string& s = keys_[k];
      size_t digits = s.size();
      while (digits > 0 && std::isdigit(uint8_t(s[digits - 1]))) --digits;
      if (used[k] && digits < s.size() && s.size() - digits <= 18) {
        const int64_t number = std::stoll(s.substr(digits));
        if (std::find(taken.begin(), taken.end(), number) != taken.end()) continue;
        taken.push_back(number);
        id[k] = number;
        largest = std::max(largest, id[k]);
      }
    }
    for (size_t k = 0; k < keys_.size(); ++k) {
      if (used[k] && id[k] < 0) id[k] = ++largest;
    }
    // The names, but not our own MATERIAL_<id>, which only says the number; where
    // TetLOD wrote the set, the name it had (kMaterialNameComment).
    // (A name that is MATERIAL_<id> but for case, as "Material_1", is written so, with
    // its comment: the comment's name is taken.)
    for (size_t k = 0; k < keys_.size(); ++k) {
      const auto given = commented_names_.find(keys_[k]);
      const bool commented = given != commented_names_.end() && given->second.id == id[k];
      if (used[k] && (commented || keys_[k] != "MATERIAL_" + std::to_string(id[k])) &&
          id[k] <= std::numeric_limits<int32_t>::max()) {
        if (commented) given->second.used = true;
        out_->material_names.push_back(
            {int32_t(id[k]), valid_utf8(commented ? given->second.name : spellings_[k])});
      }
    }
    sort_by_material(&out_->material_names);
    TetMesh& mesh = out_->mesh;
    mesh.tets.reserve(tets_.size());
    mesh.materials.reserve(tets_.size());
    out_->tet_lines.reserve(tets_.size());
    for (size_t t = 0; t < tets_.size(); ++t) {
      const PendingTet& p = tets_[t];
      Tet tet;
      for (int k = 0; k < 4; ++k) {
        const auto it = node_index_.find(p.nodes[k]);
        if (it == node_index_.end()) {
          return fail(p.line, "element " + std::to_string(p.element) + " uses node " +
                                  std::to_string(p.nodes[k]) + ", which is not defined");
        }
        tet[k] = it->second;
      }
      // A C3D10's mid-side nodes: read by its corners, but each must be a node.
      for (const int64_t node : p.mid_nodes)
        if (node != 0 && node_index_.find(node) == node_index_.end())
          return fail(p.line, "element " + std::to_string(p.element) + " uses node " +
                                  std::to_string(node) +
                                  " (a mid-side node), which is not defined");
      const int64_t material = key[t] < 0 ? 0 : id[size_t(key[t])];
      if (material > std::numeric_limits<int32_t>::max()) {
        return fail(p.line, "element " + std::to_string(p.element) + ": material " +
                                std::to_string(material) + " is too large");
      }
      mesh.tets.push_back(tet);
      mesh.materials.push_back(int32_t(material));
      out_->tet_lines.push_back(line_number(p.line));
    }
    return true;
  }

  // The *ELSETs (upper-case names) that hold every tet, when other sets (*ELSETs or
  // the *ELEMENT blocks' ELSETs) tell the tets apart; a note names them.
  std::vector<std::string> sets_holding_every_tet() {
    if (tets_.empty()) return {};
    std::vector<std::string> all;
    std::vector<uint32_t> stamp(tets_.size(), 0);
    uint32_t round = 0;
    bool others_split = false;  // another *ELSET holds some tets but not all
    for (const std::string& set_name : set_order_) {
      ++round;
      size_t held = 0;
      for (int64_t e : sets_.at(set_name)) {
        const auto it = tet_of_element_.find(e);
        if (it != tet_of_element_.end() && stamp[it->second] != round)
          stamp[it->second] = round, ++held;
      }
      if (held == tets_.size())
        all.push_back(set_name);
      else if (held > 0)
        others_split = true;
    }
    if (all.empty()) return {};
    for (const PendingTet& t : tets_)
      if (t.element_set != tets_[0].element_set) others_split = true;
    if (!others_split) return {};  // the one material there is
    std::string list;
    for (const std::string& s : all) list += (list.empty() ? "" : ", ") + set_spellings_.at(s);
    out_->notes.push_back("*ELSET " + list +
                          " holds every tetrahedron, and no *SOLID SECTION says which sets are "
                          "materials: the materials are the other sets, and it only that of the "
                          "tetrahedra no other set holds");
    return all;
  }

  // The surfaces' faces as surface groups, after resolve(): their tets are in the mesh.
  bool resolve_surfaces() {
    // Faces visited (set members included) stay within a bound proportional to the
    // input, as set members do, so that no file can exhaust memory or time.
    const uint64_t limit = 4 * uint64_t(text_.size()) + (uint64_t(1) << 16);
    uint64_t visited = 0;
    size_t dropped = 0;           // faces on elements that are not tets read
    std::string dropped_from;     // the surfaces that had them
    std::vector<uint32_t> seen;   // per tet face: the last surface (stamp) it was added to
    std::vector<uint64_t> faces;  // of the current group: tet * 4 + face - 1
    uint32_t stamp = 0;
    for (Surface& surface : surfaces_) {
      if (surface.skipped) continue;
      ++stamp;
      faces.clear();
      size_t dropped_here = 0;
      // A reference TetLOD cannot follow skips the surface (with a note), not the mesh.
      std::string unresolved;
      for (const SurfaceFace& entry : surface.faces) {
        const std::string where = "line " + std::to_string(entry.line) + ": ";
        // An element number, else a set, else an instance-qualified element number.
        int64_t element = 0;
        const std::vector<int64_t>* members =
            integer(entry.label, &element) ? nullptr : surface_set(upper(entry.label));
        std::vector<int64_t> single;
        if (members == nullptr) {
          if (!element_label(entry.label, &element)) {
            unresolved = where + "'" + entry.label + "' is neither an element nor an element set";
            break;
          }
          if (tet_of_element_.count(element) == 0 && other_elements_.count(element) == 0) {
            unresolved = where + "element " + std::to_string(element) + " is not defined";
            break;
          }
          single.push_back(element);
          members = &single;
        }
        if (members->size() > limit - visited) {
          return fail(entry.line, "the surfaces hold more faces than an input of this size can (" +
                                      std::to_string(limit) + ")");
        }
        visited += members->size();
        for (int64_t e : *members) {
          const auto it = tet_of_element_.find(e);
          if (it == tet_of_element_.end()) {
            ++dropped_here;
            continue;
          }
          if (entry.face == 0) {
            unresolved = where + "element " + std::to_string(e) +
                         " is a tetrahedron, whose faces are S1 to S4, not '" + entry.face_text +
                         "'";
            break;
          }
          if (seen.empty()) seen.assign(tets_.size() * 4, 0);
          const uint64_t face = uint64_t(it->second) * 4 + uint64_t(entry.face - 1);
          if (seen[face] == stamp) continue;  // listed twice
          seen[face] = stamp;
          faces.push_back(face);
        }
        if (!unresolved.empty()) break;
      }
      if (!unresolved.empty()) {
        unread_surfaces_.push_back(surface.name + " (" + unresolved + ")");
        continue;
      }
      if (dropped_here > 0) {
        dropped += dropped_here;
        dropped_from += (dropped_from.empty() ? "" : ", ") + surface.name;
      }
      if (faces.empty()) continue;
      InputSurfaceGroup group;
      name_surface_group(surface.name, &group);
      group.triangles.reserve(faces.size());
      const TetMesh& mesh = out_->mesh;
      for (uint64_t face : faces) {
        const Tet& tet = mesh.tets[face / 4];
        const int* corners = kAbaqusTetFace[face % 4];
        // Facing out of its element, as Abaqus takes an element-based surface's normal
        // (a group's facing is kept: surface.h), whatever the element's node order.
        std::array<Vec3, 3> t = {mesh.positions[tet[size_t(corners[0])]],
                                 mesh.positions[tet[size_t(corners[1])]],
                                 mesh.positions[tet[size_t(corners[2])]]};
        const Vec3& apex = mesh.positions[tet[size_t(6 - corners[0] - corners[1] - corners[2])]];
        if (dot(cross(t[1] - t[0], t[2] - t[0]), apex - t[0]) > 0) std::swap(t[1], t[2]);
        group.triangles.push_back(t);
      }
      add_group(std::move(group));
    }
    add_triangle_groups();
    if (dropped > 0) {
      out_->notes.push_back(std::to_string(dropped) + " faces of *SURFACE " + dropped_from +
                            " are on elements that are not tetrahedra (or not defined): not "
                            "kept in the surface groups");
    }
    if (retagged_count_ > 0) {
      std::string list;
      for (const std::string& s : retagged_) list += (list.empty() ? "" : ", ") + s;
      out_->notes.push_back(std::to_string(retagged_count_) +
                            (retagged_count_ == 1 ? " *SURFACE numbered anew: the tag its"
                                                  : " *SURFACEs numbered anew: the tag their") +
                            " TetLOD comment gives is an earlier group's, or no tag: " + list +
                            (retagged_count_ > retagged_.size() ? ", ..." : ""));
    }
    if (!unread_surfaces_.empty()) {
      std::string list;
      for (const std::string& s : unread_surfaces_) list += (list.empty() ? "" : ", ") + s;
      out_->notes.push_back("not read as surface groups: *SURFACE " + list +
                            "; TetLOD reads element-face surfaces given as 'element or element "
                            "set, Sn'");
    }
    return true;
  }

  // "** TetLOD material SET ID NAME" (kMaterialNameComment): the name the material of
  // the element set SET had before it was made an Abaqus label (spaces and all); and
  // "** TetLOD surface SURFACE TAG NAME" (kSurfaceNameComment): the tag and name of the
  // surface group written as *SURFACE SURFACE.
  // One that cannot be read is ignored, with a note (ignored_comments_note()).
  void read_name_comment(std::string_view comment) {
    const bool material = comment.substr(0, std::strlen(kMaterialNameComment)) ==
                          std::string_view(kMaterialNameComment);
    const std::string_view prefix = material ? kMaterialNameComment : kSurfaceNameComment;
    // (The line is trimmed: a bare "** TetLOD material" lacks the prefix's blank.)
    for (const std::string_view bare :
         {std::string_view(kMaterialNameComment), std::string_view(kSurfaceNameComment)})
      if (comment == bare.substr(0, bare.size() - 1)) return ignore_comment(line_);
    if (comment.substr(0, prefix.size()) != prefix) return;
    std::string_view rest = comment.substr(prefix.size());
    const size_t space = rest.find(' ');
    if (space == std::string_view::npos) return ignore_comment(line_);
    const std::string set(rest.substr(0, space));
    rest.remove_prefix(space + 1);
    int64_t id = 0;
    const auto [end, error] = std::from_chars(rest.data(), rest.data() + rest.size(), id);
    if (error != std::errc() || end == rest.data() + rest.size() || *end != ' ')
      return ignore_comment(line_);
    const std::string_view name = rest.substr(size_t(end - rest.data()) + 1);
    auto& names = material ? commented_names_ : commented_surfaces_;
    if (name.empty() || names.size() >= 100000) return ignore_comment(line_);
    // A second comment for one set or surface: the later one is taken, the earlier noted.
    auto [at, added] = names.try_emplace(upper(set));
    if (!added) ignore_comment(at->second.line);
    at->second = {id, std::string(name), line_, false};
    if (!material) commented_tags_.insert(id);
  }
  void ignore_comment(size_t line) {
    if (ignored_comment_lines_.size() < 5) ignored_comment_lines_.push_back(line);
    ++ignored_comment_count_;
  }
  // A note of the TetLOD comments that gave nothing: unreadable, or naming no set of
  // tets with that material number, or no *SURFACE of the file (so that a changed file
  // whose groups lost their tags and names does not go unnoticed).
  void ignored_comments_note() {
    for (const auto* names : {&commented_names_, &commented_surfaces_})
      for (const auto& [set, comment] : *names) {
        const bool surface = names == &commented_surfaces_;
        if (comment.used || (surface && surface_index_.count(set))) continue;
        ignore_comment(comment.line);
      }
    if (ignored_comment_count_ == 0) return;
    std::sort(ignored_comment_lines_.begin(), ignored_comment_lines_.end());
    std::string lines;
    for (size_t line : ignored_comment_lines_)
      lines += (lines.empty() ? "" : ", ") + std::to_string(line);
    if (ignored_comment_count_ > ignored_comment_lines_.size()) lines += ", ...";
    out_->notes.push_back(
        std::to_string(ignored_comment_count_) +
        (ignored_comment_count_ == 1 ? " TetLOD comment" : " TetLOD comments") + " ignored (line" +
        (ignored_comment_count_ == 1 ? " " : "s ") + lines +
        "): unreadable, or naming no *SURFACE of the file or no element set of tets with the "
        "material number given, or followed by another for the same; " +
        (ignored_comment_count_ == 1 ? "its name or tag is not used"
                                     : "their names and tags are not used"));
  }

  // The tag of the next surface group: after the largest material number (and 0), one
  // no group has yet and no TetLOD comment gives (so that a group without one does not
  // take a later group's own).
  int32_t next_surface_tag() {
    if (surface_tag_base_ < 0) {
      int64_t largest = 0;
      for (int32_t m : out_->mesh.materials) largest = std::max<int64_t>(largest, m);
      // (Numbers this high: from 1.)
      surface_tag_base_ = largest < std::numeric_limits<int32_t>::max() / 2 ? largest : 0;
    }
    int64_t tag = surface_tag_base_ + 1 + int64_t(out_->surface_groups.size());
    while (group_tags_.count(tag) || commented_tags_.count(tag)) ++tag;
    return int32_t(tag);
  }
  void add_group(InputSurfaceGroup group) {
    group_tags_.insert(group.tag);
    out_->surface_groups.push_back(std::move(group));
  }

  // The tag and name of the group of *SURFACE `surface`: those a TetLOD comment gives
  // (the tag as the file it was written from had it, even a material's number, as a
  // Gmsh file's physical surface may have; if an earlier group has it, or it is no
  // tag, the next tag, with a note), else the next tag and group_name().
  void name_surface_group(const std::string& surface, InputSurfaceGroup* group) {
    const auto it = commented_surfaces_.find(upper(surface));
    if (it == commented_surfaces_.end()) {
      group->tag = next_surface_tag();
      group->name = valid_utf8(group_name(surface));
      return;
    }
    const int64_t tag = it->second.id;
    group->name = valid_utf8(it->second.name);
    if (tag > 0 && tag <= std::numeric_limits<int32_t>::max() && !group_tags_.count(tag)) {
      group->tag = int32_t(tag);
      return;
    }
    group->tag = next_surface_tag();
    if (retagged_.size() < 5)
      retagged_.push_back(surface + " (" + std::to_string(tag) + " -> " +
                          std::to_string(group->tag) + ")");
    ++retagged_count_;
  }

  // The sets of triangle elements (as Gmsh writes a physical surface: CPS3 elements in
  // an *ELSET named after it) as surface groups, tagged after the *SURFACEs': the
  // *ELSETs that hold triangles, else the triangle *ELEMENT blocks' ELSETs.
  void add_triangle_groups() {
    if (triangles_.empty()) return;
    out_->surface_elements_not_kept = triangles_.size();  // kept only in groups (the CLI says so)
    std::vector<std::pair<std::string, const std::vector<int64_t>*>> sets;  // name, members
    for (const std::string& set_name : set_order_) {
      const std::vector<int64_t>& members = sets_.at(set_name);
      if (std::any_of(members.begin(), members.end(),
                      [&](int64_t e) { return triangles_.count(e) > 0; }))
        sets.push_back({set_spellings_.at(set_name), &members});
    }
    if (sets.empty())
      for (const std::string& name : triangle_sets_)
        if (const std::vector<int64_t>* members = members_of(upper(name)))
          sets.push_back({name, members});
    size_t unknown_nodes = 0;
    for (const auto& [name, members] : sets) {
      InputSurfaceGroup group;
      group.tag = next_surface_tag();
      group.name = valid_utf8(name);
      std::unordered_set<int64_t> listed;  // an element listed twice is one triangle
      for (int64_t e : *members) {
        const auto it = triangles_.find(e);
        if (it == triangles_.end() || !listed.insert(e).second) continue;
        std::array<Vec3, 3> corners;
        bool known = true;
        for (size_t k = 0; k < 3 && known; ++k) {
          const auto node = node_index_.find(it->second[k]);
          known = node != node_index_.end();
          if (known) corners[k] = out_->mesh.positions[node->second];
        }
        if (!known) {
          ++unknown_nodes;
          continue;
        }
        group.triangles.push_back(corners);
      }
      if (!group.triangles.empty()) add_group(std::move(group));
    }
    if (unknown_nodes > 0)
      out_->notes.push_back(std::to_string(unknown_nodes) +
                            " triangle elements name a node that is not defined: not kept in "
                            "the surface groups");
  }

  // The element set a surface's line names: as written, or, qualified by an
  // instance ("Part-1-1.Set-1"), the set of the one part.
  const std::vector<int64_t>* surface_set(const std::string& name) const {
    if (const std::vector<int64_t>* members = members_of(name)) return members;
    const size_t dot = name.find('.');
    return dot == std::string::npos ? nullptr : members_of(name.substr(dot + 1));
  }

  // A surface's group name: its own, but X for X_FACES when the file has a node set
  // X and no surface X (what write_abaqus() writes for a group X).
  std::string group_name(const std::string& surface) const {
    const std::string u = upper(surface);
    constexpr std::string_view kSuffix = "_FACES";
    if (u.size() <= kSuffix.size() ||
        u.compare(u.size() - kSuffix.size(), kSuffix.size(), kSuffix.data(), kSuffix.size()) != 0)
      return surface;
    const std::string stripped = u.substr(0, u.size() - kSuffix.size());
    if (node_sets_.count(stripped) == 0 || surface_index_.count(stripped) > 0) return surface;
    return surface.substr(0, surface.size() - kSuffix.size());
  }

  // The members of a set defined by *ELSET or by *ELEMENT's ELSET, or null.
  const std::vector<int64_t>* members_of(const std::string& name) const {
    const auto it = sets_.find(name);
    if (it != sets_.end()) return &it->second;
    const auto e = element_sets_.find(name);
    return e != element_sets_.end() ? &e->second : nullptr;
  }

  bool fail(size_t line, const std::string& message) {
    if (error_.ok()) error_ = Status::error(name_ + ":" + std::to_string(line) + ": " + message);
    return false;
  }

  struct PendingTet {
    int64_t element = 0;
    int64_t nodes[4] = {};
    int64_t mid_nodes[6] = {};  // a C3D10's, checked only (0: a C3D4)
    int element_set = -1;       // key of *ELEMENT's ELSET
    size_t line = 0;
  };
  struct Section {
    std::string set;
    int material = -1;  // key
    size_t line = 0;
  };
  // A data line of a *SURFACE: an element id or set name, and a face.
  struct SurfaceFace {
    std::string label;
    int face = 0;  // 1 to 4 for S1 to S4, else 0
    std::string face_text;
    size_t line = 0;
  };
  struct Surface {
    std::string name;  // as written
    std::vector<SurfaceFace> faces;
    bool skipped = false;  // for a form that is not read (in unread_surfaces_)
  };

  std::string_view text_;
  const std::string& name_;
  ParsedMesh* out_;
  size_t pos_ = 0;
  size_t line_ = 0;
  Status error_;
  Mode mode_ = Mode::kSkip;
  int parts_ = 0;
  size_t instance_line_ = 0;
  size_t system_line_ = 0;  // of the last *SYSTEM
  int element_nodes_ = 0;
  size_t quadratic_tets_ = 0;    // C3D10 and variants, read by their corners
  std::string skipped_type_;     // of the *ELEMENT block: a non-tet solid
  bool triangle_block_ = false;  // the *ELEMENT block's are triangles
  std::unordered_map<int64_t, std::array<int64_t, 3>> triangles_;  // by element id: corners
  std::vector<std::string> triangle_sets_;        // ELSETs of triangle *ELEMENT blocks, as written
  std::map<std::string, size_t> skipped_solids_;  // by type
  std::string skipped_other_type_;                // of the *ELEMENT block: neither a
                                                  // solid nor a triangle (T3D2, CPS4 ...)
  std::map<std::string, size_t> skipped_others_;  // by type
  int element_set_ = -1;
  std::string element_set_name_;
  std::string current_set_;
  std::unordered_map<std::string, std::vector<int64_t>> element_sets_;  // *ELEMENT's ELSET
  std::unordered_map<int64_t, uint32_t> node_index_;
  std::unordered_map<int64_t, uint32_t> tet_of_element_;
  std::vector<PendingTet> tets_;
  std::unordered_map<std::string, std::vector<int64_t>> sets_;
  std::vector<std::string> set_order_;
  std::unordered_map<std::string, std::string> set_spellings_;  // upper case -> as written
  uint64_t set_members_ = 0;                                    // in all *ELSET sets
  std::vector<Section> sections_;
  std::vector<std::string> keys_;       // material and set names, upper case
  std::vector<std::string> spellings_;  // the same as first written (material names)
  std::unordered_map<std::string, int> key_index_;
  std::unordered_set<int64_t> other_elements_;             // ids of elements that are not tets
  std::unordered_set<std::string> node_sets_;              // names, upper case
  std::vector<Surface> surfaces_;                          // element-based, in order of the file
  std::unordered_map<std::string, size_t> surface_index_;  // by upper-case name
  size_t current_surface_ = 0;
  // From kMaterialNameComment lines: set name (upper case) -> its material and name.
  struct NameComment {
    int64_t id = 0;  // material number or surface tag
    std::string name;
    size_t line = 0;
    bool used = false;  // materials: the set is one of tets with that number
  };
  std::map<std::string, NameComment> commented_names_;
  // From kSurfaceNameComment lines: surface name (upper case) -> its group's tag and name.
  std::map<std::string, NameComment> commented_surfaces_;
  std::vector<size_t> ignored_comment_lines_;  // the first few, for the note
  size_t ignored_comment_count_ = 0;
  int64_t surface_tag_base_ = -1;               // next_surface_tag(): the largest material number
  std::unordered_set<int64_t> group_tags_;      // of the surface groups added (add_group())
  std::unordered_set<int64_t> commented_tags_;  // the tags kSurfaceNameComment lines give
  std::vector<std::string> retagged_;           // "NAME (comment's tag -> tag)", the first few
  size_t retagged_count_ = 0;                   // surfaces whose comment's tag could not be kept
  std::vector<std::string> unread_surfaces_;    // "NAME (reason)", for the note
};

// Per surface group, a *NSET of its nodes (for *BOUNDARY) and a *SURFACE of element
// faces (for *DLOAD, *DFLUX, contact), both named after the group.
// The faces are those of the group's tets of the smaller material; element ids are
// the tets' positions + 1, as write_abaqus() numbers them.
// A user's name made a valid Abaqus label: letters (in their case; Abaqus compares
// labels case-insensitively), digits, '_' and '-' (as in Abaqus/CAE's "Set-1";
// CalculiX 2.20 reads them), starting with a letter (else after `prefix`). A
// character of several UTF-8 bytes ("ü") becomes one '_', not one a byte.
std::string abaqus_label(const std::string& name, const char* prefix) {
  std::string label;
  for (const char c : name) {
    const uint8_t byte = uint8_t(c);
    if ((byte & 0xC0) == 0x80) continue;  // a continuation byte of a UTF-8 character
    label += std::isalnum(byte) || c == '_' || c == '-' ? c : '_';
  }
  if (label.empty() || !std::isalpha(uint8_t(label[0]))) label = prefix + label;
  return label;
}

// The element set of material m: MATERIAL_<m>, or its name (WriteOptions::
// material_names) ending in m, so that the reader gives the tets m again.
std::string material_set_name(int32_t m, const std::vector<MaterialName>* names) {
  const std::string number = std::to_string(m);
  if (const std::string* name = find_material_name(names, m); name && !name->empty()) {
    std::string label = abaqus_label(*name, "M_");
    if (label.size() > 60) label.resize(60);  // Abaqus labels: at most 80 characters
    size_t digits = label.size();
    while (digits > 0 && std::isdigit(uint8_t(label[digits - 1]))) --digits;
    const std::string_view tail = std::string_view(label).substr(digits);
    const bool ends_in_m = !tail.empty() && tail.size() <= 18 && std::stoll(std::string(tail)) == m;
    return ends_in_m ? label : label + "_" + number;
  }
  return "MATERIAL_" + number;
}

// A coordinate in at most 20 characters: CalculiX reads each number of a *NODE line
// from its first 20 (Fortran's f20.0), so "-9.184850993605149e-15" (22) stops it
// and a 21-digit decimal would lose its last digit. The shortest text that reads back
// to the same value where it fits (nearly always); else the most digits that fit (13
// at least, for a 3-digit exponent), a relative change of at most 5e-13.
void append_inp_real(std::string* out, double value) {
  constexpr int kWidth = 20;
  char buffer[32];
  auto result = std::to_chars(buffer, buffer + sizeof(buffer), value);
  for (int digits = 16; result.ptr - buffer > kWidth && digits > 0; --digits)
    result =
        std::to_chars(buffer, buffer + sizeof(buffer), value, std::chars_format::general, digits);
  out->append(buffer, result.ptr);
}

void write_abaqus_surfaces(const SurfaceGroups& surfaces, std::string* out) {
  // Abaqus face labels of C3D4 by the corner opposite the face: S1 = nodes 1-2-3,
  // S2 = 1-4-2, S3 = 2-4-3, S4 = 3-4-1.
  static constexpr const char* kFaceLabel[4] = {"S3", "S4", "S2", "S1"};
  std::vector<uint32_t> nodes;
  std::set<std::string> used;  // upper case: labels are case-insensitive
  for (const SurfaceGroup& group : surfaces.groups) {
    // At most 80 characters with "_FACES", and one set per group: a name two groups
    // share (or share once made a label) takes the group's tag.
    std::string name = abaqus_label(group.name, "S_");
    if (name.size() > 60) name.resize(60);
    if (used.count(upper(name))) name = name.substr(0, 48) + "_" + std::to_string(group.tag);
    for (int k = 2; used.count(upper(name)); ++k)
      name = name.substr(0, 48) + "_" + std::to_string(k);
    used.insert(upper(name));
    std::string one_line = group.name;
    for (char& c : one_line)
      if (c == '\n' || c == '\r') c = ' ';
    out->append(std::string(kSurfaceNameComment) + name + "_FACES " + std::to_string(group.tag) +
                " " + (one_line.empty() ? name : one_line) + "\n");
    nodes.clear();
    for (uint32_t i : group.triangles) {
      for (uint32_t v : surfaces.surface[i].v) nodes.push_back(v);
    }
    std::sort(nodes.begin(), nodes.end());
    nodes.erase(std::unique(nodes.begin(), nodes.end()), nodes.end());
    out->append("*NSET, NSET=" + name + "\n");
    for (size_t i = 0; i < nodes.size(); ++i) {  // at most 16 entries per data line
      append_number(out, nodes[i] + 1);
      out->append(i + 1 == nodes.size() || i % 16 == 15 ? "\n" : ", ");
    }
    out->append("*SURFACE, TYPE=ELEMENT, NAME=" + name + "_FACES\n");
    for (uint32_t i : group.triangles) {
      const SurfaceTriangle& t = surfaces.surface[i];
      append_number(out, t.tet + 1);
      out->append(", ");
      out->append(kFaceLabel[t.corner]);
      out->push_back('\n');
    }
  }
}

}  // namespace

Status parse_abaqus(std::string_view text, const std::string& name, ParsedMesh* out) {
  AbaqusParser parser(text, name, out);
  return parser.parse();
}

void write_abaqus(const TetMesh& mesh, const SurfaceGroups* surfaces,
                  const std::vector<MaterialName>* names, std::string* out) {
  out->reserve(out->size() + mesh.vertex_count() * 64 + mesh.tet_count() * 48);
  out->append("*HEADING\nTetLOD tetrahedral mesh: ");
  append_number(out, mesh.vertex_count());
  out->append(" nodes, ");
  append_number(out, mesh.tet_count());
  out->append(
      " C3D4 elements, one element set per material (MATERIAL_<id>, or the "
      "material's name ending in its id)");
  if (surfaces) out->append(", a node set and a surface (<name>_FACES) per surface group");
  out->push_back('\n');
  // The names as they were (a label has no spaces and ends in the id), in comments,
  // for TetLOD to read back.
  if (names) {
    std::vector<int32_t> materials(mesh.materials.begin(), mesh.materials.end());
    std::sort(materials.begin(), materials.end());
    materials.erase(std::unique(materials.begin(), materials.end()), materials.end());
    for (int32_t m : materials) {
      const std::string* name = find_material_name(names, m);
      if (!name || name->empty()) continue;
      std::string one_line = *name;
      for (char& c : one_line)
        if (c == '\n' || c == '\r') c = ' ';
      out->append(std::string(kMaterialNameComment) + material_set_name(m, names) + " " +
                  std::to_string(m) + " " + one_line + "\n");
    }
  }
  out->append("*NODE\n");
  for (size_t v = 0; v < mesh.vertex_count(); ++v) {
    const Vec3& p = mesh.positions[v];
    append_number(out, v + 1);
    for (int k = 0; k < 3; ++k) {
      out->append(", ");
      append_inp_real(out, p[k]);
    }
    out->push_back('\n');
  }
  // One *ELEMENT block per material, in order of the materials' ids; element ids
  // are the tets' positions in the mesh.
  std::vector<uint32_t> order(mesh.tet_count());
  for (uint32_t t = 0; t < order.size(); ++t) order[t] = t;
  std::stable_sort(order.begin(), order.end(),
                   [&](uint32_t a, uint32_t b) { return mesh.materials[a] < mesh.materials[b]; });
  for (size_t i = 0; i < order.size(); ++i) {
    const uint32_t t = order[i];
    if (i == 0 || mesh.materials[t] != mesh.materials[order[i - 1]]) {
      out->append("*ELEMENT, TYPE=C3D4, ELSET=" + material_set_name(mesh.materials[t], names) +
                  "\n");
    }
    append_number(out, t + 1);
    for (uint32_t v : mesh.tets[t]) {
      out->append(", ");
      append_number(out, v + 1);
    }
    out->push_back('\n');
  }
  if (surfaces) write_abaqus_surfaces(*surfaces, out);
}

}  // namespace tetlod::io
