#include "core/sizing.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <vector>

#include "core/metrics.h"

namespace tetlod {

double SizingField::size_at(const Vec3& p, int32_t material) const {
  double size = material_size(material);
  apply_regions(1, &p.x, &p.y, &p.z, &size);
  return size;
}

double SizingField::material_size(int32_t material) const {
  double size = uniform;
  if (!material_sizes.empty()) {
    const auto it = std::lower_bound(
        material_sizes.begin(), material_sizes.end(), material,
        [](const std::pair<int32_t, double>& e, int32_t m) { return e.first < m; });
    if (it != material_sizes.end() && it->first == material) size = std::min(size, it->second);
  }
  return size;
}

// Rule by rule over the points, so that the loops run down arrays. The operations are
// those of the Vec3 forms (d = p - c; d -= axis dot(d, axis); size0 + growth |d|), in
// the same order.
void SizingField::apply_regions(size_t n, const double* x, const double* y, const double* z,
                                double* size) const {
  for (const Radial& r : radial) {
    const Vec3 c = r.center, a = r.axis;
    const bool from_axis = a != Vec3{};
    for (size_t i = 0; i < n; ++i) {
      double dx = x[i] - c.x, dy = y[i] - c.y, dz = z[i] - c.z;
      if (from_axis) {
        const double along = dx * a.x + dy * a.y + dz * a.z;
        dx = dx - a.x * along;
        dy = dy - a.y * along;
        dz = dz - a.z * along;
      }
      size[i] = std::min(size[i], r.size0 + r.growth * std::sqrt(dx * dx + dy * dy + dz * dz));
    }
  }
  for (const Box& b : boxes) {
    for (size_t i = 0; i < n; ++i) {
      if (x[i] >= b.low.x && x[i] <= b.high.x && y[i] >= b.low.y && y[i] <= b.high.y &&
          z[i] >= b.low.z && z[i] <= b.high.z) {
        size[i] = std::min(size[i], b.size);
      }
    }
  }
  if (map) map->apply(n, x, y, z, size);
}

double suggested_size(const TetMesh& mesh, bool* raised) {
  if (raised) *raised = false;
  if (mesh.tets.empty()) return 0;
  // The median of the squared longest edges; the square root of that one only (the
  // same value as tet_shape's size, which is the root of the same maximum).
  std::vector<double> longest2;
  longest2.reserve(mesh.tets.size());
  for (const Tet& t : mesh.tets) {
    const Vec3 &a = mesh.positions[t[0]], &b = mesh.positions[t[1]], &c = mesh.positions[t[2]],
               &d = mesh.positions[t[3]];
    longest2.push_back(tet_longest_edge2(a, b, c, d));
  }
  const auto median = longest2.begin() + static_cast<std::ptrdiff_t>(longest2.size() / 2);
  std::nth_element(longest2.begin(), median, longest2.end());
  double size = 3 * std::sqrt(*median);
  if (!(size > 0) || !std::isfinite(size)) return size;
  // Subdivision's growth at `s`, estimated: a tet whose longest edge is L > s/2 becomes
  // about (2L/s)^3 tets (an overestimate: the thresholds refuse many splits).
  std::vector<double> longest = std::move(longest2);
  for (double& l : longest) l = std::sqrt(l);
  const auto growth = [&longest](double s) {
    double tets = 0;
    for (const double l : longest) {
      const double pieces = 2 * l / s;
      tets += std::max(1.0, pieces * pieces * pieces);
    }
    return tets / double(longest.size());
  };
  // Two significant digits: 23.43 -> 23, 2.34 -> 2.3 (up, `up`: 2.34 -> 2.4).
  const auto two_digits = [](double s, bool up) {
    const double unit = std::pow(10.0, std::floor(std::log10(s)) - 1);
    return (up ? std::ceil(s / unit - 1e-9) : std::round(s / unit)) * unit;
  };
  // On a graded mesh, at least the size that all but kSuggestedAbove of its tets meet:
  // subdivision leaves tets above the size where it cannot split their long edges within
  // the valence, and they make a second run, past the valence (a 1.37 M-tet Gmsh
  // transformer, 3.2 % of its tets above 3 x its median: 49,583 left above that size
  // after 50 s; at its 99th percentile, 17 after 41 s).
  const auto quantile = longest.begin() + static_cast<std::ptrdiff_t>(double(longest.size() - 1) *
                                                                      (1 - kSuggestedAbove));
  std::nth_element(longest.begin(), quantile, longest.end());
  const double most = *quantile;
  if (growth(size) <= kSuggestedGrowth) {
    if (two_digits(size, false) >= most) return two_digits(size, false);
    if (raised) *raised = true;
    return two_digits(most, true);
  }
  if (raised) *raised = true;
  // A graded mesh (fine parts, coarse air): the median is the fine parts', at which the
  // air's tets would be subdivided many times over. The smallest size at which the
  // estimate is kSuggestedGrowth instead (at twice the longest edge it is 1).
  double hi = 2 * *std::max_element(longest.begin(), longest.end());
  for (int i = 0; i < 40 && hi - size > 1e-4 * hi; ++i) {
    const double mid = 0.5 * (size + hi);
    (growth(mid) <= kSuggestedGrowth ? hi : size) = mid;
  }
  return two_digits(std::max(hi, most), true);
}

double SizingField::smallest_size() const {
  double size = uniform;
  for (const auto& m : material_sizes) size = std::min(size, m.second);
  for (const Radial& r : radial) size = std::min(size, r.size0);
  for (const Box& b : boxes) size = std::min(size, b.size);
  if (map) size = std::min(size, map->smallest());
  return size;
}

bool SizingField::has_local_rules() const {
  return !material_sizes.empty() || !radial.empty() || !boxes.empty() || map;
}

bool SizingField::unlimited() const {
  return std::isinf(uniform) && !has_local_rules();
}

namespace {

std::vector<std::string> split(const std::string& text, char separator) {
  std::vector<std::string> parts;
  size_t start = 0;
  while (true) {
    const size_t end = text.find(separator, start);
    parts.push_back(text.substr(start, end == std::string::npos ? std::string::npos : end - start));
    if (end == std::string::npos) break;
    start = end + 1;
  }
  return parts;
}

bool to_double(const std::string& text, double* value) {
  const char* end = text.data() + text.size();
  const auto [ptr, ec] = std::from_chars(text.data(), end, *value);
  return ec == std::errc() && ptr == end && std::isfinite(*value);
}

Status positive_size(const std::string& where, const std::string& text, double* value) {
  if (!to_double(text, value) || !(*value > 0)) {
    return Status::error(where + ": size '" + text + "' must be a finite number > 0");
  }
  return Status();
}

}  // namespace

Status parse_material_sizes(const std::string& spec, SizingField* field) {
  if (spec.empty()) return Status::error("--material-size: empty specification");
  for (const std::string& item : split(spec, ',')) {
    const size_t eq = item.find('=');
    if (item.empty())
      return Status::error("--material-size '" + spec +
                           "': an empty item (a comma at either end, or two in a row)");
    if (eq == std::string::npos) {
      return Status::error("--material-size: '" + item + "' is not of the form MATERIAL=SIZE");
    }
    const std::string id_text = item.substr(0, eq);
    int32_t id = 0;
    const char* end = id_text.data() + id_text.size();
    const auto [ptr, ec] = std::from_chars(id_text.data(), end, id);
    if (ec != std::errc() || ptr != end || id < 0) {
      return Status::error("--material-size: '" + id_text + "' is not a material id (>= 0)");
    }
    double size = 0;
    Status s = positive_size("--material-size " + item, item.substr(eq + 1), &size);
    if (!s) return s;
    for (const auto& m : field->material_sizes) {
      if (m.first == id) {
        return Status::error("--material-size: material " + id_text + " is given twice");
      }
    }
    field->material_sizes.push_back({id, size});
  }
  std::sort(field->material_sizes.begin(), field->material_sizes.end());
  return Status();
}

Status parse_size_field(const std::string& spec, SizingField* field) {
  if (spec.find_first_not_of(" ;") == std::string::npos)
    return Status::error("--size-field: empty specification");
  for (const std::string& rule : split(spec, ';')) {
    if (rule.empty()) continue;  // "box:...;" as typed, or ";;"
    const size_t colon = rule.find(':');
    const std::string kind = rule.substr(0, colon);
    const std::vector<std::string> values = colon == std::string::npos
                                                ? std::vector<std::string>{}
                                                : split(rule.substr(colon + 1), ',');
    const size_t expected = kind == "radial" ? 5 : kind == "axis" ? 8 : kind == "box" ? 7 : 0;
    if (expected == 0) {
      return Status::error("--size-field: unknown rule '" + rule +
                           "' (expected radial:..., axis:... or box:...)");
    }
    if (values.size() != expected) {
      return Status::error("--size-field: rule '" + rule + "' needs " + std::to_string(expected) +
                           " comma-separated numbers");
    }
    double v[8];
    for (size_t i = 0; i < expected; ++i) {
      if (!to_double(values[i], &v[i])) {
        return Status::error("--size-field: '" + values[i] + "' in rule '" + rule +
                             "' is not a finite number");
      }
    }
    const std::string where = "--size-field " + rule;
    if (kind == "box") {
      SizingField::Box b{{v[0], v[1], v[2]}, {v[3], v[4], v[5]}, v[6]};
      if (!(b.low.x < b.high.x && b.low.y < b.high.y && b.low.z < b.high.z)) {
        return Status::error(where + ": the box's low corner must be below its high corner");
      }
      Status s = positive_size(where, values[6], &b.size);
      if (!s) return s;
      field->boxes.push_back(b);
      continue;
    }
    SizingField::Radial r;
    r.center = {v[0], v[1], v[2]};
    const size_t k = kind == "axis" ? 6 : 3;
    if (kind == "axis") {
      const Vec3 axis{v[3], v[4], v[5]};
      if (!unit_direction(axis, &r.axis))
        return Status::error(where + ": the axis direction is zero");
    }
    Status s = positive_size(where, values[k], &r.size0);
    if (!s) return s;
    r.growth = v[k + 1];
    if (!(r.growth >= 0)) {
      return Status::error(where + ": growth '" + values[k + 1] + "' must be >= 0");
    }
    field->radial.push_back(r);
  }
  return Status();
}

}  // namespace tetlod
