#include "app/viewer_script.h"

#include <sys/stat.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <optional>
#include <sstream>

#include "app/cli_util.h"
#include "core/io/file_access.h"
#include "core/simplify.h"
#include "core/sizing.h"

namespace tetlod::app {
namespace {

// The most frames a wait or a frame benchmark may take (a bound, as seconds= has one:
// at 60 frames a second, about half an hour).
constexpr long long kMostFrames = 100000;

using Kind = ScriptAction::Kind;

struct LineParser {
  std::string name;
  int line = 0;
  std::vector<std::string> words;

  Status error(const std::string& what) const {
    return Status::error(name + ":" + std::to_string(line) + ": " + what);
  }
  // Splits "key=value"; false if there is no '='.
  static bool key_value(const std::string& word, std::string* key, std::string* value) {
    const size_t eq = word.find('=');
    if (eq == std::string::npos) return false;
    *key = word.substr(0, eq);
    *value = word.substr(eq + 1);
    return true;
  }
  Status number(const std::string& key, const std::string& text, double* out) const {
    const std::optional<double> v = parse_double(text);
    if (!v) return error("'" + key + "' needs a number, got '" + text + "'");
    *out = *v;
    return Status();
  }
  Status integer(const std::string& key, const std::string& text, long long* out) const {
    const std::optional<long long> v = parse_integer(text);
    if (!v) return error("'" + key + "' needs a whole number, got '" + text + "'");
    *out = *v;
    return Status();
  }
  Status on_off(const std::string& key, const std::string& text, bool* out) const {
    if (text == "1" || text == "on" || text == "true") {
      *out = true;
    } else if (text == "0" || text == "off" || text == "false") {
      *out = false;
    } else {
      return error("'" + key + "' needs on/off (or 1/0), got '" + text + "'");
    }
    return Status();
  }
  Status arg_count(size_t low, size_t high) const {
    const size_t n = words.size() - 1;
    if (n < low || n > high) {
      return error("'" + words[0] + "' takes " +
                   (low == high ? std::to_string(low)
                                : std::to_string(low) + " to " + std::to_string(high)) +
                   " argument(s), got " + std::to_string(n));
    }
    return Status();
  }
};

Status parse_thresholds(const LineParser& p, ScriptAction* a) {
  if (p.words.size() < 2) return p.error("'thresholds' needs at least one key=value");
  for (size_t i = 1; i < p.words.size(); ++i) {
    std::string key, value;
    if (!LineParser::key_value(p.words[i], &key, &value))
      return p.error("expected key=value, got '" + p.words[i] + "'");
    for (size_t j = 1; j < i; ++j) {
      std::string earlier, unused;
      if (LineParser::key_value(p.words[j], &earlier, &unused) && earlier == key)
        return p.error("'" + key + "' is given twice");
    }
    double number = 0;
    if (key == "size" || key == "stretch" || key == "tolerance" || key == "crease-angle") {
      if (Status s = p.number(key, value, &number); !s) return s;
      if (key == "size") {
        if (!(number > 0)) return p.error("size must be > 0");
        a->size = number;
      } else if (key == "stretch") {
        if (!(number >= kMinStretch && number < 1))
          return p.error("stretch=" + value +
                         " must be in [0.00012, 1) (below, tets too flat to read back would "
                         "pass)");
        a->stretch = number;
      } else if (key == "crease-angle") {
        if (!(number > 0 && number < 180))
          return p.error("crease-angle=" + value +
                         " must lie strictly between 0 and 180 (degrees)");
        a->crease_angle = number;
      } else {
        if (!(number >= 0)) return p.error("tolerance must be >= 0");
        a->tolerance = number;
      }
    } else if (key == "valence") {
      long long v = 0;
      if (Status s = p.integer(key, value, &v); !s) return s;
      if (v < 4 || v > kMaxValence)
        return p.error("valence must be in [4, " + std::to_string(kMaxValence) + "]");
      a->valence = v;
    } else if (key == "subdivide") {
      bool on = false;
      if (Status s = p.on_off(key, value, &on); !s) return s;
      a->subdivide = on;
    } else if (key == "keep-inside") {
      bool on = false;
      if (Status s = p.on_off(key, value, &on); !s) return s;
      a->keep_inside = on;
    } else if (key == "material-sizes") {
      std::vector<std::pair<int32_t, double>> ids;
      if (Status s = resolve_material_sizes(value, nullptr, &ids); !s) return p.error(s.message());
      a->material_sizes = value;
    } else if (key == "region") {
      SizingField field;
      if (Status s = parse_size_field(value, &field); !s) {
        // Its messages name the CLI's option.
        std::string message = s.message();
        if (message.rfind("--size-field", 0) == 0) message.replace(0, 12, "region");
        return p.error(message);
      }
      a->region = value;
    } else if (key == "sizing") {
      if (value != "map" && value != "uniform")
        return p.error("sizing must be map or uniform (region= and material-sizes= set theirs)");
      a->size_map = value == "map";
    } else {
      return p.error("unknown threshold '" + key +
                     "' (size, stretch, valence, tolerance, subdivide, keep-inside, "
                     "crease-angle, material-sizes, region, sizing)");
    }
  }
  return Status();
}

std::optional<int32_t> material_id(const std::string& text) {
  const std::optional<long long> n = parse_integer(text);
  if (!n || *n < 0 || *n > 0x7fffffff) return std::nullopt;
  return static_cast<int32_t>(*n);
}

// "M:X,M:X": materials (ids, or names resolved when the line runs) and finite numbers.
Status parse_material_values(const LineParser& p, const std::string& key, const std::string& text,
                             std::vector<std::pair<int32_t, double>>* out,
                             std::vector<ScriptAction::NamedMaterial>* named) {
  for (const std::string& item : split_value_items(text, ':')) {
    if (item.empty()) return p.error("'" + key + "=" + text + "': " + kEmptyItem);
    std::string material;
    double value = 0;
    const bool has_value = split_material_value(item, ':', &material, &value);
    const std::optional<int32_t> id = material_id(material);
    if (!(id || is_material_name(material)) || !has_value)
      return p.error("'" + key + "': '" + item +
                     "' is not MATERIAL:NUMBER (a material id >= 0 or name, and a finite "
                     "number)");
    if (id)
      out->push_back({*id, value});
    else
      named->push_back({key, material, value});
  }
  return Status();
}

Status parse_analysis(const LineParser& p, ScriptAction* a) {
  if (p.words.size() < 2) return p.error("'analysis' needs conductor=M:V");
  bool has_ground = false;
  for (size_t i = 1; i < p.words.size(); ++i) {
    std::string key, value;
    if (!LineParser::key_value(p.words[i], &key, &value))
      return p.error("expected key=value, got '" + p.words[i] + "'");
    if (key == "conductor") {
      if (Status s = parse_material_values(p, key, value, &a->problem.conductors, &a->named); !s)
        return s;
    } else if (key == "eps") {
      if (Status s = parse_material_values(p, key, value, &a->problem.permittivities, &a->named);
          !s)
        return s;
    } else if (key == "ground") {
      has_ground = true;
      for (const std::string& item : split_items(value)) {
        if (item.empty()) return p.error("'ground=" + value + "': " + kEmptyItem);
        if (item == "boundary") {
          a->problem.ground_boundary = true;
        } else if (const auto m = material_id(item)) {
          a->problem.ground_materials.push_back(*m);
        } else if (is_material_name(item)) {
          a->named.push_back({key, item, 0});
        } else {
          return p.error("'ground': '" + item +
                         "' is neither 'boundary' nor a material id or name");
        }
      }
    } else {
      return p.error("unknown analysis key '" + key + "' (conductor, ground, eps)");
    }
  }
  std::vector<double> potentials;
  for (const auto& [m, v] : a->problem.conductors) potentials.push_back(v);
  for (const ScriptAction::NamedMaterial& n : a->named)
    if (n.key == "conductor") potentials.push_back(n.value);
  if (potentials.empty()) return p.error("'analysis' needs conductor=M:V");
  const bool two_potentials = std::any_of(potentials.begin(), potentials.end(),
                                          [&](double v) { return v != potentials[0]; });
  if (!has_ground && !two_potentials)
    return p.error("'analysis' needs ground=boundary|M[,...] (or conductors at two potentials)");
  return Status();
}

Status parse_line(const LineParser& p, ScriptAction* a) {
  const std::string& command = p.words[0];
  const std::vector<std::string>& w = p.words;
  if (command == "open") {
    a->kind = Kind::kOpen;
    if (Status s = p.arg_count(1, 2); !s) return s;
    a->path = w[1];
    if (w.size() == 3) {
      if (w[2] != "may-fail") return p.error("expected 'may-fail', got '" + w[2] + "'");
      a->flag = true;
    }
  } else if (command == "thresholds") {
    a->kind = Kind::kThresholds;
    return parse_thresholds(p, a);
  } else if (command == "simplify") {
    a->kind = Kind::kSimplify;
    a->flag = true;
    if (Status s = p.arg_count(0, 1); !s) return s;
    if (w.size() == 2) {
      std::string key, value;
      if (!LineParser::key_value(w[1], &key, &value) || key != "wait")
        return p.error("'simplify' takes wait=0|1, got '" + w[1] + "'");
      return p.on_off(key, value, &a->flag);
    }
  } else if (command == "cancel") {
    a->kind = Kind::kCancel;
    return p.arg_count(0, 0);
  } else if (command == "scrub") {
    if (Status s = p.arg_count(1, 1); !s) return s;
    std::string key, value;
    if (w[1] == "end") {
      a->kind = Kind::kScrubEnd;
    } else if (LineParser::key_value(w[1], &key, &value) && (key == "step" || key == "elements")) {
      a->kind = key == "step" ? Kind::kScrubStep : Kind::kScrubElements;
      if (Status s = p.integer(key, value, &a->count); !s) return s;
      // (elements, as --elements: a level of at least one element.)
      const long long least = key == "elements" ? 1 : 0;
      if (a->count < least) return p.error("'" + key + "' must be >= " + std::to_string(least));
    } else {
      return p.error("'scrub' takes step=K, elements=N or end, got '" + w[1] + "'");
    }
  } else if (command == "cut") {
    if (Status s = p.arg_count(1, 2); !s) return s;
    if (w[1] == "off") {
      a->kind = Kind::kCutOff;
      return p.arg_count(1, 1);
    }
    a->kind = Kind::kCut;
    std::string key, value;
    if (!LineParser::key_value(w[1], &key, &value) || key.size() != 1 || key[0] < 'x' ||
        key[0] > 'z')
      return p.error("'cut' takes x=V, y=V or z=V (or off), got '" + w[1] + "'");
    a->axis = key[0] - 'x';
    if (Status s = p.number(key, value, &a->value); !s) return s;
    if (w.size() == 3) {
      if (w[2] != "flip") return p.error("expected 'flip', got '" + w[2] + "'");
      a->flag = true;
    }
  } else if (command == "hide" || command == "show") {
    a->kind = command == "hide" ? Kind::kHide : Kind::kShow;
    if (w.size() < 2) return p.arg_count(1, 1);
    std::string rest;  // a name is the rest of the line: hide rotor iron, hide 2 pole magnet
    for (size_t i = 1; i < w.size(); ++i) rest += (i > 1 ? " " : "") + w[i];
    const std::vector<std::string> items = split_items(rest);
    if (items.size() > 1 && std::none_of(items.begin(), items.end(), is_material_name))
      return p.error("'" + command + "' takes one material a line, got '" + rest +
                     "'");  // --hide's list
    if (is_material_name(rest)) {
      a->word = rest;
    } else if (Status s = p.integer("material", rest, &a->count); !s) {
      return s;
    } else if (a->count < 0 || a->count > 0x7fffffff) {
      return p.error("'" + rest + "' is not a material id (>= 0)");
    }
  } else if (command == "groups") {
    a->kind = Kind::kGroups;
    if (w.size() < 2) return p.arg_count(1, 1);
    for (size_t i = 1; i < w.size(); ++i) a->word += (i > 1 ? " " : "") + w[i];
  } else if (command == "color") {
    a->kind = Kind::kColor;
    if (Status s = p.arg_count(1, 1); !s) return s;
    if (w[1] != "stretch" && w[1] != "material" && w[1] != "field" && w[1] != "size")
      return p.error("'color' takes stretch, material, field or size, got '" + w[1] + "'");
    a->word = w[1];
  } else if (command == "colormap") {
    a->kind = Kind::kColormap;
    if (Status s = p.arg_count(1, 1); !s) return s;
    if (w[1] != "viridis" && w[1] != "turbo")
      return p.error("'colormap' takes viridis or turbo, got '" + w[1] + "'");
    a->word = w[1];
  } else if (command == "range") {
    a->kind = Kind::kRange;
    if (Status s = p.arg_count(2, 2); !s) return s;
    if (Status s = p.number("min", w[1], &a->value); !s) return s;
    if (Status s = p.number("max", w[2], &a->value2); !s) return s;
    if (!(a->value < a->value2)) return p.error("range needs MIN < MAX");
  } else if (command == "wireframe") {
    a->kind = Kind::kWireframe;
    if (Status s = p.arg_count(1, 1); !s) return s;
    return p.on_off("wireframe", w[1], &a->flag);
  } else if (command == "legend") {
    a->kind = Kind::kLegend;
    if (Status s = p.arg_count(1, 1); !s) return s;
    return p.on_off("legend", w[1], &a->flag);
  } else if (command == "highlight") {
    if (Status s = p.arg_count(1, 1); !s) return s;
    if (w[1] == "off") {
      a->kind = Kind::kHighlightOff;
    } else {
      a->kind = Kind::kHighlight;
      if (Status s = p.number("highlight", w[1], &a->value); !s) return s;
      // As --highlight-below (and the panel's slider): a stretch in (0, 1].
      if (!(a->value > 0 && a->value <= 1))
        return p.error("'highlight' takes a stretch in (0, 1] or off, got '" + w[1] + "'");
    }
  } else if (command == "view") {
    a->kind = Kind::kView;
    if (Status s = p.arg_count(1, 1); !s) return s;
    if (w[1] != "iso" && w[1] != "x" && w[1] != "y" && w[1] != "z" && w[1] != "fit")
      return p.error("'view' takes iso, x, y, z or fit, got '" + w[1] + "'");
    a->word = w[1];
  } else if (command == "orbit" || command == "pan") {
    a->kind = command == "orbit" ? Kind::kOrbit : Kind::kPan;
    if (Status s = p.arg_count(2, 2); !s) return s;
    if (Status s = p.number("dx", w[1], &a->value); !s) return s;
    if (Status s = p.number("dy", w[2], &a->value2); !s) return s;
  } else if (command == "mouse") {
    a->kind = Kind::kMouse;
    if (Status s = p.arg_count(2, 2); !s) return s;
    if (Status s = p.number("x", w[1], &a->value); !s) return s;
    if (Status s = p.number("y", w[2], &a->value2); !s) return s;
    if (!(a->value >= 0 && a->value <= 16384 && a->value2 >= 0 && a->value2 <= 16384))
      return p.error("'mouse' takes pixel coordinates in [0, 16384]");
  } else if (command == "zoom") {
    a->kind = Kind::kZoom;
    if (Status s = p.arg_count(1, 1); !s) return s;
    if (Status s = p.number("clicks", w[1], &a->value); !s) return s;
  } else if (command == "screenshot") {
    a->kind = Kind::kScreenshot;
    if (Status s = p.arg_count(1, 4); !s) return s;
    a->path = w[1];
    if (std::string problem = screenshot_problem(a->path, 0, 0); !problem.empty())
      return p.error(problem);
    for (size_t i = 2; i < w.size(); ++i) {
      std::string key, value;
      long long v = 0;
      if (!LineParser::key_value(w[i], &key, &value))
        return p.error("expected key=value, got '" + w[i] + "'");
      if (key == "ui") {
        if (Status s = p.on_off(key, value, &a->flag); !s) return s;
      } else if (key == "width" || key == "height") {
        if (Status s = p.integer(key, value, &v); !s) return s;
        if (v < 16 || v > 8192)
          return p.error("'" + key +
                         "' must be in [16, 8192] (or leave out width and height for "
                         "the view's size)");
        (key == "width" ? a->width : a->height) = static_cast<int>(v);
      } else {
        return p.error("unknown screenshot option '" + key + "' (ui, width, height)");
      }
    }
    if ((a->width == 0) != (a->height == 0)) return p.error("give both width and height");
    if (a->flag && a->width != 0)
      return p.error("a screenshot with the UI is taken at the window size (--size WxH)");
  } else if (command == "save") {
    a->kind = Kind::kSave;
    if (Status s = p.arg_count(1, 4); !s) return s;
    a->path = w[1];
    for (size_t i = 2; i < w.size(); ++i) {
      bool* option = w[i] == "improve"    ? &a->flag
                     : w[i] == "surfaces" ? &a->surfaces
                     : w[i] == "binary"   ? &a->binary
                                          : nullptr;
      if (!option || *option) return p.error("'save' takes PATH [improve] [surfaces] [binary]");
      *option = true;
    }
  } else if (command == "wait") {
    a->kind = Kind::kWait;
    if (Status s = p.arg_count(1, 1); !s) return s;
    std::string key, value;
    if (w[1] == "done") {
      a->flag = true;
      return Status();
    }
    if (!LineParser::key_value(w[1], &key, &value) || (key != "frames" && key != "seconds"))
      return p.error("'wait' takes frames=N, seconds=S or done");
    if (key == "frames") {
      if (Status s = p.integer(key, value, &a->count); !s) return s;
      if (a->count < 0 || a->count > kMostFrames)
        return p.error("frames must be in [0, " + std::to_string(kMostFrames) + "]");
    } else {
      if (Status s = p.number(key, value, &a->value); !s) return s;
      if (!(a->value >= 0 && a->value <= 3600)) return p.error("seconds must be in [0, 3600]");
    }
  } else if (command == "bench-scrub" || command == "bench-frames") {
    a->kind = command == "bench-scrub" ? Kind::kBenchScrub : Kind::kBenchFrames;
    a->count = 120;
    if (Status s = p.arg_count(0, 2); !s) return s;
    for (size_t i = 1; i < w.size(); ++i) {
      std::string key, value;
      if (!LineParser::key_value(w[i], &key, &value))
        return p.error("expected key=value, got '" + w[i] + "'");
      if (key == "frames") {
        if (Status s = p.integer(key, value, &a->count); !s) return s;
        if (a->count < 1 || a->count > kMostFrames)
          return p.error("frames must be in [1, " + std::to_string(kMostFrames) + "]");
      } else if (key == "out") {
        a->path = value;
      } else {
        return p.error("unknown " + command + " option '" + key + "' (frames, out)");
      }
    }
  } else if (command == "field-range") {
    a->kind = Kind::kFieldRange;
    if (Status s = p.arg_count(1, 1); !s) return s;
    a->value = 100;
    if (w[1] != "max") {
      if (Status s = p.number("percentile", w[1], &a->value); !s) return s;
      if (!(a->value > 0 && a->value <= 100))
        return p.error("the percentile must be in (0, 100], got '" + w[1] + "'");
    }
  } else if (command == "analysis") {
    a->kind = Kind::kAnalysis;
    return parse_analysis(p, a);
  } else if (command == "solve") {
    a->kind = Kind::kSolve;
    a->count = 1;  // wait
    if (Status s = p.arg_count(0, 2); !s) return s;
    for (size_t i = 1; i < w.size(); ++i) {
      std::string key, value;
      if (w[i] == "may-fail") {
        a->flag = true;
      } else if (LineParser::key_value(w[i], &key, &value) && key == "wait") {
        bool wait = true;
        if (Status s = p.on_off(key, value, &wait); !s) return s;
        a->count = wait ? 1 : 0;
      } else {
        return p.error("'solve' takes may-fail and wait=0|1, got '" + w[i] + "'");
      }
    }
  } else if (command == "report-analysis" || command == "report-tet") {
    a->kind = command == "report-tet" ? Kind::kReportTet : Kind::kReportAnalysis;
    if (Status s = p.arg_count(1, 1); !s) return s;
    a->path = w[1];
  } else if (command == "quit") {
    a->kind = Kind::kQuit;
    return p.arg_count(0, 0);
  } else {
    return p.error("unknown command '" + command + "'");
  }
  return Status();
}

// The words of a line, blank-separated; double quotes keep blanks in a word ("rotor
// iron") and are dropped; '#' outside quotes starts a comment. False for a quote left
// open.
bool split_words(const std::string& line, std::vector<std::string>* words) {
  words->clear();
  std::string word;
  bool in_word = false, quoted = false;
  for (const char c : line) {
    if (c == '"') {
      quoted = !quoted;
      in_word = true;
    } else if (!quoted && c == '#') {
      break;
    } else if (!quoted && (c == ' ' || c == '\t' || c == '\r')) {
      if (in_word) words->push_back(std::move(word));
      word.clear();
      in_word = false;
    } else {
      word += c;
      in_word = true;
    }
  }
  if (in_word) words->push_back(std::move(word));
  return !quoted;
}

}  // namespace

Status resolve_material_sizes(const std::string& spec, const std::vector<MaterialName>* names,
                              std::vector<std::pair<int32_t, double>>* out) {
  out->clear();
  for (const std::string& item : split_value_items(spec, '=')) {
    std::string material;
    double size = 0;
    const bool has_size = split_material_value(item, '=', &material, &size);
    const std::optional<int32_t> id = material_id(material);
    if (!(id || is_material_name(material)) || !has_size || !(size > 0))
      return Status::error("material-sizes: '" + item +
                           "' is not MATERIAL=SIZE (a material id >= 0 or name, and a size > 0)");
    int32_t m = id.value_or(0);
    if (!id && names) {
      std::string why;
      if (!find_material(material, *names, &m, &why))
        return Status::error("material-sizes: " + why);
    }
    if (!id && !names) continue;
    for (const auto& [given, unused] : *out)
      if (given == m)
        return Status::error("material-sizes: material " + std::to_string(m) + " is given twice");
    out->push_back({m, size});
  }
  std::sort(out->begin(), out->end());
  return Status();
}

std::string screenshot_problem(const std::string& path, int width, int height) {
  if (!has_extension(path, ".png"))
    return "a screenshot is written as PNG: give a .png name, got '" + path + "'";
  const auto in_range = [](int v) { return v >= 16 && v <= 8192; };
  if (!(width == 0 && height == 0) && !(in_range(width) && in_range(height)))
    return "a screenshot's size is 16 to 8192 pixels a side, or 0 x 0 for the view's, not " +
           std::to_string(width) + " x " + std::to_string(height);
  return "";
}

Status parse_script_text(const std::string& text, const std::string& name,
                         std::vector<ScriptAction>* actions) {
  std::vector<ScriptAction> out;
  std::istringstream lines(text);
  std::string line;
  LineParser p;
  p.name = name;
  while (std::getline(lines, line)) {
    ++p.line;
    // A byte-order mark before the first line, as some editors write it.
    if (p.line == 1 && line.compare(0, 3, "\xef\xbb\xbf") == 0) line.erase(0, 3);
    // A NUL would cut a path where it is opened, not where it is read.
    if (line.find('\0') != std::string::npos) return p.error("a NUL byte");
    if (!split_words(line, &p.words)) return p.error("a '\"' is left open");
    if (p.words.empty()) continue;
    ScriptAction a;
    a.line = p.line;
    if (Status s = parse_line(p, &a); !s) return s;
    out.push_back(std::move(a));
  }
  *actions = std::move(out);
  return Status();
}

Status parse_script(const std::string& path, std::vector<ScriptAction>* actions) {
  // A script is small; an endless file (/dev/zero) is not one. A named pipe (a
  // shell's <(...)) is read as io::read_file() reads one: one nobody writes to is an
  // error after a wait, not a wait without end in opening it.
  constexpr size_t kMaxScriptBytes = size_t(16) << 20;
  std::string text;
  struct stat info;
  if (stat(path.c_str(), &info) == 0 && S_ISFIFO(info.st_mode)) {
    if (Status s = io::read_file(path, &text); !s) return s;
    if (text.size() > kMaxScriptBytes)
      return Status::error(path + ": more than 16 MiB: not a script");
    return parse_script_text(text, path, actions);
  }
  std::ifstream in(path, std::ios::binary);
  if (!in) return Status::error(path + ": cannot open the script");
  char buffer[1 << 16];
  while (in.read(buffer, sizeof buffer) || in.gcount() > 0) {
    text.append(buffer, size_t(in.gcount()));
    if (text.size() > kMaxScriptBytes)
      return Status::error(path + ": more than 16 MiB: not a script");
  }
  return parse_script_text(text, path, actions);
}

}  // namespace tetlod::app
