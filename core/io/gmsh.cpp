// Gmsh MSH 2.2 and 4.1 (.msh), ASCII and binary, as specified in the Gmsh reference
// manual, section "MSH file format" (https://gmsh.info/doc/texinfo/gmsh.html).
// TetLOD writes ASCII.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <limits>
#include <map>
#include <numeric>
#include <set>
#include <unordered_map>
#include <unordered_set>

#include "core/io/mesh_formats.h"
#include "core/io/text_scanner.h"
#include "core/io/text_writer.h"

namespace tetlod::io {
namespace {

constexpr int64_t kTet4 = 4;
constexpr int64_t kTriangle3 = 2;
constexpr int64_t kTet10 = 11;

// Nodes of an element type (Gmsh's GmshDefines.h, as Gmsh 4 numbers them: the
// manual's list 1..31, 92 and 93, and the higher orders of tets, triangles,
// quadrangles and lines; 0 if unknown.
int nodes_per_element(int64_t type) {
  static constexpr int kNodes[84] = {
      0,  2,  3,  4,  4,  8,  6,  5,  3,   6,   9,   10,  27,  18, 14, 1,  8,  20, 15, 13, 9,
      10, 12, 15, 15, 21, 4,  5,  6,  20,  35,  56,  22,  28,  0,  0,  16, 25, 36, 12, 16, 20,
      28, 36, 45, 55, 66, 49, 64, 81, 100, 121, 18,  21,  24,  27, 30, 24, 28, 32, 36, 40, 7,
      8,  9,  10, 11, 0,  0,  0,  0,  84,  120, 165, 220, 286, 0,  0,  0,  34, 40, 46, 52, 58};
  // 84 to 140: first-order "_1" elements, then prisms, hexahedra and pyramids of higher
  // orders (the node count is the name's number), the sub-elements (unknown), and the
  // 16-node tet, mini-elements and the 4-node triangle.
  static constexpr int kMore[57] = {
      1,   1,   1,   1,   1,   1,   40,  75,  64, 125, 216, 343, 512, 729, 1000, 32, 44, 56, 68,
      80,  92,  104, 126, 196, 288, 405, 550, 24, 33,  42,  51,  60,  69,  78,   30, 55, 91, 140,
      204, 285, 385, 21,  29,  37,  45,  53,  61, 69,  1,   0,   0,   0,   0,    16, 4,  5,  4};
  if (type >= 1 && type < 84) return kNodes[type];
  if (type >= 84 && type <= 140) return kMore[type - 84];
  return 0;
}

// Tets of any order, complete or not (4 to 286 nodes): Gmsh lists their corners first,
// and they are read by them.
bool is_tet_type(int64_t type) {
  return type == kTet4 || type == kTet10 || (type >= 29 && type <= 33) ||
         (type >= 71 && type <= 75) || (type >= 79 && type <= 83) || type == 137;
}
// Triangles of any order (3 to 66 nodes): their corners come first.
bool is_triangle_type(int64_t type) {
  return type == kTriangle3 || type == 9 || (type >= 20 && type <= 25) ||
         (type >= 42 && type <= 46) || (type >= 52 && type <= 56);
}
// Quadrangles of any order (4 to 121 nodes).
bool is_quadrangle_type(int64_t type) {
  return type == 3 || type == 10 || type == 16 || (type >= 36 && type <= 41) ||
         (type >= 47 && type <= 51) || (type >= 57 && type <= 61);
}
constexpr int64_t kMaxTag = std::numeric_limits<int64_t>::max();
constexpr const char* kMaterialPrefix = "material_";

// What a reader that keeps only tets says of the elements it skips:
// the plural name of a volume or surface element type, nullptr for other types
// (points, lines), which a tet mesh's file holds as a matter of course.
const char* skipped_volume_elements(int64_t type) {
  if (type == 5 || type == 12 || type == 17 || type == 88 || (type >= 92 && type <= 105))
    return "hexahedra";
  if (type == 6 || type == 13 || type == 18 || (type >= 89 && type <= 91) ||
      (type >= 106 && type <= 117))
    return "prisms";
  if (type == 7 || type == 14 || type == 19 || (type >= 118 && type <= 132)) return "pyramids";
  return nullptr;
}
bool is_surface_element(int64_t type) {
  return is_triangle_type(type) || is_quadrangle_type(type);
}

// "material_<n>" with 0 <= n <= INT32_MAX, written as TetLOD writes it (no leading
// zero: "material_00" is a name), gives n; else -1.
int64_t material_from_name(std::string_view name) {
  const std::string_view prefix = kMaterialPrefix;
  if (name.size() <= prefix.size() || name.size() > prefix.size() + 10 ||
      name.substr(0, prefix.size()) != prefix ||
      (name[prefix.size()] == '0' && name.size() > prefix.size() + 1)) {
    return -1;
  }
  int64_t value = 0;
  for (char c : name.substr(prefix.size())) {
    if (c < '0' || c > '9') return -1;
    value = value * 10 + (c - '0');
  }
  return value <= std::numeric_limits<int32_t>::max() ? value : -1;
}

// The numbers of a binary section, read in the file's byte order: int (4 bytes),
// double (8) and, in 4.1, size_t (8). A read past the end returns 0 and clears ok().
class BinaryCursor {
 public:
  BinaryCursor(std::string_view data, bool swap) : data_(data), swap_(swap) {}

  int32_t i32() { return get<int32_t>(); }
  uint64_t u64() { return get<uint64_t>(); }
  double f64() { return get<double>(); }
  // True if `count` items of `bytes_each` bytes fit in what is left.
  bool fits(uint64_t count, uint64_t bytes_each) const {
    return bytes_each == 0 || count <= (data_.size() - at_) / bytes_each;
  }
  bool ok() const { return ok_; }
  size_t used() const { return at_; }

 private:
  template <typename T>
  T get() {
    T value{};
    if (data_.size() - at_ < sizeof(T)) {
      ok_ = false;
      at_ = data_.size();
      return value;
    }
    unsigned char bytes[sizeof(T)];
    std::memcpy(bytes, data_.data() + at_, sizeof(T));
    if (swap_) std::reverse(bytes, bytes + sizeof(T));
    std::memcpy(&value, bytes, sizeof(T));
    at_ += sizeof(T);
    return value;
  }

  std::string_view data_;
  bool swap_;
  size_t at_ = 0;
  bool ok_ = true;
};

class GmshParser {
 public:
  GmshParser(std::string_view text, const std::string& name, ParsedMesh* out)
      : text_(text), scanner_(text, name), out_(out) {}

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
      } else if (section == "$PartitionedEntities" && version_ == 41) {
        if (!seen_elements_) {
          binary_ ? parse_partitioned_entities_binary() : parse_partitioned_entities();
        } else {
          scanner_.fail("$PartitionedEntities after $Elements is not supported");
        }
      } else if (section == "$Entities" && version_ == 41) {
        if (!seen_elements_) {
          binary_ ? parse_entities_binary() : parse_entities();
        } else {
          scanner_.fail("$Entities after $Elements is not supported");
        }
      } else if (section == "$Nodes") {
        if (seen_nodes_) {
          scanner_.fail("a second $Nodes section");
        } else if (binary_
                       ? (version_ == 22 ? parse_nodes_22_binary(false) : parse_nodes_41_binary())
                       : (version_ == 22 ? parse_nodes_22(false) : parse_nodes_41())) {
          seen_nodes_ = true;
          finish_nodes();
        }
      } else if (section == "$ParametricNodes" && version_ == 22) {
        // Gmsh's -setnumber Mesh.SaveParametric 1: the nodes with where they lie on
        // the geometry.
        if (seen_nodes_) {
          scanner_.fail("a second $Nodes (or $ParametricNodes) section");
        } else if (binary_ ? parse_nodes_22_binary(true) : parse_nodes_22(true)) {
          seen_nodes_ = true;
          finish_nodes();
        }
      } else if (section == "$Elements") {
        if (!seen_nodes_ || seen_elements_) {
          scanner_.fail(seen_elements_ ? "a second $Elements section" : "$Elements before $Nodes");
        } else if (binary_
                       ? (version_ == 22 ? parse_elements_22_binary() : parse_elements_41_binary())
                       : (version_ == 22 ? parse_elements_22() : parse_elements_41())) {
          seen_elements_ = true;
          finish_elements();
        }
      } else if (section.size() > 1 && section[0] == '$' && section.substr(0, 4) != "$End") {
        periodic_ = periodic_ || section == "$Periodic";
        skip_section(section);
      } else {
        scanner_.fail("expected a section such as '$Nodes', found " + TextScanner::quote(section));
      }
    }
    if (scanner_.failed()) return scanner_.status();
    if (!seen_elements_) return Status::error(scanner_.name() + ": no $Elements section");
    if (periodic_) {  // (Gmsh writes it after $Elements)
      out_->notes.push_back(
          "the $Periodic section is not kept: the nodes it matches across periodic surfaces "
          "are read as any others, and simplify does not keep them matched");
    }
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
    if (file_type != 0 && file_type != 1) {
      return scanner_.fail("file type " + std::to_string(file_type) +
                           " is not 0 (ASCII) or 1 (binary)");
    }
    if (number >= 2 && number < 3) {
      version_ = 22;
    } else if (number == 4.1) {
      version_ = 41;
    } else {
      return scanner_.fail("unsupported .msh version " + TextScanner::quote(version_text) +
                           " (supported: 2.2 and 4.1)");
    }
    if (file_type == 1 && !start_binary_file(data_size)) return false;
    return expect_end("$EndMeshFormat");
  }

  // ------------------------------------------------------------------ binary
  // A binary file has the same sections, with the numbers stored as raw values
  // (4.1: everything after each section's name; 2.2: after the count line of $Nodes
  // and $Elements). $PhysicalNames stays text.

  // Reads the binary 1 after the header line that gives the byte order.
  bool start_binary_file(int64_t data_size) {
    if (data_size != 8) {
      return scanner_.fail("binary .msh with data size " + std::to_string(data_size) +
                           " is not supported (only 8: double precision)");
    }
    if (!begin_binary()) return false;
    const std::string_view data = scanner_.remaining_text();
    int32_t one = 0;
    if (data.size() < 4) return scanner_.fail("the file ends inside the binary header");
    std::memcpy(&one, data.data(), 4);
    if (one == 1) {
      swap_ = false;
    } else if (one == 0x01000000) {
      swap_ = true;
    } else {
      return scanner_.fail("the binary header's byte-order check reads " + std::to_string(one) +
                           ", not 1");
    }
    binary_ = true;
    scanner_.advance(4);
    scanner_.report_byte_offsets(text_.data());
    return true;
  }

  // Moves past the line break that ends a text line before binary data.
  bool begin_binary() {
    const std::string_view rest = scanner_.rest_of_line();
    if (!rest.empty()) {
      return scanner_.fail("unexpected " + TextScanner::quote(rest) +
                           " before the binary data of the section");
    }
    return true;
  }

  BinaryCursor binary_cursor() const { return BinaryCursor(scanner_.remaining_text(), swap_); }

  // Moves the scanner past what `cursor` read; fails if it ran past the end.
  bool end_binary(const BinaryCursor& cursor, const char* section) {
    if (!cursor.ok()) return truncated(section);
    scanner_.advance(cursor.used());
    return true;
  }

  // The rest of the file is shorter than a section's counts say.
  bool truncated(const char* section) {
    scanner_.advance(scanner_.remaining_bytes());
    return scanner_.fail(std::string("the file ends inside the binary ") + section +
                         " section (truncated file?)");
  }

  bool fail_binary(const BinaryCursor& cursor, const std::string& message) {
    scanner_.advance(cursor.used());
    return scanner_.fail(message);
  }

  // A size_t count of items taking at least `bytes_each` bytes each.
  bool binary_count(BinaryCursor& cursor, uint64_t* count, const char* what, uint64_t bytes_each) {
    *count = cursor.u64();
    if (cursor.ok() && !cursor.fits(*count, bytes_each)) {
      return fail_binary(cursor, std::string(what) + " " + std::to_string(*count) +
                                     " is more than the rest of the file can hold");
    }
    return true;
  }

  // A partitioned mesh (gmsh -part): its elements are in partition entities, each
  // the piece of a model entity (its parent) in one partition. A partition volume
  // takes its own physical tag, else its parent volume's, and its parent's tag as
  // the elementary one.
  void add_partition_volume(int64_t tag, int64_t parent_dimension, int64_t parent,
                            int64_t physical) {
    if (parent_dimension != 3) return;
    if (physical == 0) {
      const auto it = volume_physical_.find(parent);
      if (it != volume_physical_.end()) physical = it->second;
    }
    volume_physical_[tag] = physical;
    volume_parent_[tag] = parent;
  }
  // A partition surface, likewise: its own physical tags, else its parent surface's.
  // One between two partitions (a volume as parent) is in no surface group, though
  // Gmsh gives it its volume's physical tag.
  void add_partition_surface(int64_t tag, int64_t parent_dimension, int64_t parent,
                             int64_t physical, std::vector<int64_t> others) {
    if (parent_dimension != 2) {
      physical = 0;
      others.clear();
    } else if (physical == 0) {
      physical = surface_physical_of(parent);
      if (const std::vector<int64_t>* inherited = other_physicals_of(parent)) others = *inherited;
    }
    surface_physical_[tag] = physical;
    if (!others.empty()) surface_other_physicals_[tag] = std::move(others);
  }

  bool parse_partitioned_entities() {
    uint64_t partitions = 0, ghosts = 0;
    if (!scanner_.read_count(&partitions, "partition count", 1) ||
        !scanner_.read_count(&ghosts, "ghost entity count", 4) ||
        !scanner_.skip_numbers(2 * ghosts, "ghost entities")) {
      return false;
    }
    uint64_t counts[4] = {};
    for (uint64_t& count : counts) {
      // An entity line takes at least 16 bytes ("1 0 1 1 1 0 0 0 0\n").
      if (!scanner_.read_count(&count, "partitioned entity count", 16)) return false;
    }
    for (int dimension = 0; dimension < 4; ++dimension) {
      for (uint64_t i = 0; i < counts[dimension]; ++i) {
        int64_t tag = 0, parent_dimension = 0, parent = 0, physical = 0;
        uint64_t partition_count = 0;
        std::vector<int64_t> others;
        if (!scanner_.read_int(&tag, "entity tag") ||
            !scanner_.read_int(&parent_dimension, "parent dimension") ||
            !scanner_.read_int(&parent, "parent tag") ||
            !scanner_.read_count(&partition_count, "partition count", 2) ||
            !scanner_.skip_numbers(partition_count, "partition tags") ||
            !scanner_.skip_numbers(dimension == 0 ? 3 : 6, "entity bounding box") ||
            !read_physical_tags(&physical, &others)) {
          return false;
        }
        if (dimension > 0) {
          uint64_t bounding = 0;
          if (!scanner_.read_count(&bounding, "bounding entity count", 2) ||
              !scanner_.skip_numbers(bounding, "bounding entity tags")) {
            return false;
          }
        }
        if (dimension == 3) add_partition_volume(tag, parent_dimension, parent, physical);
        if (dimension == 2)
          add_partition_surface(tag, parent_dimension, parent, physical, std::move(others));
      }
    }
    return expect_end("$EndPartitionedEntities");
  }

  // The rest of a binary (partitioned) entity after its tags: the coordinates or
  // bounding box, the physical tags (the first into `physical`, 0 if none), and for
  // curves, surfaces and volumes the bounding entities.
  // `others`, if given, receives the physical tags after the first (at most 64).
  bool binary_entity_tail(BinaryCursor& c, int dimension, int32_t* physical,
                          std::vector<int64_t>* others = nullptr) {
    for (int k = 0; k < (dimension == 0 ? 3 : 6); ++k) c.f64();
    uint64_t physical_count = 0;
    if (!binary_count(c, &physical_count, "physical tag count", 4)) return false;
    *physical = 0;
    for (uint64_t k = 0; k < physical_count; ++k) {
      const int32_t value = c.i32();
      if (k == 0) *physical = value;
      if (k > 0 && others && others->size() < 64) others->push_back(value);
    }
    if (dimension > 0) {
      uint64_t bounding = 0;
      if (!binary_count(c, &bounding, "bounding entity count", 4)) return false;
      for (uint64_t k = 0; k < bounding; ++k) c.i32();
    }
    return true;
  }

  bool parse_partitioned_entities_binary() {
    if (!begin_binary()) return false;
    BinaryCursor c = binary_cursor();
    uint64_t partitions = 0, ghosts = 0;
    if (!binary_count(c, &partitions, "partition count", 0) ||
        !binary_count(c, &ghosts, "ghost entity count", 8)) {
      return false;
    }
    for (uint64_t k = 0; k < 2 * ghosts; ++k) c.i32();
    uint64_t counts[4] = {};
    for (int d = 0; d < 4; ++d) {
      // A point takes at least 52 bytes, another entity 84.
      if (!binary_count(c, &counts[d], "partitioned entity count", d == 0 ? 52 : 84)) return false;
    }
    for (int dimension = 0; dimension < 4 && c.ok(); ++dimension) {
      for (uint64_t i = 0; i < counts[dimension] && c.ok(); ++i) {
        const int32_t tag = c.i32();
        const int32_t parent_dimension = c.i32();
        const int32_t parent = c.i32();
        uint64_t partition_count = 0;
        if (!binary_count(c, &partition_count, "partition count", 4)) return false;
        for (uint64_t k = 0; k < partition_count; ++k) c.i32();
        int32_t physical = 0;
        std::vector<int64_t> others;
        if (!binary_entity_tail(c, dimension, &physical, &others)) return false;
        if (dimension == 3 && c.ok()) add_partition_volume(tag, parent_dimension, parent, physical);
        if (dimension == 2 && c.ok())
          add_partition_surface(tag, parent_dimension, parent, physical, std::move(others));
      }
    }
    return end_binary(c, "$PartitionedEntities") && expect_end("$EndPartitionedEntities");
  }

  bool parse_entities_binary() {
    if (!begin_binary()) return false;
    BinaryCursor c = binary_cursor();
    uint64_t counts[4] = {};
    const char* names[4] = {"point entity count", "curve entity count", "surface entity count",
                            "volume entity count"};
    for (int d = 0; d < 4; ++d) {
      // A point takes at least 36 bytes, another entity 68.
      if (!binary_count(c, &counts[d], names[d], d == 0 ? 36 : 68)) return false;
    }
    for (int dimension = 0; dimension < 4 && c.ok(); ++dimension) {
      for (uint64_t i = 0; i < counts[dimension] && c.ok(); ++i) {
        const int32_t tag = c.i32();
        int32_t physical = 0;
        std::vector<int64_t> others;
        if (!binary_entity_tail(c, dimension, &physical, &others)) return false;
        if (dimension == 3) volume_physical_[tag] = physical;
        if (dimension == 2) surface_physical_[tag] = physical;
        if (dimension == 3) add_volume_groups(tag, physical, others);
        if (dimension == 2 && !others.empty()) surface_other_physicals_[tag] = std::move(others);
      }
    }
    return end_binary(c, "$Entities") && expect_end("$EndEntities");
  }

  bool add_binary_position(BinaryCursor& c) {
    Vec3 p;
    p.x = c.f64();
    p.y = c.f64();
    p.z = c.f64();
    if (c.ok() && !(std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z))) {
      return fail_binary(c, "node " + std::to_string(out_->mesh.positions.size() + 1) +
                                " has a coordinate that is not a finite number");
    }
    out_->mesh.positions.push_back(p);
    return true;
  }

  // A node takes 28 bytes (int tag, three doubles); in $ParametricNodes (as Gmsh 4.8
  // writes them with -bin) also an int dimension, an int entity and a double per
  // dimension of a curve or surface: 36 bytes at least.
  bool parse_nodes_22_binary(bool parametric) {
    const char* section = parametric ? "$ParametricNodes" : "$Nodes";
    const uint64_t least = parametric ? 36 : 28;
    uint64_t count = 0;
    if (!scanner_.read_count(&count, "node count", least) || !reserve_nodes(count) ||
        !begin_binary()) {
      return false;
    }
    BinaryCursor c = binary_cursor();
    if (!c.fits(count, least)) return truncated(section);
    for (uint64_t i = 0; i < count; ++i) {
      const int32_t tag = c.i32();
      if (tag < 1) return fail_binary(c, "node tag " + std::to_string(tag) + " is below 1");
      node_tags_.push_back(uint64_t(tag));
      if (!add_binary_position(c)) return false;
      if (!parametric) continue;
      const int32_t dimension = c.i32();
      c.i32();  // the entity
      if (dimension < 0 || dimension > 3)
        return fail_binary(c, "node " + std::to_string(tag) + ": entity dimension " +
                                  std::to_string(dimension) + " is not 0 to 3");
      for (int k = 0; k < (dimension == 1 || dimension == 2 ? dimension : 0); ++k) c.f64();
      if (!c.ok()) return truncated(section);
    }
    return end_binary(c, section) && expect_end(parametric ? "$EndParametricNodes" : "$EndNodes");
  }

  bool parse_nodes_41_binary() {
    if (!begin_binary()) return false;
    BinaryCursor c = binary_cursor();
    uint64_t block_count = 0, count = 0;
    // A block header takes 20 bytes, a node at least 32.
    if (!binary_count(c, &block_count, "entity block count", 20) ||
        !binary_count(c, &count, "node count", 32)) {
      return false;
    }
    c.u64();  // the smallest and largest node tags
    c.u64();
    if (!c.ok()) return end_binary(c, "$Nodes");
    if (!reserve_nodes(count)) return false;
    for (uint64_t block = 0; block < block_count; ++block) {
      const int32_t dimension = c.i32();
      c.i32();  // entity tag
      const int32_t parametric = c.i32();
      const uint64_t block_size = c.u64();
      if (!c.ok()) return end_binary(c, "$Nodes");
      if (dimension < 0 || dimension > 3 || parametric < 0 || parametric > 1) {
        return fail_binary(c, "node block " + std::to_string(block + 1) + " has entity dimension " +
                                  std::to_string(dimension) + " and parametric flag " +
                                  std::to_string(parametric));
      }
      if (block_size > count - node_tags_.size()) {
        return fail_binary(c, "the node blocks hold more nodes than the " + std::to_string(count) +
                                  " of the $Nodes header");
      }
      const uint64_t parameters = parametric ? uint64_t(dimension) : 0;
      if (!c.fits(block_size, 32 + 8 * parameters)) return truncated("$Nodes");
      for (uint64_t i = 0; i < block_size; ++i) {
        const uint64_t tag = c.u64();
        if (tag < 1 || tag > uint64_t(kMaxTag)) {
          return fail_binary(c, "node tag " + std::to_string(tag) + " is out of range");
        }
        node_tags_.push_back(tag);
      }
      for (uint64_t i = 0; i < block_size; ++i) {
        if (!add_binary_position(c)) return false;
        for (uint64_t k = 0; k < parameters; ++k) c.f64();
      }
    }
    if (node_tags_.size() != count) {
      return fail_binary(c, "the node blocks hold " + std::to_string(node_tags_.size()) +
                                " nodes, the $Nodes header says " + std::to_string(count));
    }
    return end_binary(c, "$Nodes") && expect_end("$EndNodes");
  }

  // The node count of an element type: a binary file gives no other way to skip it.
  bool binary_nodes_per_element(const BinaryCursor& c, int32_t type, int* nodes) {
    *nodes = nodes_per_element(type);
    if (*nodes > 0) return true;
    return fail_binary(c, "element type " + std::to_string(type) +
                              " is unknown: a binary file does not say how many nodes it has");
  }

  bool parse_elements_22_binary() {
    uint64_t count = 0;
    // An element takes at least 12 bytes (tag, no tags, one node).
    if (!scanner_.read_count(&count, "element count", 12) || !begin_binary()) return false;
    BinaryCursor c = binary_cursor();
    uint64_t read = 0;
    while (read < count) {
      // A header: element type, elements following, tags per element.
      const int32_t type = c.i32();
      const int32_t following = c.i32();
      const int32_t tag_count = c.i32();
      if (!c.ok()) return end_binary(c, "$Elements");
      int nodes = 0;
      if (!binary_nodes_per_element(c, type, &nodes)) return false;
      if (following < 1 || uint64_t(following) > count - read || tag_count < 0) {
        return fail_binary(c, "an element header gives " + std::to_string(following) +
                                  " elements with " + std::to_string(tag_count) + " tags each, " +
                                  std::to_string(count - read) + " elements being left");
      }
      const uint64_t ints = 1 + uint64_t(tag_count) + uint64_t(nodes);
      if (!c.fits(uint64_t(following), 4 * ints)) return truncated("$Elements");
      count_elements(type, uint64_t(following));
      const bool is_tet = is_tet_type(type);
      for (int32_t e = 0; e < following; ++e) {
        const int64_t element_tag = c.i32();
        int64_t physical = 0, elementary = 0;
        for (int32_t k = 0; k < tag_count; ++k) {
          const int32_t value = c.i32();
          if (k == 0) physical = value;
          if (k == 1) elementary = value;
        }
        if (is_tet) {
          int64_t corners[4];
          for (int64_t& corner : corners) corner = c.i32();
          bool others = true;
          for (int k = 4; k < nodes; ++k) others = others && other_node(element_tag, c.i32());
          int32_t material = 0;
          if (!others || !resolve_material(physical, elementary, &material) ||
              !store_tet(element_tag, corners, material, 0)) {
            scanner_.advance(c.used());
            return false;
          }
        } else {
          int64_t corners[3] = {0, 0, 0};
          for (int k = 0; k < nodes; ++k) {
            const int32_t node = c.i32();
            if (k < 3) corners[k] = node;
          }
          if (c.ok() && physical > 0 && is_triangle_type(type)) store_triangle(physical, corners);
          if (c.ok() && physical > 0 && is_quadrangle_type(type)) ++grouped_quads_[physical];
        }
      }
      read += uint64_t(following);
    }
    return end_binary(c, "$Elements") && expect_end("$EndElements");
  }

  bool parse_elements_41_binary() {
    if (!begin_binary()) return false;
    BinaryCursor c = binary_cursor();
    uint64_t block_count = 0, count = 0, elements_read = 0;
    // A block header takes 20 bytes, an element at least 16.
    if (!binary_count(c, &block_count, "entity block count", 20) ||
        !binary_count(c, &count, "element count", 16)) {
      return false;
    }
    c.u64();  // the smallest and largest element tags
    c.u64();
    // At most `count` tets (the count fits in the file): no regrowth.
    out_->mesh.tets.reserve(count);
    out_->mesh.materials.reserve(count);
    element_tags_.reserve(count);
    for (uint64_t block = 0; block < block_count; ++block) {
      const int32_t dimension = c.i32();
      const int32_t entity = c.i32();
      const int32_t type = c.i32();
      const uint64_t block_size = c.u64();
      if (!c.ok()) return end_binary(c, "$Elements");
      int nodes = 0;
      if (!binary_nodes_per_element(c, type, &nodes)) return false;
      if (block_size > count - elements_read) {
        return fail_binary(c, "the element blocks hold more elements than the " +
                                  std::to_string(count) + " of the $Elements header");
      }
      if (!c.fits(block_size, 8 * (1 + uint64_t(nodes)))) {
        return truncated("$Elements");
      }
      elements_read += block_size;
      count_elements(type, block_size);
      const bool is_tet = is_tet_type(type);
      int32_t material = 0;
      if (is_tet) {
        if (!entity_material(entity, block_size, &material)) {
          scanner_.advance(c.used());
          return false;
        }
      }
      const int64_t surface_group =
          dimension == 2 && is_triangle_type(type) ? surface_physical_of(entity) : 0;
      const std::vector<int64_t>* other_groups =
          surface_group > 0 ? other_physicals_of(entity) : nullptr;
      count_grouped_quads(dimension, entity, type, block_size);
      for (uint64_t i = 0; i < block_size; ++i) {
        const uint64_t element_tag = c.u64();
        if (!is_tet) {
          int64_t corners[3] = {0, 0, 0};
          for (int k = 0; k < nodes; ++k) {
            const uint64_t node = c.u64();
            if (k < 3) corners[k] = as_tag(node);
          }
          if (c.ok() && surface_group > 0) {
            store_triangle(surface_group, corners);
            if (other_groups)
              for (int64_t other : *other_groups) store_triangle(other, corners);
          }
          continue;
        }
        int64_t corners[4];
        for (int64_t& corner : corners) corner = as_tag(c.u64());
        bool others = true;
        for (int k = 4; k < nodes; ++k)
          others = others && other_node(as_tag(element_tag), as_tag(c.u64()));
        if (!others || !store_tet(as_tag(element_tag), corners, material, 0)) {
          scanner_.advance(c.used());
          return false;
        }
      }
    }
    if (elements_read != count) {
      return fail_binary(c, "the element blocks hold " + std::to_string(elements_read) +
                                " elements, the $Elements header says " + std::to_string(count));
    }
    return end_binary(c, "$Elements") && expect_end("$EndElements");
  }

  // A size_t tag as a signed one (-1 if it does not fit: no node has it).
  static int64_t as_tag(uint64_t tag) { return tag > uint64_t(kMaxTag) ? -1 : int64_t(tag); }

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
      // A volume group's tag is its material. "material_0" is how TetLOD writes material
      // 0, which takes another tag; "material_<tag>" is its name for a material without
      // one. Any other name is the material's, "material_<n>" too: it was taken as
      // material n, which swapped or merged groups whose names and tags disagree.
      // A second group named "material_0" (TetLOD writes one) keeps its tag: two would
      // merge.
      int64_t material = dimension == 3 ? material_from_name(name) : -1;
      if (material == 0 && !named_materials_.empty() && named_materials_.count(tag) == 0)
        material = -1;
      if (material == 0) named_materials_[tag] = 0;
      const bool default_name = material == 0 || (material > 0 && material == tag);
      if ((dimension == 2 || dimension == 3) && !default_name && physical_names_.size() < 1000) {
        std::string& kept = physical_names_[{dimension, tag}];
        std::string named = valid_utf8(name);
        if (!kept.empty() && kept != named && renamed_.size() < 10) {
          renamed_.push_back("the " + std::string(dimension == 3 ? "volume" : "surface") +
                             " group " + std::to_string(tag) + " is named '" + kept + "', then '" +
                             named + "'");
        }
        kept = std::move(named);
      }
    }
    return expect_end("$EndPhysicalNames");
  }

  // Reads "numPhysicalTags tag..." and returns the first tag (0 if none).
  // `others`, if given, receives the tags after the first (at most 64).
  bool read_physical_tags(int64_t* first, std::vector<int64_t>* others = nullptr) {
    uint64_t count = 0;
    if (!scanner_.read_count(&count, "physical tag count", 2)) return false;
    *first = 0;
    for (uint64_t i = 0; i < count; ++i) {
      int64_t tag = 0;
      if (!scanner_.read_int(&tag, "physical tag")) return false;
      if (i == 0) *first = tag;
      if (i > 0 && others && others->size() < 64) others->push_back(tag);
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
        std::vector<int64_t> others;
        if (!read_physical_tags(&physical, &others)) return false;
        if (dimension > 0) {
          uint64_t bounding = 0;
          if (!scanner_.read_count(&bounding, "bounding entity count", 2) ||
              !scanner_.skip_numbers(bounding, "bounding entity tags")) {
            return false;
          }
        }
        if (dimension == 3) volume_physical_[tag] = physical;
        if (dimension == 2) surface_physical_[tag] = physical;
        if (dimension == 3) add_volume_groups(tag, physical, others);
        if (dimension == 2 && !others.empty()) surface_other_physicals_[tag] = std::move(others);
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

  // "tag x y z\n" (at least 8 bytes); in $ParametricNodes (Gmsh's -setnumber
  // Mesh.SaveParametric 1) then "dimension entity" and as many parameters as the
  // dimension of a curve or surface (none on points and volumes): at least 12 bytes.
  bool parse_nodes_22(bool parametric) {
    uint64_t count = 0;
    if (!scanner_.read_count(&count, "node count", parametric ? 12 : 8) || !reserve_nodes(count))
      return false;
    for (uint64_t i = 0; i < count; ++i) {
      if (!read_node_tag() || !read_position()) return false;
      int64_t dimension = 0, entity = 0;
      if (parametric &&
          (!scanner_.read_int_in_range(&dimension, "entity dimension", 0, 3) ||
           !scanner_.read_int(&entity, "entity tag") ||
           !scanner_.skip_numbers(dimension == 1 || dimension == 2 ? uint64_t(dimension) : 0,
                                  "parametric coordinates")))
        return false;
    }
    return expect_end(parametric ? "$EndParametricNodes" : "$EndNodes");
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
      std::vector<uint32_t> lines(node_lines_.size());
      std::vector<Vec3> positions(count);
      for (size_t i = 0; i < count; ++i) {
        tags[i] = node_tags_[order[i]];
        if (!lines.empty()) lines[i] = node_lines_[order[i]];
        positions[i] = mesh.positions[order[i]];
      }
      node_tags_.swap(tags);
      node_lines_.swap(lines);
      mesh.positions.swap(positions);
    }
    for (size_t i = 1; i < count; ++i) {
      if (node_tags_[i] == node_tags_[i - 1]) {
        return scanner_.fail_at_line(
            binary_ ? 0 : node_lines_[i],
            "node tag " + std::to_string(node_tags_[i]) + " is defined twice");
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

  // The elementary tag of a 4.1 volume entity: a partition volume's parent's.
  int64_t elementary_of(int64_t entity) const {
    const auto it = volume_parent_.find(entity);
    return it != volume_parent_.end() ? it->second : entity;
  }

  // Material of a tet from its physical tag (0: none) and elementary tag.
  // Runs of elements with the same tags (a 2.2 file's are in runs; 4.1 asks once per
  // block) reuse the last answer, so the bookkeeping for the notes is done once a run.
  bool resolve_material(int64_t physical, int64_t elementary, int32_t* material) {
    if (has_last_tags_ && physical == last_physical_ && elementary == current_elementary_) {
      *material = last_material_;
      return true;
    }
    from_elementary_ = physical == 0;
    current_elementary_ = elementary;
    // An elementary entity in two physical groups: Gmsh 2.2 writes its elements once
    // per group (drop_repeated_tets()).
    const auto [first, inserted] = first_physical_of_.try_emplace(elementary, physical);
    if (!inserted && first->second != physical) entity_in_two_groups_ = true;
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
    std::set<int32_t>& noted = from_elementary_ ? elementary_materials_ : physical_materials_;
    if (noted.size() < 1000) noted.insert(*material);
    has_last_tags_ = true;
    last_physical_ = physical;
    last_material_ = *material;
    return true;
  }

  // Reads the node tags of a tet element (of any order) and stores its corners.
  bool read_tet(int64_t element_tag, int64_t type, int32_t material, size_t line) {
    int64_t corners[4];
    for (int64_t& corner : corners) {
      if (!scanner_.read_int(&corner, "node tag")) return false;
    }
    if (!store_tet(element_tag, corners, material, line)) return false;
    for (int k = 4; k < nodes_per_element(type); ++k) {
      int64_t tag = 0;
      if (!scanner_.read_int(&tag, "node tag") || !other_node(element_tag, tag)) return false;
    }
    return true;
  }

  // A higher-order tet's node past its corners: read by its corners only, but each node
  // it names must be in $Nodes, as a corner must.
  bool other_node(int64_t element_tag, int64_t tag) {
    if (find_node(tag) != kInvalidIndex) return true;
    return scanner_.fail("element " + std::to_string(element_tag) + " uses node " +
                         std::to_string(tag) + " (a higher-order node), which is not in $Nodes");
  }

  // Stores a tet from the node tags of its corners (`line` only for text files).
  bool store_tet(int64_t element_tag, const int64_t corners[4], int32_t material, size_t line) {
    Tet tet;
    for (int k = 0; k < 4; ++k) {
      tet[k] = find_node(corners[k]);
      if (tet[k] == kInvalidIndex) {
        return scanner_.fail("element " + std::to_string(element_tag) + " uses node " +
                             std::to_string(corners[k]) + ", which is not in $Nodes");
      }
    }
    if (out_->mesh.tets.size() + 1 >= kInvalidIndex) return scanner_.fail("too many tetrahedra");
    out_->mesh.tets.push_back(tet);
    out_->mesh.materials.push_back(material);
    if (!binary_) out_->tet_lines.push_back(line_number(line));
    element_tags_.push_back(element_tag);
    if (version_ == 22) tet_elementary_.push_back(current_elementary_);
    tet_from_elementary_.push_back(from_elementary_);
    ++(from_elementary_ ? elementary_tets_ : physical_tets_);
    return true;
  }

  // The first physical tag of a 4.1 surface entity (a partition's: its own, else its
  // parent's), 0 if none.
  int64_t surface_physical_of(int64_t entity) const {
    const auto it = surface_physical_.find(entity);
    return it != surface_physical_.end() ? it->second : 0;
  }
  // Its other physical tags (a surface in several groups), or null.
  // A volume entity's physical tags after the first (4.1): each such group is said to
  // hold the tets read in the first.
  void add_volume_groups(int64_t entity, int64_t first, const std::vector<int64_t>& others) {
    for (int64_t other : others) read_in_groups_[other].insert(first);
    if (!others.empty()) volume_other_physicals_[entity] = others;
  }

  // The material of `tets` tets of volume entity `entity` (4.1): its first physical
  // tag's, else its own. An entity of several groups is counted for a note.
  bool entity_material(int64_t entity, uint64_t tets, int32_t* material) {
    const auto first = volume_physical_.find(entity);
    if (const auto more = volume_other_physicals_.find(entity);
        more != volume_other_physicals_.end() && tets > 0) {
      shared_volume_tets_ += tets;
      for (int64_t group : more->second)
        if (groups_not_read_in_.size() < 10) groups_not_read_in_.insert(group);
    }
    return resolve_material(first != volume_physical_.end() ? first->second : 0,
                            elementary_of(entity), material);
  }

  const std::vector<int64_t>* other_physicals_of(int64_t entity) const {
    const auto it = surface_other_physicals_.find(entity);
    return it != surface_other_physicals_.end() ? &it->second : nullptr;
  }

  // A triangle of the physical surface `physical`, by its corners' node tags, kept by
  // their positions for SurfacePatches; one naming a node not in $Nodes is
  // left out (its group then matches nothing).
  void store_triangle(int64_t physical, const int64_t corners[3]) {
    std::array<Vec3, 3> triangle;
    for (int k = 0; k < 3; ++k) {
      const uint32_t v = find_node(corners[k]);
      if (v == kInvalidIndex) return;
      triangle[size_t(k)] = out_->mesh.positions[v];
    }
    surface_triangles_[physical].push_back(triangle);
  }

  // Reads a triangle element's node tags (of any order) and stores its corners.
  bool read_triangle(int64_t type, int64_t physical, const std::vector<int64_t>* others) {
    int64_t corners[3];
    for (int64_t& corner : corners) {
      if (!scanner_.read_int(&corner, "node tag")) return false;
    }
    store_triangle(physical, corners);
    if (others)
      for (int64_t other : *others) store_triangle(other, corners);
    return scanner_.skip_numbers(uint64_t(nodes_per_element(type) - 3), "node tags");
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
      count_elements(type, 1);
      if (is_tet_type(type)) {
        int32_t material = 0;
        if (!resolve_material(physical, elementary, &material) ||
            !read_tet(element_tag, type, material, line)) {
          return false;
        }
      } else if (physical > 0 && is_triangle_type(type)) {
        if (!read_triangle(type, physical, nullptr)) return false;
      } else {
        if (physical > 0 && is_quadrangle_type(type)) ++grouped_quads_[physical];
        if (!skip_element_nodes(type)) return false;
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
      count_elements(type, block_size);
      const bool is_tet = is_tet_type(type);
      int32_t material = 0;
      if (is_tet) {
        if (!entity_material(entity, block_size, &material)) {
          return false;
        }
      }
      const int64_t surface_group =
          dimension == 2 && is_triangle_type(type) ? surface_physical_of(entity) : 0;
      const std::vector<int64_t>* other_groups =
          surface_group > 0 ? other_physicals_of(entity) : nullptr;
      count_grouped_quads(dimension, entity, type, block_size);
      for (uint64_t i = 0; i < block_size; ++i) {
        int64_t element_tag = 0;
        if (!scanner_.read_int(&element_tag, "element tag")) return false;
        const bool ok = is_tet              ? read_tet(element_tag, type, material, scanner_.line())
                        : surface_group > 0 ? read_triangle(type, surface_group, other_groups)
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

  void count_elements(int64_t type, uint64_t count) { element_counts_[type] += count; }
  // A 4.1 block of quadrangles of a physical surface: a group that is not kept.
  void count_grouped_quads(int64_t dimension, int64_t entity, int64_t type, uint64_t count) {
    if (dimension != 2 || !is_quadrangle_type(type)) return;
    if (const int64_t group = surface_physical_of(entity); group > 0)
      grouped_quads_[group] += count;
  }

  // What the user should know of what was not read: elements other than 4- and
  // 10-node tets, the mid-edge nodes of 10-node ones, surface groups, and how groups
  // became materials.
  void add_notes() {
    auto quoted_list = [](const std::vector<std::string>& items) {
      std::string text;
      for (size_t i = 0; i < std::min<size_t>(items.size(), 10); ++i)
        text += (i == 0 ? "" : ", ") + items[i];
      if (items.size() > 10) text += " and " + std::to_string(items.size() - 10) + " more";
      return text;
    };
    std::map<std::string, size_t> skipped_volumes;
    uint64_t surface_elements = 0, lines = 0, points = 0, higher_order = 0;
    std::vector<std::string> unknown;  // "type 140: 12 elements"
    for (const auto& [type, count] : element_counts_) {
      if (const char* name = skipped_volume_elements(type)) skipped_volumes[name] += count;
      if (is_surface_element(type)) surface_elements += count;
      if (type == 1 || type == 8 || (type >= 26 && type <= 28) || (type >= 62 && type <= 66))
        lines += count;
      if (type == 15) points += count;
      if (is_tet_type(type) && type != kTet4) higher_order += count;
      if (nodes_per_element(type) == 0 && !skipped_volume_elements(type))
        unknown.push_back("type " + std::to_string(type) + ": " + std::to_string(count) +
                          (count == 1 ? " element" : " elements"));
    }
    if (!unknown.empty()) {
      out_->notes.push_back("elements of types TetLOD does not know (" + quoted_list(unknown) +
                            ") are not kept: it reads tetrahedra of any order, and the "
                            "triangles of surface groups");
    }
    if (lines + points > 0) {
      const std::string what =
          lines == 0 ? std::to_string(points) + (points == 1 ? " point element" : " point elements")
          : points == 0
              ? std::to_string(lines) + (lines == 1 ? " line element" : " line elements")
              : std::to_string(lines) + " line and " + std::to_string(points) + " point elements";
      out_->notes.push_back(what +
                            " (Gmsh writes those of physical curves and points, or "
                            "all with Mesh.SaveAll) are not kept: TetLOD keeps the tetrahedra, "
                            "their volume groups and the surface groups");
    }

    if (!skipped_volumes.empty()) {
      out_->notes.push_back("skipped " + count_list(skipped_volumes) +
                            ": TetLOD reads tetrahedra only, so a region "
                            "meshed with other elements is not in the mesh");
    }
    if (higher_order > 0) {
      out_->notes.push_back(std::to_string(higher_order) +
                            " higher-order tetrahedra (10 nodes or more) were read as 4-node "
                            "ones (by their corners; their other nodes are dropped)");
    }
    std::vector<std::string> volume_names;
    // The materials the tets have, for the volume groups left without tets (one pass,
    // not one per group).
    std::unordered_set<int32_t> present;
    if (!physical_names_.empty())
      present.insert(out_->mesh.materials.begin(), out_->mesh.materials.end());
    for (const auto& [key, name] : physical_names_) {
      if (key.first == 3) {
        const bool has_tets = key.second >= 0 &&
                              key.second <= std::numeric_limits<int32_t>::max() &&
                              present.count(int32_t(key.second)) > 0;
        // A group without tets of its own may share a volume with the group its tets
        // were read in (a second physical tag of a 4.1 volume entity; a 2.2 element
        // listed again).
        std::vector<std::string> holders;
        if (const auto in = read_in_groups_.find(key.second); in != read_in_groups_.end()) {
          for (int64_t group : in->second) {
            const auto named = named_materials_.find(group);
            const int64_t material = named != named_materials_.end() ? named->second : group;
            if (material >= 0 && material <= std::numeric_limits<int32_t>::max() &&
                present.count(int32_t(material)) > 0 && holders.size() < 10)
              holders.push_back(std::to_string(group));
          }
        }
        const std::string why =
            holders.empty()
                ? " (no tetrahedra: not in the mesh)"
                : " (no tetrahedra of its own: they are read in group" +
                      std::string(holders.size() > 1 ? "s " : " ") + quoted_list(holders) +
                      (holders.size() > 1 ? ", which hold the same volumes; a tet has one "
                                            "material, so this group is not kept: name "
                                            "those)"
                                          : ", which holds the same volume; a tet has one "
                                            "material, so this group is not kept: name "
                                            "that one)");
        volume_names.push_back("'" + name + "' = " + std::to_string(key.second) +
                               (has_tets ? "" : why));
        // Sorted by tag, so by material; a group's name is its material's.
        if (has_tets) out_->material_names.push_back({int32_t(key.second), name});
      }
    }
    // Quadrangles of surface groups: said here, by group (the CLI's note on surface
    // elements counts the others, and called these "in no group").
    uint64_t quads = 0;
    std::vector<std::string> quad_groups;
    for (const auto& [group, count] : grouped_quads_) {
      quads += count;
      const auto named = physical_names_.find({2, group});
      quad_groups.push_back(named != physical_names_.end() ? "'" + named->second + "'"
                                                           : std::to_string(group));
    }
    if (quads > 0) {
      out_->notes.push_back(
          std::to_string(quads) + (quads == 1 ? " quadrangle" : " quadrangles") +
          " of the surface group" + (quad_groups.size() > 1 ? "s " : " ") +
          quoted_list(quad_groups) + (quads == 1 ? " is" : " are") +
          " not kept: TetLOD keeps surface groups of triangles (mesh those surfaces "
          "without recombining them into quadrangles)");
    }
    out_->surface_elements_not_kept = surface_elements - std::min(surface_elements, quads);
    for (const std::string& renamed : renamed_)
      out_->notes.push_back(renamed + " in $PhysicalNames: the last name is kept");
    if (!volume_names.empty()) {
      out_->notes.push_back(
          "volume groups are materials by their number (.msh, .inp, .vtk and .vtu "
          "outputs keep their names): " +
          quoted_list(volume_names));
    }
    if (elementary_tets_ > 0 && physical_tets_ > 0) {
      std::vector<std::string> ids, shared;
      for (int32_t m : elementary_materials_) {
        const auto as = renumbered_entities_.find(m);
        ids.push_back(std::to_string(m) + (as != renumbered_entities_.end()
                                               ? " as " + std::to_string(as->second)
                                               : ""));
        if (as == renumbered_entities_.end() && physical_materials_.count(m))
          shared.push_back(std::to_string(m));
      }
      out_->notes.push_back(
          std::to_string(elementary_tets_) +
          " tetrahedra are in no physical group: their material is their volume's entity tag (" +
          quoted_list(ids) + ")" +
          (shared.empty() ? std::string()
                          : "; " + quoted_list(shared) +
                                " is also a physical group's number, so both are one material"));
    }
    if (!renumbered_entities_.empty()) {
      std::vector<std::string> list;
      for (const auto& [from, to] : renumbered_entities_)
        list.push_back(std::to_string(from) + " as " + std::to_string(to));
      out_->notes.push_back(
          "tetrahedra in no physical group whose volume entity's tag is also a volume "
          "group's number are read as materials of their own: entity " +
          quoted_list(list));
    }
  }

  // Orders the tets by element tag and rejects repeated tags.
  // Gmsh 2.2 writes an element once for each physical group that holds it: the same
  // tet (same nodes, same elementary entity) twice. Each is kept once, in the first
  // group the file lists it in, and a note says so. Two different entities' tets on
  // the same nodes stay, for the validation to report.
  void drop_repeated_tets() {
    if (version_ != 22 || !entity_in_two_groups_) return;
    TetMesh& mesh = out_->mesh;
    const size_t count = mesh.tets.size();
    std::vector<Tet> keys(mesh.tets);
    for (Tet& k : keys) std::sort(k.begin(), k.end());
    std::vector<uint32_t> order(count);
    std::iota(order.begin(), order.end(), 0u);
    std::sort(order.begin(), order.end(), [&](uint32_t a, uint32_t b) {
      return keys[a] != keys[b] ? keys[a] < keys[b] : a < b;
    });
    std::vector<uint8_t> drop(count, 0);
    std::set<int32_t> dropped_materials;
    size_t dropped = 0;
    for (size_t i = 0, first = 0; i < count; ++i) {
      if (i == 0 || keys[order[i]] != keys[order[first]]) {
        first = i;
        continue;
      }
      const uint32_t t = order[i];
      for (size_t j = first; j < i; ++j) {
        const uint32_t kept = order[j];
        if (!drop[kept] && tet_elementary_[kept] == tet_elementary_[t]) {
          drop[t] = 1;
          read_in_groups_[mesh.materials[t]].insert(mesh.materials[kept]);
          ++dropped;
          if (dropped_materials.size() < 10) dropped_materials.insert(mesh.materials[t]);
          break;
        }
      }
    }
    if (dropped == 0) return;
    size_t kept = 0;
    for (size_t t = 0; t < count; ++t) {
      if (drop[t]) continue;
      mesh.tets[kept] = mesh.tets[t];
      mesh.materials[kept] = mesh.materials[t];
      element_tags_[kept] = element_tags_[t];
      tet_from_elementary_[kept] = tet_from_elementary_[t];
      if (!out_->tet_lines.empty()) out_->tet_lines[kept] = out_->tet_lines[t];
      ++kept;
    }
    mesh.tets.resize(kept);
    tet_from_elementary_.resize(kept);
    mesh.materials.resize(kept);
    element_tags_.resize(kept);
    if (!out_->tet_lines.empty()) out_->tet_lines.resize(kept);
    std::string groups;
    for (int32_t m : dropped_materials) groups += (groups.empty() ? "" : ", ") + std::to_string(m);
    out_->notes.push_back(std::to_string(dropped) +
                          " tetrahedra are listed again in another physical group (Gmsh 2.2 "
                          "writes an element once per group that holds it): each is read "
                          "once, in the first group listed, not in group(s) " +
                          groups);
  }

  // Tets in no physical group take their volume entity's tag as material. Where that
  // number is also a volume group's (one that holds tets, or one $PhysicalNames names),
  // those tets get a number above every group's and material's, so that two bodies are
  // not read as one material, nor named after a group they are not in (Gmsh numbers
  // entities and groups apart: Mesh.SaveAll writes 2.2 files with every element in no
  // group, and their volume groups' names).
  void separate_entity_materials() {
    if (elementary_tets_ == 0) return;
    std::vector<int32_t>& materials = out_->mesh.materials;
    std::set<int64_t> groups;
    for (size_t t = 0; t < materials.size(); ++t)
      if (!tet_from_elementary_[t]) groups.insert(materials[t]);
    for (const auto& entry : physical_names_)
      if (entry.first.first == 3) groups.insert(entry.first.second);
    for (const auto& [tag, material] : named_materials_) groups.insert(tag);
    std::map<int32_t, int32_t> renumbered;
    int64_t next = groups.empty() ? 0 : *groups.rbegin();
    for (int32_t m : materials) next = std::max<int64_t>(next, m);
    for (size_t t = 0; t < materials.size(); ++t)
      if (tet_from_elementary_[t] && groups.count(materials[t])) renumbered[materials[t]] = 0;
    for (auto& [from, to] : renumbered) {
      if (++next > std::numeric_limits<int32_t>::max()) return;  // (left as one material)
      to = int32_t(next);
    }
    for (size_t t = 0; t < materials.size(); ++t) {
      if (!tet_from_elementary_[t]) continue;
      if (const auto it = renumbered.find(materials[t]); it != renumbered.end())
        materials[t] = it->second;
    }
    renumbered_entities_ = std::move(renumbered);
  }

  bool finish_elements() {
    drop_repeated_tets();
    if (shared_volume_tets_ > 0) {
      std::string groups;
      for (int64_t g : groups_not_read_in_)
        groups += (groups.empty() ? "" : ", ") + std::to_string(g);
      const bool one = shared_volume_tets_ == 1;
      out_->notes.push_back(
          std::to_string(shared_volume_tets_) + (one ? " tetrahedron is" : " tetrahedra are") +
          " in a volume of more than one physical group: " + (one ? "it is" : "each is") +
          " read once, in the volume's first group, not in group(s) " + groups);
    }
    separate_entity_materials();
    add_notes();
    for (auto& [tag, triangles] : surface_triangles_) {
      if (tag > std::numeric_limits<int32_t>::max()) continue;
      InputSurfaceGroup group;
      group.tag = int32_t(tag);
      const auto name = physical_names_.find({2, tag});
      if (name != physical_names_.end()) group.name = name->second;
      group.triangles = std::move(triangles);
      out_->surface_groups.push_back(std::move(group));
    }
    surface_triangles_.clear();
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
            binary_ ? 0 : out_->tet_lines[order[i]],
            "element tag " + std::to_string(element_tags_[order[i]]) + " is used twice");
      }
    }
    if (std::is_sorted(element_tags_.begin(), element_tags_.end())) return true;
    std::vector<Tet> tets(count);
    std::vector<int32_t> materials(count);
    std::vector<uint32_t> lines(out_->tet_lines.size());
    for (size_t i = 0; i < count; ++i) {
      tets[i] = mesh.tets[order[i]];
      materials[i] = mesh.materials[order[i]];
      if (!lines.empty()) lines[i] = out_->tet_lines[order[i]];
    }
    mesh.tets.swap(tets);
    mesh.materials.swap(materials);
    out_->tet_lines.swap(lines);
    return true;
  }

  std::string_view text_;
  TextScanner scanner_;
  ParsedMesh* out_;
  int version_ = 0;
  bool binary_ = false;  // file type 1
  bool swap_ = false;    // binary numbers in the other byte order
  bool seen_nodes_ = false;
  bool seen_elements_ = false;
  std::unordered_map<int64_t, int64_t> named_materials_;  // physical tag -> 0 ("material_0")
  std::unordered_map<int64_t, int64_t> volume_physical_;  // volume entity -> first physical tag
  std::unordered_map<int64_t, std::vector<int64_t>> volume_other_physicals_;  // the others
  uint64_t shared_volume_tets_ = 0;       // tets of entities of several groups (4.1)
  std::set<int64_t> groups_not_read_in_;  // those groups' tags after the first (10 at most)
  std::unordered_map<int64_t, int64_t> volume_parent_;     // partition volume -> model volume
  std::unordered_map<int64_t, int64_t> surface_physical_;  // surface entity -> first physical
  std::unordered_map<int64_t, std::vector<int64_t>> surface_other_physicals_;  // -> the others
  // A volume group's tag -> the groups its tets were read in instead (for the notes).
  std::map<int64_t, std::set<int64_t>> read_in_groups_;
  std::map<int64_t, std::vector<std::array<Vec3, 3>>> surface_triangles_;  // by physical tag
  // For the notes: physical names of surfaces and volumes other than "material_<n>"
  // ((dimension, tag) -> name), elements by type, tets by where their material came from.
  std::map<std::pair<int64_t, int64_t>, std::string> physical_names_;
  std::vector<std::string> renamed_;  // groups named twice, for a note (at most 10)
  std::map<int64_t, uint64_t> element_counts_;
  std::map<int64_t, uint64_t> grouped_quads_;  // physical surface -> its quadrangles
  bool from_elementary_ = false;               // of the last resolve_material()
  bool periodic_ = false;                      // the file has a $Periodic section (not read)
  uint64_t physical_tets_ = 0, elementary_tets_ = 0;
  std::set<int32_t> elementary_materials_, physical_materials_;  // the first 1000
  std::vector<uint64_t> node_tags_;                              // sorted by finish_nodes()
  std::vector<uint32_t> node_lines_;
  uint64_t first_tag_ = 0;
  std::vector<uint32_t> dense_index_;               // node tag - first_tag_ -> vertex, when compact
  std::vector<int64_t> element_tags_;               // per tet
  std::vector<int64_t> tet_elementary_;             // per tet: its elementary entity's tag
  std::vector<uint8_t> tet_from_elementary_;        // per tet: its material is its entity's tag
  std::map<int32_t, int32_t> renumbered_entities_;  // separate_entity_materials(): tag -> material
  // The tags of the last resolve_material() and its answer.
  bool has_last_tags_ = false;
  int64_t last_physical_ = 0, current_elementary_ = 0;
  int32_t last_material_ = 0;
  std::unordered_map<int64_t, int64_t> first_physical_of_;  // elementary -> physical
  bool entity_in_two_groups_ = false;
};

// A user's name inside Gmsh's quotes: no quote or line break.
std::string quotable(std::string name) {
  for (char& c : name) c = c == '"' || uint8_t(c) < 32 ? '_' : c;
  return name;
}

void append_physical_names(const std::vector<int32_t>& materials,
                           const std::vector<int32_t>& physical_tags, const SurfaceGroups* surfaces,
                           const std::vector<MaterialName>* names, std::string* out) {
  out->append("$PhysicalNames\n");
  append_line(out, materials.size() + (surfaces ? surfaces->groups.size() : 0));
  if (surfaces) {
    for (const SurfaceGroup& group : surfaces->groups) {
      out->append("2 ");
      append_number(out, group.tag);
      out->append(" \"" + quotable(group.name) + "\"\n");
    }
  }
  for (size_t i = 0; i < materials.size(); ++i) {
    out->append("3 ");
    append_number(out, physical_tags[i]);
    out->append(" \"");
    // A name of its own, unless it is empty, or "material_0", which would read as
    // material 0, or the tag is not the id (material 0).
    const std::string* name = materials[i] > 0 ? find_material_name(names, materials[i]) : nullptr;
    if (name && (name->empty() || material_from_name(*name) == 0)) name = nullptr;
    if (name) {
      out->append(quotable(*name));
    } else {
      out->append(kMaterialPrefix);
      append_number(out, materials[i]);
    }
    out->append("\"\n");
  }
  out->append("$EndPhysicalNames\n");
}

// The values of a .msh section: as text, a line per record (append_line()); in binary
// (file type 1), each value as the C type the format gives it, without separators, in
// this machine's byte order (the 1 after the header tells readers which).
struct I32 {
  int64_t v;
};
struct U64 {
  uint64_t v;
};
struct F64 {
  double v;
};
class MshRecords {
 public:
  MshRecords(std::string* out, bool binary) : out_(out), binary_(binary) {}
  template <typename... Values>
  void record(Values... values) {
    if (binary_) {
      (put(values), ...);
    } else {
      append_line(out_, value_of(values)...);
    }
  }
  // "$EndNodes" and the like: after binary data, on a line of their own.
  void end_section(const char* name) {
    if (binary_) out_->push_back('\n');
    out_->append(name);
    out_->push_back('\n');
  }

 private:
  static int64_t value_of(I32 x) { return x.v; }
  static uint64_t value_of(U64 x) { return x.v; }
  static double value_of(F64 x) { return x.v; }
  void put(I32 x) { put_bytes(int32_t(x.v)); }
  void put(U64 x) { put_bytes(x.v); }
  void put(F64 x) { put_bytes(x.v); }
  template <typename T>
  void put_bytes(T value) {
    char bytes[sizeof(T)];
    std::memcpy(bytes, &value, sizeof(T));
    out_->append(bytes, sizeof(T));
  }
  std::string* out_;
  bool binary_;
};

}  // namespace

Status parse_gmsh(std::string_view text, const std::string& name, ParsedMesh* out, int* version) {
  GmshParser parser(text, name, out);
  return parser.parse(version);
}

void write_gmsh(const TetMesh& mesh, int version, bool binary, const SurfaceGroups* surfaces,
                const std::vector<MaterialName>* names, std::string* out) {
  // Distinct materials and their physical tags: m for m > 0; 0 takes the smallest
  // positive tag no material uses.
  std::vector<int32_t> materials = mesh.materials;
  std::sort(materials.begin(), materials.end());
  materials.erase(std::unique(materials.begin(), materials.end()), materials.end());
  const int32_t zero_tag = gmsh_material_zero_tag(materials);
  std::vector<int32_t> physical_tags(materials.size());
  for (size_t i = 0; i < materials.size(); ++i) {
    physical_tags[i] = materials[i] > 0 ? materials[i] : zero_tag;
  }
  auto group_of = [&](int32_t material) {
    return size_t(std::lower_bound(materials.begin(), materials.end(), material) -
                  materials.begin());
  };

  out->reserve(out->size() + mesh.vertex_count() * 64 + mesh.tet_count() * 48);
  MshRecords r(out, binary);
  out->append(version == 22 ? "$MeshFormat\n2.2 " : "$MeshFormat\n4.1 ");
  out->append(binary ? "1 8\n" : "0 8\n");
  if (binary) r.record(I32{1});
  r.end_section("$EndMeshFormat");
  append_physical_names(materials, physical_tags, surfaces, names, out);
  const std::vector<SurfaceGroup> no_groups;
  const std::vector<SurfaceGroup>& groups = surfaces ? surfaces->groups : no_groups;
  size_t triangle_count = 0;
  for (const SurfaceGroup& group : groups) triangle_count += group.triangles.size();

  if (version == 22) {
    // The counts stay text lines in binary files too; there an element is its tag,
    // tags and nodes, after a header (type, count, number of tags) per run of one type.
    out->append("$Nodes\n");
    append_line(out, mesh.vertex_count());
    for (size_t v = 0; v < mesh.vertex_count(); ++v) {
      const Vec3& p = mesh.positions[v];
      r.record(I32{int64_t(v) + 1}, F64{p.x}, F64{p.y}, F64{p.z});
    }
    r.end_section("$EndNodes");
    out->append("$Elements\n");
    append_line(out, mesh.tet_count() + triangle_count);
    if (binary) r.record(I32{kTet4}, I32{int64_t(mesh.tet_count())}, I32{2});
    for (size_t t = 0; t < mesh.tet_count(); ++t) {
      const Tet& tet = mesh.tets[t];
      const int32_t tag = physical_tags[group_of(mesh.materials[t])];
      if (binary) {
        r.record(I32{int64_t(t) + 1}, I32{tag}, I32{tag}, I32{tet[0] + 1}, I32{tet[1] + 1},
                 I32{tet[2] + 1}, I32{tet[3] + 1});
      } else {
        append_line(out, t + 1, kTet4, 2, tag, tag, tet[0] + 1, tet[1] + 1, tet[2] + 1, tet[3] + 1);
      }
    }
    // Triangles after the tets, so that tet t keeps element tag t + 1.
    if (binary && triangle_count > 0)
      r.record(I32{kTriangle3}, I32{int64_t(triangle_count)}, I32{2});
    size_t element = mesh.tet_count();
    for (const SurfaceGroup& group : groups) {
      for (uint32_t i : group.triangles) {
        const auto& v = surfaces->surface[i].v;
        ++element;
        if (binary) {
          r.record(I32{int64_t(element)}, I32{group.tag}, I32{group.tag}, I32{v[0] + 1},
                   I32{v[1] + 1}, I32{v[2] + 1});
        } else {
          append_line(out, element, kTriangle3, 2, group.tag, group.tag, v[0] + 1, v[1] + 1,
                      v[2] + 1);
        }
      }
    }
    r.end_section("$EndElements");
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
  r.record(U64{0}, U64{0}, U64{groups.size()}, U64{group_count});
  // One surface entity per surface group (entity tag = physical tag).
  for (const SurfaceGroup& group : groups) {
    Vec3 lo = mesh.positions[surfaces->surface[group.triangles[0]].v[0]];  // never empty
    Vec3 hi = lo;
    for (uint32_t i : group.triangles) {
      for (uint32_t v : surfaces->surface[i].v) {
        for (int k = 0; k < 3; ++k) {
          lo[k] = std::min(lo[k], mesh.positions[v][k]);
          hi[k] = std::max(hi[k], mesh.positions[v][k]);
        }
      }
    }
    r.record(I32{group.tag}, F64{lo.x}, F64{lo.y}, F64{lo.z}, F64{hi.x}, F64{hi.y}, F64{hi.z},
             U64{1}, I32{group.tag}, U64{0});
  }
  for (size_t g = 0; g < group_count; ++g) {
    const Vec3& lo = box_min[g];
    const Vec3& hi = box_max[g];
    r.record(I32{physical_tags[g]}, F64{lo.x}, F64{lo.y}, F64{lo.z}, F64{hi.x}, F64{hi.y},
             F64{hi.z}, U64{1}, I32{physical_tags[g]}, U64{0});
  }
  r.end_section("$EndEntities");
  out->append("$Nodes\n");
  r.record(U64{node_block_count}, U64{mesh.vertex_count()}, U64{mesh.vertex_count() > 0 ? 1u : 0u},
           U64{mesh.vertex_count()});
  for (size_t g = 0; g < group_count; ++g) {
    const std::vector<uint32_t>& vertices = group_vertices[g];
    if (vertices.empty()) continue;
    r.record(I32{3}, I32{physical_tags[g]}, I32{0}, U64{vertices.size()});
    for (uint32_t v : vertices) r.record(U64{uint64_t(v) + 1});
    for (uint32_t v : vertices) {
      const Vec3& p = mesh.positions[v];
      r.record(F64{p.x}, F64{p.y}, F64{p.z});
    }
  }
  r.end_section("$EndNodes");
  out->append("$Elements\n");
  const size_t element_count = mesh.tet_count() + triangle_count;
  r.record(U64{group_count + groups.size()}, U64{element_count}, U64{element_count > 0 ? 1u : 0u},
           U64{element_count});
  // Triangles numbered after the tets, so that tet t keeps element tag t + 1.
  size_t element = mesh.tet_count();
  for (const SurfaceGroup& group : groups) {
    r.record(I32{2}, I32{group.tag}, I32{kTriangle3}, U64{group.triangles.size()});
    for (uint32_t i : group.triangles) {
      const auto& v = surfaces->surface[i].v;
      r.record(U64{++element}, U64{v[0] + 1u}, U64{v[1] + 1u}, U64{v[2] + 1u});
    }
  }
  for (size_t g = 0; g < group_count; ++g) {
    r.record(I32{3}, I32{physical_tags[g]}, I32{kTet4},
             U64{group_tet_start[g + 1] - group_tet_start[g]});
    for (size_t i = group_tet_start[g]; i < group_tet_start[g + 1]; ++i) {
      const uint32_t t = tet_order[i];
      const Tet& tet = mesh.tets[t];
      r.record(U64{t + 1u}, U64{tet[0] + 1u}, U64{tet[1] + 1u}, U64{tet[2] + 1u}, U64{tet[3] + 1u});
    }
  }
  r.end_section("$EndElements");
}

}  // namespace tetlod::io
