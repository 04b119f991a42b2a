// Gmsh MSH ASCII 2.2 and 4.1 (.msh), as specified in the Gmsh reference manual,
// section "MSH file format" (https://gmsh.info/doc/texinfo/gmsh.html).
#include <algorithm>
#include <limits>
#include <numeric>
#include <unordered_map>

#include "core/io/mesh_formats.h"
#include "core/io/text_scanner.h"
#include "core/io/text_writer.h"

namespace tetlod::io {
namespace {

constexpr int64_t kTet4 = 4;
constexpr int64_t kTet10 = 11;
constexpr int64_t kMaxTag = std::numeric_limits<int64_t>::max();
constexpr const char* kMaterialPrefix = "material_";

// Nodes of the element types of the manual's list (1..31, 92, 93); 0 if unknown.
int nodes_per_element(int64_t type) {
  static constexpr int kNodes[32] = {0, 2,  3,  4,  4, 8,  6,  5,  3,  6,  9, 10, 27, 18, 14, 1,
                                     8, 20, 15, 13, 9, 10, 12, 15, 15, 21, 4, 5,  6,  20, 35, 56};
  if (type >= 1 && type <= 31) return kNodes[type];
  if (type == 92) return 64;
  if (type == 93) return 125;
  return 0;
}

// "material_<n>" with 0 <= n <= INT32_MAX gives n; else -1.
int64_t material_from_name(std::string_view name) {
  const std::string_view prefix = kMaterialPrefix;
  if (name.size() <= prefix.size() || name.size() > prefix.size() + 10 ||
      name.substr(0, prefix.size()) != prefix) {
    return -1;
  }
  int64_t value = 0;
  for (char c : name.substr(prefix.size())) {
    if (c < '0' || c > '9') return -1;
    value = value * 10 + (c - '0');
  }
  return value <= std::numeric_limits<int32_t>::max() ? value : -1;
}

class GmshParser {
 public:
  GmshParser(std::string_view text, const std::string& name, ParsedMesh* out)
      : scanner_(text, name), out_(out) {}

  Status parse(int* version) {
    if (!parse_header()) return scanner_.status();
    std::string_view section;
    while (!scanner_.failed() && scanner_.next_token(&section)) {
      if (section == "$PhysicalNames") {
        if (!seen_elements_) {
          parse_physical_names();
        } else {
          scanner_.fail("$PhysicalNames after $Elements is not supported");
        }
      } else if (section == "$Entities" && version_ == 41) {
        if (!seen_elements_) {
          parse_entities();
        } else {
          scanner_.fail("$Entities after $Elements is not supported");
        }
      } else if (section == "$Nodes") {
        if (seen_nodes_) {
          scanner_.fail("a second $Nodes section");
        } else if (version_ == 22 ? parse_nodes_22() : parse_nodes_41()) {
          seen_nodes_ = true;
          finish_nodes();
        }
      } else if (section == "$Elements") {
        if (!seen_nodes_ || seen_elements_) {
          scanner_.fail(seen_elements_ ? "a second $Elements section" : "$Elements before $Nodes");
        } else if (version_ == 22 ? parse_elements_22() : parse_elements_41()) {
          seen_elements_ = true;
          finish_elements();
        }
      } else if (section.size() > 1 && section[0] == '$' && section.substr(0, 4) != "$End") {
        skip_section(section);
      } else {
        scanner_.fail("expected a section such as '$Nodes', found " + TextScanner::quote(section));
      }
    }
    if (scanner_.failed()) return scanner_.status();
    if (!seen_elements_) return Status::error(scanner_.name() + ": no $Elements section");
    *version = version_;
    return Status();
  }

 private:
  bool parse_header() {
    std::string_view token;
    if (!scanner_.next_token(&token) || token != "$MeshFormat") {
      return scanner_.fail("not a Gmsh file: expected '$MeshFormat' first");
    }
    double number = 0;
    int64_t file_type = 0, data_size = 0;
    std::string_view version_text;
    scanner_.peek_token(&version_text);
    if (!scanner_.read_double(&number, "format version") ||
        !scanner_.read_int(&file_type, "file type") ||
        !scanner_.read_int(&data_size, "data size")) {
      return false;
    }
    if (file_type != 0) {
      return scanner_.fail("binary .msh is not supported; save the mesh as ASCII");
    }
    if (number >= 2 && number < 3) {
      version_ = 22;
    } else if (number == 4.1) {
      version_ = 41;
    } else {
      return scanner_.fail("unsupported .msh version " + TextScanner::quote(version_text) +
                           " (supported: 2.2 and 4.1)");
    }
    return expect_end("$EndMeshFormat");
  }

  bool expect_end(const char* marker) {
    std::string_view token;
    if (!scanner_.next_token(&token)) {
      return scanner_.fail(std::string("unexpected end of file, expected '") + marker + "'");
    }
    if (token != marker) {
      return scanner_.fail(std::string("expected '") + marker + "', found " +
                           TextScanner::quote(token) + " (wrong count?)");
    }
    return true;
  }

  bool skip_section(std::string_view section) {
    const size_t start_line = scanner_.line();
    const std::string end_marker = "$End" + std::string(section.substr(1));
    std::string_view token;
    while (scanner_.next_token(&token)) {
      if (token == end_marker) return true;
    }
    return scanner_.fail_at_line(
        start_line, "section " + TextScanner::quote(section) + " has no '" + end_marker + "'");
  }

  bool parse_physical_names() {
    uint64_t count = 0;
    if (!scanner_.read_count(&count, "physical name count", 6)) return false;
    for (uint64_t i = 0; i < count; ++i) {
      int64_t dimension = 0, tag = 0;
      if (!scanner_.read_int(&dimension, "physical dimension") ||
          !scanner_.read_int(&tag, "physical tag")) {
        return false;
      }
      std::string_view name = scanner_.rest_of_line();
      while (!name.empty() && (name.front() == ' ' || name.front() == '\t')) name.remove_prefix(1);
      while (!name.empty() && (name.back() == ' ' || name.back() == '\t')) name.remove_suffix(1);
      if (name.size() >= 2 && name.front() == '"' && name.back() == '"') {
        name = name.substr(1, name.size() - 2);
      }
      const int64_t material = material_from_name(name);
      if (dimension == 3 && material >= 0) named_materials_[tag] = material;
    }
    return expect_end("$EndPhysicalNames");
  }

  // Reads "numPhysicalTags tag..." and returns the first tag (0 if none).
  bool read_physical_tags(int64_t* first) {
    uint64_t count = 0;
    if (!scanner_.read_count(&count, "physical tag count", 2)) return false;
    *first = 0;
    for (uint64_t i = 0; i < count; ++i) {
      int64_t tag = 0;
      if (!scanner_.read_int(&tag, "physical tag")) return false;
      if (i == 0) *first = tag;
    }
    return true;
  }

  bool parse_entities() {
    uint64_t counts[4] = {};
    const char* names[4] = {"point entity count", "curve entity count", "surface entity count",
                            "volume entity count"};
    for (int d = 0; d < 4; ++d) {
      // An entity line takes at least 8 bytes ("1 0 0 0\n").
      if (!scanner_.read_count(&counts[d], names[d], 8)) return false;
    }
    for (int dimension = 0; dimension < 4; ++dimension) {
      for (uint64_t i = 0; i < counts[dimension]; ++i) {
        int64_t tag = 0, physical = 0;
        double coordinate = 0;
        if (!scanner_.read_int(&tag, "entity tag")) return false;
        // A point has X Y Z, other entities a bounding box.
        for (int k = 0; k < (dimension == 0 ? 3 : 6); ++k) {
          if (!scanner_.read_double(&coordinate, "entity bounding box")) return false;
        }
        if (!read_physical_tags(&physical)) return false;
        if (dimension > 0) {
          uint64_t bounding = 0;
          if (!scanner_.read_count(&bounding, "bounding entity count", 2) ||
              !scanner_.skip_numbers(bounding, "bounding entity tags")) {
            return false;
          }
        }
        if (dimension == 3) volume_physical_[tag] = physical;
      }
    }
    return expect_end("$EndEntities");
  }

  bool read_node_tag() {
    int64_t tag = 0;
    if (!scanner_.read_int_in_range(&tag, "node tag", 1, kMaxTag)) return false;
    node_tags_.push_back(uint64_t(tag));
    node_lines_.push_back(line_number(scanner_.line()));
    return true;
  }

  bool read_position() {
    Vec3 p;
    if (!scanner_.read_double(&p.x, "x coordinate") ||
        !scanner_.read_double(&p.y, "y coordinate") ||
        !scanner_.read_double(&p.z, "z coordinate")) {
      return false;
    }
    out_->mesh.positions.push_back(p);
    return true;
  }

  bool reserve_nodes(uint64_t count) {
    if (count >= kInvalidIndex) return scanner_.fail("too many nodes");
    out_->mesh.positions.reserve(count);
    node_tags_.reserve(count);
    node_lines_.reserve(count);
    return true;
  }

  bool parse_nodes_22() {
    uint64_t count = 0;
    // "tag x y z\n" takes at least 8 bytes.
    if (!scanner_.read_count(&count, "node count", 8) || !reserve_nodes(count)) return false;
    for (uint64_t i = 0; i < count; ++i) {
      if (!read_node_tag() || !read_position()) return false;
    }
    return expect_end("$EndNodes");
  }

  bool parse_nodes_41() {
    uint64_t block_count = 0, count = 0;
    int64_t min_tag = 0, max_tag = 0;
    if (!scanner_.read_count(&block_count, "entity block count", 8) ||
        !scanner_.read_count(&count, "node count", 8) ||
        !scanner_.read_int(&min_tag, "minimum node tag") ||
        !scanner_.read_int(&max_tag, "maximum node tag") || !reserve_nodes(count)) {
      return false;
    }
    for (uint64_t block = 0; block < block_count; ++block) {
      int64_t dimension = 0, entity = 0, parametric = 0;
      uint64_t block_size = 0;
      if (!scanner_.read_int_in_range(&dimension, "entity dimension", 0, 3) ||
          !scanner_.read_int(&entity, "entity tag") ||
          !scanner_.read_int_in_range(&parametric, "parametric flag", 0, 1) ||
          !scanner_.read_count(&block_size, "node count of the block", 8)) {
        return false;
      }
      if (block_size > count - node_tags_.size()) {
        return scanner_.fail("the node blocks hold more nodes than the " + std::to_string(count) +
                             " of the $Nodes header");
      }
      for (uint64_t i = 0; i < block_size; ++i) {
        if (!read_node_tag()) return false;
      }
      const uint64_t parameters = parametric ? uint64_t(dimension) : 0;
      for (uint64_t i = 0; i < block_size; ++i) {
        if (!read_position() || !scanner_.skip_numbers(parameters, "parametric coordinates")) {
          return false;
        }
      }
    }
    if (node_tags_.size() != count) {
      return scanner_.fail("the node blocks hold " + std::to_string(node_tags_.size()) +
                           " nodes, the $Nodes header says " + std::to_string(count));
    }
    return expect_end("$EndNodes");
  }

  // Orders the nodes by tag, rejects repeated tags and builds the tag lookup.
  bool finish_nodes() {
    TetMesh& mesh = out_->mesh;
    const size_t count = node_tags_.size();
    if (!std::is_sorted(node_tags_.begin(), node_tags_.end())) {
      std::vector<uint32_t> order(count);
      std::iota(order.begin(), order.end(), 0u);
      std::stable_sort(order.begin(), order.end(),
                       [&](uint32_t a, uint32_t b) { return node_tags_[a] < node_tags_[b]; });
      std::vector<uint64_t> tags(count);
      std::vector<uint32_t> lines(count);
      std::vector<Vec3> positions(count);
      for (size_t i = 0; i < count; ++i) {
        tags[i] = node_tags_[order[i]];
        lines[i] = node_lines_[order[i]];
        positions[i] = mesh.positions[order[i]];
      }
      node_tags_.swap(tags);
      node_lines_.swap(lines);
      mesh.positions.swap(positions);
    }
    for (size_t i = 1; i < count; ++i) {
      if (node_tags_[i] == node_tags_[i - 1]) {
        return scanner_.fail_at_line(
            node_lines_[i], "node tag " + std::to_string(node_tags_[i]) + " is defined twice");
      }
    }
    node_lines_ = {};
    // Dense lookup when the tags are compact enough, else binary search.
    if (count > 0 && node_tags_.back() - node_tags_.front() < 4 * uint64_t(count) + 1024) {
      first_tag_ = node_tags_.front();
      dense_index_.assign(node_tags_.back() - first_tag_ + 1, kInvalidIndex);
      for (size_t i = 0; i < count; ++i) dense_index_[node_tags_[i] - first_tag_] = uint32_t(i);
    }
    return true;
  }

  uint32_t find_node(int64_t tag) const {
    const uint64_t key = uint64_t(tag);
    if (!dense_index_.empty()) {
      if (tag < 1 || key < first_tag_ || key - first_tag_ >= dense_index_.size()) {
        return kInvalidIndex;
      }
      return dense_index_[key - first_tag_];
    }
    const auto it = std::lower_bound(node_tags_.begin(), node_tags_.end(), key);
    if (tag < 1 || it == node_tags_.end() || *it != key) return kInvalidIndex;
    return uint32_t(it - node_tags_.begin());
  }

  // Material of a tet from its physical tag (0: none) and elementary tag.
  bool resolve_material(int64_t physical, int64_t elementary, int32_t* material) {
    int64_t value = elementary;
    if (physical != 0) {
      const auto it = named_materials_.find(physical);
      value = it != named_materials_.end() ? it->second : physical;
    }
    if (value < std::numeric_limits<int32_t>::min() ||
        value > std::numeric_limits<int32_t>::max()) {
      return scanner_.fail("material id " + std::to_string(value) + " is out of range");
    }
    *material = int32_t(value);
    return true;
  }

  // Reads the node tags of a tet element (4 or 10 nodes) and stores its corners.
  bool read_tet(int64_t element_tag, int64_t type, int32_t material, size_t line) {
    Tet tet;
    for (int k = 0; k < 4; ++k) {
      int64_t tag = 0;
      if (!scanner_.read_int(&tag, "node tag")) return false;
      tet[k] = find_node(tag);
      if (tet[k] == kInvalidIndex) {
        return scanner_.fail("element " + std::to_string(element_tag) + " uses node " +
                             std::to_string(tag) + ", which is not in $Nodes");
      }
    }
    if (type == kTet10 && !scanner_.skip_numbers(6, "node tags")) return false;
    if (out_->mesh.tets.size() + 1 >= kInvalidIndex) return scanner_.fail("too many tetrahedra");
    out_->mesh.tets.push_back(tet);
    out_->mesh.materials.push_back(material);
    out_->tet_lines.push_back(line_number(line));
    element_tags_.push_back(element_tag);
    return true;
  }

  // Skips the nodes of an element that is not a tet.
  bool skip_element_nodes(int64_t type) {
    const int nodes = nodes_per_element(type);
    if (nodes > 0) return scanner_.skip_numbers(uint64_t(nodes), "node tags");
    // Unknown type: Gmsh writes one element per line.
    scanner_.rest_of_line();
    return true;
  }

  bool parse_elements_22() {
    uint64_t count = 0;
    // "tag type 0 node\n" takes at least 8 bytes.
    if (!scanner_.read_count(&count, "element count", 8)) return false;
    for (uint64_t i = 0; i < count; ++i) {
      int64_t element_tag = 0, type = 0, physical = 0, elementary = 0, value = 0;
      uint64_t tag_count = 0;
      if (!scanner_.read_int(&element_tag, "element tag")) return false;
      const size_t line = scanner_.line();
      if (!scanner_.read_int(&type, "element type") ||
          !scanner_.read_count(&tag_count, "element tag count", 2)) {
        return false;
      }
      for (uint64_t k = 0; k < tag_count; ++k) {
        if (!scanner_.read_int(&value, "element tag")) return false;
        if (k == 0) physical = value;
        if (k == 1) elementary = value;
      }
      if (type == kTet4 || type == kTet10) {
        int32_t material = 0;
        if (!resolve_material(physical, elementary, &material) ||
            !read_tet(element_tag, type, material, line)) {
          return false;
        }
      } else if (!skip_element_nodes(type)) {
        return false;
      }
    }
    return expect_end("$EndElements");
  }

  bool parse_elements_41() {
    uint64_t block_count = 0, count = 0, elements_read = 0;
    int64_t min_tag = 0, max_tag = 0;
    if (!scanner_.read_count(&block_count, "entity block count", 8) ||
        !scanner_.read_count(&count, "element count", 4) ||
        !scanner_.read_int(&min_tag, "minimum element tag") ||
        !scanner_.read_int(&max_tag, "maximum element tag")) {
      return false;
    }
    for (uint64_t block = 0; block < block_count; ++block) {
      int64_t dimension = 0, entity = 0, type = 0;
      uint64_t block_size = 0;
      if (!scanner_.read_int_in_range(&dimension, "entity dimension", 0, 3) ||
          !scanner_.read_int(&entity, "entity tag") || !scanner_.read_int(&type, "element type") ||
          !scanner_.read_count(&block_size, "element count of the block", 4)) {
        return false;
      }
      if (block_size > count - elements_read) {
        return scanner_.fail("the element blocks hold more elements than the " +
                             std::to_string(count) + " of the $Elements header");
      }
      elements_read += block_size;
      const bool is_tet = type == kTet4 || type == kTet10;
      int32_t material = 0;
      if (is_tet) {
        const auto it = volume_physical_.find(entity);
        if (!resolve_material(it != volume_physical_.end() ? it->second : 0, entity, &material)) {
          return false;
        }
      }
      for (uint64_t i = 0; i < block_size; ++i) {
        int64_t element_tag = 0;
        if (!scanner_.read_int(&element_tag, "element tag")) return false;
        const bool ok = is_tet ? read_tet(element_tag, type, material, scanner_.line())
                               : skip_element_nodes(type);
        if (!ok) return false;
      }
    }
    if (elements_read != count) {
      return scanner_.fail("the element blocks hold " + std::to_string(elements_read) +
                           " elements, the $Elements header says " + std::to_string(count));
    }
    return expect_end("$EndElements");
  }

  // Orders the tets by element tag and rejects repeated tags.
  bool finish_elements() {
    TetMesh& mesh = out_->mesh;
    const size_t count = mesh.tets.size();
    std::vector<uint32_t> order(count);
    std::iota(order.begin(), order.end(), 0u);
    if (!std::is_sorted(element_tags_.begin(), element_tags_.end())) {
      std::stable_sort(order.begin(), order.end(),
                       [&](uint32_t a, uint32_t b) { return element_tags_[a] < element_tags_[b]; });
    }
    for (size_t i = 1; i < count; ++i) {
      if (element_tags_[order[i]] == element_tags_[order[i - 1]]) {
        return scanner_.fail_at_line(
            out_->tet_lines[order[i]],
            "element tag " + std::to_string(element_tags_[order[i]]) + " is used twice");
      }
    }
    if (std::is_sorted(element_tags_.begin(), element_tags_.end())) return true;
    std::vector<Tet> tets(count);
    std::vector<int32_t> materials(count);
    std::vector<uint32_t> lines(count);
    for (size_t i = 0; i < count; ++i) {
      tets[i] = mesh.tets[order[i]];
      materials[i] = mesh.materials[order[i]];
      lines[i] = out_->tet_lines[order[i]];
    }
    mesh.tets.swap(tets);
    mesh.materials.swap(materials);
    out_->tet_lines.swap(lines);
    return true;
  }

  TextScanner scanner_;
  ParsedMesh* out_;
  int version_ = 0;
  bool seen_nodes_ = false;
  bool seen_elements_ = false;
  std::unordered_map<int64_t, int64_t> named_materials_;  // physical tag -> "material_<n>"
  std::unordered_map<int64_t, int64_t> volume_physical_;  // volume entity -> first physical tag
  std::vector<uint64_t> node_tags_;                       // sorted by finish_nodes()
  std::vector<uint32_t> node_lines_;
  uint64_t first_tag_ = 0;
  std::vector<uint32_t> dense_index_;  // node tag - first_tag_ -> vertex, when compact
  std::vector<int64_t> element_tags_;  // per tet
};

void append_physical_names(const std::vector<int32_t>& materials,
                           const std::vector<int32_t>& physical_tags, std::string* out) {
  out->append("$PhysicalNames\n");
  append_line(out, materials.size());
  for (size_t i = 0; i < materials.size(); ++i) {
    out->append("3 ");
    append_number(out, physical_tags[i]);
    out->append(" \"");
    out->append(kMaterialPrefix);
    append_number(out, materials[i]);
    out->append("\"\n");
  }
  out->append("$EndPhysicalNames\n");
}

}  // namespace

Status parse_gmsh(std::string_view text, const std::string& name, ParsedMesh* out, int* version) {
  GmshParser parser(text, name, out);
  return parser.parse(version);
}

void write_gmsh(const TetMesh& mesh, int version, std::string* out) {
  // Distinct materials and their physical tags: m for m > 0; 0 takes the smallest
  // positive tag no material uses.
  std::vector<int32_t> materials = mesh.materials;
  std::sort(materials.begin(), materials.end());
  materials.erase(std::unique(materials.begin(), materials.end()), materials.end());
  int32_t zero_tag = 1;
  for (int32_t m : materials) {
    if (m == zero_tag) ++zero_tag;
  }
  std::vector<int32_t> physical_tags(materials.size());
  for (size_t i = 0; i < materials.size(); ++i) {
    physical_tags[i] = materials[i] > 0 ? materials[i] : zero_tag;
  }
  auto group_of = [&](int32_t material) {
    return size_t(std::lower_bound(materials.begin(), materials.end(), material) -
                  materials.begin());
  };

  out->reserve(out->size() + mesh.vertex_count() * 64 + mesh.tet_count() * 48);
  out->append(version == 22 ? "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n"
                            : "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n");
  append_physical_names(materials, physical_tags, out);

  if (version == 22) {
    out->append("$Nodes\n");
    append_line(out, mesh.vertex_count());
    for (size_t v = 0; v < mesh.vertex_count(); ++v) {
      const Vec3& p = mesh.positions[v];
      append_line(out, v + 1, p.x, p.y, p.z);
    }
    out->append("$EndNodes\n$Elements\n");
    append_line(out, mesh.tet_count());
    for (size_t t = 0; t < mesh.tet_count(); ++t) {
      const Tet& tet = mesh.tets[t];
      const int32_t tag = physical_tags[group_of(mesh.materials[t])];
      append_line(out, t + 1, kTet4, 2, tag, tag, tet[0] + 1, tet[1] + 1, tet[2] + 1, tet[3] + 1);
    }
    out->append("$EndElements\n");
    return;
  }

  // 4.1: one volume entity per material (entity tag = physical tag). Tets are
  // grouped by material; each node goes into the block of the first group using it.
  const size_t group_count = materials.size();
  std::vector<uint32_t> tet_group(mesh.tet_count());
  std::vector<size_t> group_tet_start(group_count + 1, 0);
  for (size_t t = 0; t < mesh.tet_count(); ++t) {
    tet_group[t] = uint32_t(group_of(mesh.materials[t]));
    ++group_tet_start[tet_group[t] + 1];
  }
  std::partial_sum(group_tet_start.begin(), group_tet_start.end(), group_tet_start.begin());
  std::vector<uint32_t> tet_order(mesh.tet_count());
  {
    std::vector<size_t> next(group_tet_start.begin(), group_tet_start.end() - 1);
    for (size_t t = 0; t < mesh.tet_count(); ++t) tet_order[next[tet_group[t]]++] = uint32_t(t);
  }
  std::vector<Vec3> box_min(group_count, mesh.positions.empty() ? Vec3{} : mesh.positions[0]);
  std::vector<Vec3> box_max = box_min;
  std::vector<bool> box_empty(group_count, true);
  // Vertices no tet uses (not in a valid mesh) go with the first group.
  std::vector<uint32_t> vertex_group(mesh.vertex_count(), 0);
  std::vector<bool> assigned(mesh.vertex_count(), false);
  for (uint32_t t : tet_order) {
    const uint32_t group = tet_group[t];
    for (uint32_t v : mesh.tets[t]) {
      const Vec3& p = mesh.positions[v];
      if (box_empty[group]) {
        box_min[group] = box_max[group] = p;
        box_empty[group] = false;
      }
      for (int k = 0; k < 3; ++k) {
        box_min[group][k] = std::min(box_min[group][k], p[k]);
        box_max[group][k] = std::max(box_max[group][k], p[k]);
      }
      if (!assigned[v]) {
        assigned[v] = true;
        vertex_group[v] = group;
      }
    }
  }
  std::vector<std::vector<uint32_t>> group_vertices(group_count);
  for (size_t v = 0; v < mesh.vertex_count(); ++v) {
    group_vertices[vertex_group[v]].push_back(uint32_t(v));
  }
  size_t node_block_count = 0;
  for (const auto& vertices : group_vertices) node_block_count += vertices.empty() ? 0 : 1;

  out->append("$Entities\n");
  append_line(out, 0, 0, 0, group_count);
  for (size_t g = 0; g < group_count; ++g) {
    const Vec3& lo = box_min[g];
    const Vec3& hi = box_max[g];
    append_line(out, physical_tags[g], lo.x, lo.y, lo.z, hi.x, hi.y, hi.z, 1, physical_tags[g], 0);
  }
  out->append("$EndEntities\n$Nodes\n");
  append_line(out, node_block_count, mesh.vertex_count(), mesh.vertex_count() > 0 ? 1 : 0,
              mesh.vertex_count());
  for (size_t g = 0; g < group_count; ++g) {
    const std::vector<uint32_t>& vertices = group_vertices[g];
    if (vertices.empty()) continue;
    append_line(out, 3, physical_tags[g], 0, vertices.size());
    for (uint32_t v : vertices) append_line(out, v + 1);
    for (uint32_t v : vertices) {
      const Vec3& p = mesh.positions[v];
      append_line(out, p.x, p.y, p.z);
    }
  }
  out->append("$EndNodes\n$Elements\n");
  append_line(out, group_count, mesh.tet_count(), mesh.tet_count() > 0 ? 1 : 0, mesh.tet_count());
  for (size_t g = 0; g < group_count; ++g) {
    append_line(out, 3, physical_tags[g], kTet4, group_tet_start[g + 1] - group_tet_start[g]);
    for (size_t i = group_tet_start[g]; i < group_tet_start[g + 1]; ++i) {
      const uint32_t t = tet_order[i];
      const Tet& tet = mesh.tets[t];
      append_line(out, t + 1, tet[0] + 1, tet[1] + 1, tet[2] + 1, tet[3] + 1);
    }
  }
  out->append("$EndElements\n");
}

}  // namespace tetlod::io
