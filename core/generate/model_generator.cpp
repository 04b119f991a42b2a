// Model dispatch, option checks and the search for a volume bound that gives about
// the requested number of tets.
#include "core/generate/model_generator.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <utility>

namespace tetlod {
namespace {

// The tet count of a model meshed with volume bound a is modelled as
//   tets(a) ~ feature_tets + fill * domain_volume / a,
// feature_tets being what the PLC's small features need whatever the bound (the
// count as a grows without limit) and fill the tets per bound-sized volume in the
// volume-bound regime. Both were measured with the default quality.
struct ModelTraits {
  Model model;
  const char* name;
  double domain_volume;
  double feature_tets;  // for spheres: per icosphere triangle (all three spheres)
  double fill;
  double default_max_volume;  // the density of the committed asset
};

constexpr double kMotorBoxVolume =
    (2 * kMotorBoxHalfWidth) * (2 * kMotorBoxHalfWidth) * (2 * kMotorBoxHalfHeight);
constexpr double kSpheresBoxVolume =
    (2 * kSpheresBoxHalfWidth) * (2 * kSpheresBoxHalfWidth) * (2 * kSpheresBoxHalfWidth);

constexpr ModelTraits kModels[] = {
    {Model::kMotor, "motor", kMotorBoxVolume, 23000, 2.15, 400.0},   // asset: 26.5k tets
    {Model::kSpheres, "spheres", kSpheresBoxVolume, 3.7, 2.7, 0.5},  // asset: 16.1k tets
    {Model::kBox2, "box2", 2.0, 0, 3.4, 0.05},                       // asset: 136 tets
};

const ModelTraits& traits(Model model) {
  for (const ModelTraits& t : kModels)
    if (t.model == model) return t;
  return kModels[0];
}

double feature_tets(Model model, const GenerateOptions& options) {
  const ModelTraits& t = traits(model);
  if (model != Model::kSpheres) return t.feature_tets;
  const double triangles = 3 * 20 * std::pow(4.0, options.sphere_level);
  return t.feature_tets * triangles;
}

std::string number(double value) {
  char text[64];
  std::snprintf(text, sizeof(text), "%g", value);
  return text;
}

// How far `count` is from `target`, symmetric in over- and undershoot.
double miss(size_t count, size_t target) {
  return std::abs(std::log(static_cast<double>(count) / static_cast<double>(target)));
}

// Meshes with volume bounds chosen to land near options.target_tets, using the count
// model above: the first bound from the measured fill factor, each next one from the
// fill factor the last run implies, bisected (geometrically) between the bounds known
// to give too many and too few tets when the model would overshoot. The count is not
// continuous in the bound (it jumps where TetGen's segment splitting changes, e.g. by
// 20 % between motor bounds 1.95 and 2.0), hence the 15 % acceptance. Stops within
// 15 % or after kMaxRuns runs; a target at or below feature_tets gets the unbounded
// mesh (bound = domain volume), the smallest the model allows. Returns the closest of
// the runs.
Status generate_for_target(Model model, const Plc& plc, const GenerateOptions& options,
                           TetMesh* mesh, GenerateInfo* info) {
  constexpr int kMaxRuns = 4;
  constexpr double kGoodEnough = 0.15;
  const ModelTraits& model_traits = traits(model);
  const double volume = model_traits.domain_volume;
  const double target = static_cast<double>(options.target_tets);
  const double base = feature_tets(model, options);
  auto bound_for = [&](double fill) {
    return target > base ? std::min(volume, fill * volume / (target - base)) : volume;
  };

  double fill = model_traits.fill;
  double bound = bound_for(fill);
  double too_fine = 0;           // the largest bound known to give too many tets
  double too_coarse = HUGE_VAL;  // the smallest bound known to give too few
  TetMesh candidate;
  for (int run = 0; run < kMaxRuns; ++run) {
    if (Status s = tetrahedralize_plc(plc, {bound, options.quality}, &candidate); !s) return s;
    ++info->meshing_runs;
    const size_t count = candidate.tet_count();
    if (run == 0 ||
        miss(count, options.target_tets) < miss(mesh->tet_count(), options.target_tets)) {
      std::swap(*mesh, candidate);
      info->max_volume = bound;
    }
    if (miss(count, options.target_tets) <= std::log1p(kGoodEnough)) break;

    if (count > target) {
      too_fine = std::max(too_fine, bound);
    } else {
      too_coarse = std::min(too_coarse, bound);
    }
    const double excess = static_cast<double>(count) - base;
    if (excess > 0.1 * base) {
      fill = std::clamp(excess * bound / volume, fill / 4, fill * 4);
    } else {
      fill = count < target ? fill / 2 : fill * 2;  // the feature count is off
    }
    double next = bound_for(fill);
    if ((next <= too_fine || next >= too_coarse) && too_fine > 0 && too_coarse < HUGE_VAL) {
      next = std::sqrt(too_fine * too_coarse);
    }
    if (next == bound) break;
    bound = next;
  }
  return Status();
}

}  // namespace

const char* model_name(Model model) {
  return traits(model).name;
}

bool parse_model_name(const std::string& name, Model* model) {
  for (const ModelTraits& t : kModels) {
    if (name == t.name) {
      *model = t.model;
      return true;
    }
  }
  return false;
}

double model_domain_volume(Model model) {
  return traits(model).domain_volume;
}

Status check_generate_options(Model model, const GenerateOptions& options) {
  const ModelTraits& model_traits = traits(model);
  if (options.max_volume != 0 && options.target_tets != 0) {
    return Status::error("give either a maximum tet volume or a tet count, not both");
  }
  if (options.max_volume != 0) {
    if (!std::isfinite(options.max_volume) || options.max_volume < 0) {
      return Status::error("the maximum tet volume must be a positive number, not " +
                           number(options.max_volume));
    }
    const double estimate = feature_tets(model, options) +
                            model_traits.domain_volume * model_traits.fill / options.max_volume;
    if (estimate > static_cast<double>(kMaxTets)) {
      return Status::error("a maximum tet volume of " + number(options.max_volume) +
                           " would give about " + number(estimate) + " tets for the " +
                           model_traits.name + " model (the limit is " + number(kMaxTets) + ")");
    }
  }
  if (options.target_tets > kMaxTets) {
    return Status::error("a tet count of " + std::to_string(options.target_tets) +
                         " is above the limit of " + std::to_string(kMaxTets));
  }
  if (!(options.quality >= kMinQuality && options.quality <= kMaxQuality)) {
    return Status::error("the quality (radius-edge ratio bound) must be in [" +
                         number(kMinQuality) + ", " + number(kMaxQuality) + "], not " +
                         number(options.quality));
  }
  if (options.sphere_level < 0 || options.sphere_level > kMaxSphereLevel) {
    return Status::error("the sphere level must be in [0, " + std::to_string(kMaxSphereLevel) +
                         "], not " + std::to_string(options.sphere_level));
  }
  return Status();
}

Plc build_model_plc(Model model, const GenerateOptions& options) {
  switch (model) {
    case Model::kMotor:
      return build_motor_plc();
    case Model::kSpheres:
      return build_spheres_plc(options.sphere_level);
    case Model::kBox2:
      return build_box2_plc();
  }
  return Plc();
}

Status generate_model(Model model, const GenerateOptions& options, TetMesh* mesh,
                      GenerateInfo* info) {
  GenerateInfo local;
  GenerateInfo& out = info ? *info : local;
  out = GenerateInfo();
  if (Status s = check_generate_options(model, options); !s) return s;
  const Plc plc = build_model_plc(model, options);
  *mesh = TetMesh();
  if (options.target_tets > 0) return generate_for_target(model, plc, options, mesh, &out);

  out.max_volume = options.max_volume > 0 ? options.max_volume : traits(model).default_max_volume;
  out.meshing_runs = 1;
  return tetrahedralize_plc(plc, {out.max_volume, options.quality}, mesh);
}

}  // namespace tetlod
