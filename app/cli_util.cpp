#include "app/cli_util.h"

#include <charconv>
#include <cmath>

namespace tetlod::app {

bool wants_help(const Args& args) {
  for (const std::string& a : args)
    if (a == "-h" || a == "--help") return true;
  return false;
}

std::optional<double> parse_double(const std::string& text) {
  double value = 0;
  const char* end = text.data() + text.size();
  const auto [ptr, ec] = std::from_chars(text.data(), end, value);
  if (ec != std::errc() || ptr != end || !std::isfinite(value)) return std::nullopt;
  return value;
}

std::optional<long long> parse_integer(const std::string& text) {
  long long value = 0;
  const char* end = text.data() + text.size();
  const auto [ptr, ec] = std::from_chars(text.data(), end, value);
  if (ec != std::errc() || ptr != end) return std::nullopt;
  return value;
}

bool load_mesh(const std::string& path, TetMesh* mesh, ReadInfo* info) {
  const Status status = read_mesh(path, mesh, info);
  if (!status) {
    std::fprintf(stderr, "tetlod: %s\n", status.message().c_str());
    return false;
  }
  if (info->validation.reoriented_tets > 0) {
    std::fprintf(stderr, "tetlod: %s: note: %zu negatively oriented tetrahedra were reoriented\n",
                 path.c_str(), info->validation.reoriented_tets);
  }
  if (info->validation.removed_unused_vertices > 0) {
    std::fprintf(stderr, "tetlod: %s: note: %zu vertices used by no tetrahedron were dropped\n",
                 path.c_str(), info->validation.removed_unused_vertices);
  }
  return true;
}

void print_property_table(const MeshStats& stats) {
  std::printf("%-14s %9s %9s %10s %9s %9s %8s %11s %12s\n", "", "#nodes", "#edges", "#elements",
              "ave.str", "min.str", "max.val", "max.size", "volume");
  auto row = [](const std::string& label, const PropertyRow& r) {
    std::printf("%-14s %9zu %9zu %10zu %9.4f %9.4f %8u %11.5g %12.6g\n", label.c_str(), r.nodes,
                r.edges, r.elements, r.average_stretch, r.min_stretch, r.max_valence, r.max_size,
                r.volume);
  };
  row("whole mesh", stats.whole);
  for (const MaterialRow& m : stats.per_material)
    row("material " + std::to_string(m.material), m.row);
}

std::string json_escape(const std::string& text) {
  std::string out;
  for (const char c : text) {
    const auto u = static_cast<unsigned char>(c);
    if (c == '"' || c == '\\') {
      out += '\\';
      out += c;
    } else if (u < 0x20) {
      char buffer[8];
      std::snprintf(buffer, sizeof buffer, "\\u%04x", u);
      out += buffer;
    } else {
      out += c;
    }
  }
  return out;
}

}  // namespace tetlod::app
