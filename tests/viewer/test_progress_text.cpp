// The texts of the viewer's progress bars (ui::top_progress_text() and its siblings),
// for set statuses and for every report of real runs, as the viewer copies them from
// SimplifyProgress into its status; and what the panel says after a run of what its
// final mesh and its input break (ui::final_mesh_text()).
#include <gtest/gtest.h>

#include <set>
#include <string>
#include <vector>

#include "core/io/mesh_io.h"
#include "core/simplify.h"
#include "ui/viewer_ui.h"

namespace tetlod {
namespace {

ui::ViewerStatus running(const std::string& phase, double fraction, size_t collapses) {
  ui::ViewerStatus s;
  s.running = true;
  s.phase = phase;
  s.phase_fraction = fraction;
  s.collapses = collapses;
  return s;
}

TEST(ProgressText, FirstRun) {
  const ui::ViewerStatus evaluate = running("evaluate edges", 0.694, 0);
  EXPECT_EQ(ui::top_progress_text(evaluate), "simplifying: evaluate edges 69%");
  EXPECT_EQ(ui::section_progress_text(evaluate), "evaluate edges 69%");
  const ui::ViewerStatus collapsing = running("simplify", 0.06, 19958);
  EXPECT_EQ(ui::top_progress_text(collapsing), "simplify 6%, 19958 collapses");
  EXPECT_EQ(ui::section_progress_text(collapsing), "simplify 6%");
  EXPECT_EQ(ui::other_run_progress_text(collapsing), "");  // no second run: no second bar
  EXPECT_EQ(ui::top_progress_text(running("subdivide", 1, 0)), "simplifying: subdivide 100%");
}

TEST(ProgressText, RunPastTheValence) {
  ui::ViewerStatus past = running("valence collapses", 0.2, 120);
  past.past_valence_run = true;
  EXPECT_EQ(ui::top_progress_text(past), "past the valence: valence collapses 20%");
  EXPECT_EQ(ui::section_progress_text(past), "past the valence: valence collapses 20%");
  ui::ViewerStatus alongside = running("simplify", 0.5, 3000);
  alongside.other_phase = "red levels";
  alongside.other_fraction = 0.655;
  EXPECT_EQ(ui::top_progress_text(alongside), "simplify 50%, 3000 collapses");
  EXPECT_EQ(ui::other_run_progress_text(alongside), "past the valence: red levels 66%");
}

// A phase name longer than the bars' buffers is cut, not overrun.
TEST(ProgressText, LongPhaseIsCut) {
  const std::string text = ui::top_progress_text(running(std::string(500, 'x'), 0.5, 0));
  EXPECT_LT(text.size(), 200u);
  EXPECT_EQ(text.rfind("simplifying: xxx", 0), 0u);
}

// Every report of real runs gives the bars a text naming its phase and percentage:
// the bundled motor at size 18 makes a run past the valence, after the first run (its
// phases then are the run past the valence's) or alongside it on a second thread (the
// first run's reports then say where that run is).
TEST(ProgressText, EveryReportOfRealRuns) {
  TetMesh input;
  ReadInfo info;
  ASSERT_TRUE(read_mesh(TETLOD_SOURCE_DIR "/assets/motor.mesh", &input, &info));
  std::set<std::string> seen;
  bool past_seen = false, other_seen = false;
  for (const bool alongside : {false, true}) {
    SimplifyParams params;
    params.sizing.uniform = 18;
    params.tolerance = 0.05;
    params.past_valence_alongside = alongside;
    SimplifyResult result;
    std::vector<SimplifyProgress> reports;
    std::vector<std::string> other_phases;  // the pointers live only during the call
    ASSERT_TRUE(simplify(input, params, &result, [&](const SimplifyProgress& p) {
      reports.push_back(p);
      other_phases.emplace_back(p.other_phase ? p.other_phase : "");
    }));
    ASSERT_TRUE(result.past_valence.tried);
    ASSERT_FALSE(reports.empty());
    for (size_t i = 0; i < reports.size(); ++i) {
      const SimplifyProgress& p = reports[i];
      ui::ViewerStatus s = running(p.phase, p.fraction, p.collapses);
      s.past_valence_run = p.past_valence;
      s.other_phase = other_phases[i];
      s.other_fraction = p.other_fraction;
      const std::string top = ui::top_progress_text(s);
      SCOPED_TRACE(top);
      EXPECT_NE(top.find(p.phase), std::string::npos);
      // "<phase> <percent>%", the percentage rounded.
      const std::string section = ui::section_progress_text(s);
      const std::string phase_space = std::string(p.phase) + " ";
      const size_t at = section.find(phase_space);
      ASSERT_NE(at, std::string::npos) << section;
      ASSERT_EQ(section.back(), '%') << section;
      const std::string digits =
          section.substr(at + phase_space.size(), section.size() - 1 - at - phase_space.size());
      EXPECT_NEAR(std::stod(digits), 100 * p.fraction, 0.5) << section;
      EXPECT_NE(top.find(digits + "%"), std::string::npos);
      EXPECT_EQ(top.rfind("past the valence: ", 0) == 0, p.past_valence);
      const std::string other = ui::other_run_progress_text(s);
      EXPECT_EQ(other.empty(), other_phases[i].empty());
      if (!other.empty()) {
        EXPECT_EQ(other.rfind("past the valence: " + other_phases[i], 0), 0u);
      }
      seen.insert(p.phase);
      past_seen |= p.past_valence;
      other_seen |= !other_phases[i].empty();
    }
  }
  for (const char* phase : {"subdivide", "classify", "evaluate edges", "simplify", "red levels"})
    EXPECT_EQ(seen.count(phase), 1u) << phase;
  EXPECT_TRUE(past_seen);
  EXPECT_TRUE(other_seen);
}

// After a run: what the final mesh breaks, whether it is all the input's, and what the
// input broke.
TEST(FinalMeshText, SaysWhatTheFinalMeshAndTheInputBreak) {
  ui::ViewerStatus s;
  s.has_result = true;
  s.violations = {4, 0, 1, 0};
  s.input_breaks = {6, 0, 1};
  EXPECT_EQ(ui::final_mesh_text(s),
            "Final mesh: 4 tets below the stretch, 0 above the size, 1 node above the valence; "
            "all input ones or pieces of input tets that already broke it; the input: 6 tets "
            "below the stretch, 0 above the size, 1 node above the valence.");
  s.violations = {};
  EXPECT_EQ(ui::final_mesh_text(s),
            "Final mesh: every tet and node within the thresholds; the input: 6 tets below the "
            "stretch, 0 above the size, 1 node above the valence.");
  s.violations = {1, 0, 0, 1};
  EXPECT_NE(ui::final_mesh_text(s).find("some new ones: please report it"), std::string::npos);
}

// The panel's stretch range keeps its ends apart (it allowed MIN = MAX).
TEST(FinalMeshText, RangeEndsKeptApart) {
  float low = 0.2f, high = 0.2f;
  ui::keep_range_apart(&low, &high);
  EXPECT_FLOAT_EQ(low, 0.2f);
  EXPECT_FLOAT_EQ(high, 0.21f);
  low = 1.0f, high = 1.0f;
  ui::keep_range_apart(&low, &high);
  EXPECT_FLOAT_EQ(low, 0.99f);
  EXPECT_FLOAT_EQ(high, 1.0f);
  low = 0.1f, high = 0.5f;
  ui::keep_range_apart(&low, &high);
  EXPECT_FLOAT_EQ(low, 0.1f);
  EXPECT_FLOAT_EQ(high, 0.5f);
}

// The strip without levels asks for a run only if there was none (after a run that
// allowed no collapse it asked for the Simplify just done).
TEST(FinalMeshText, NoHistoryText) {
  ui::ViewerStatus s;
  s.elements = 136;
  EXPECT_EQ(ui::no_history_text(s), "Simplify to get a collapse history (136 elements).");
  s.has_result = true;
  EXPECT_EQ(ui::no_history_text(s), "no collapse: the thresholds allowed none (136 elements).");
  s.has_result = false;
  s.from_history = true;
  EXPECT_EQ(ui::no_history_text(s), "no collapse: the thresholds allowed none (136 elements).");
}

// The verdict names the thresholds it was computed with, and once the panel's differ
// from them it says it is not of the panel's (it stayed under the sliders after they
// were changed, as if it applied to the new values).
TEST(FinalMeshText, NamesTheRunsThresholdsAndWhetherThePanelsDiffer) {
  ui::ViewerStatus s;
  s.has_result = true;
  s.violations = {0, 2, 0, 0};
  s.result_thresholds = "size 30, stretch 0.1, valence 25, tolerance 0.05";
  EXPECT_EQ(ui::final_mesh_text(s),
            "Final mesh, for the run's thresholds (size 30, stretch 0.1, valence 25, tolerance "
            "0.05): 0 tets below the stretch, 2 above the size, 0 nodes above the valence; all "
            "input ones or pieces of input tets that already broke it; the input: 0 tets below "
            "the stretch, 0 above the size, 0 nodes above the valence.");
  s.result_thresholds_changed = true;
  const std::string stale = ui::final_mesh_text(s);
  EXPECT_EQ(stale.substr(0, stale.find(':')),
            "Final mesh, for the run's thresholds (size 30, stretch 0.1, valence 25, tolerance "
            "0.05), not the panel's, changed since");
}

// Whether the panel still shows the run's thresholds: any threshold or the sizing
// changed makes it differ.
TEST(FinalMeshText, SameThresholdsComparesEveryThresholdAndTheSizing) {
  ui::ThresholdSettings panel;
  panel.size = 30;
  SimplifyParams run;
  std::string error;
  ASSERT_TRUE(ui::to_simplify_params(panel, &run, &error)) << error;
  EXPECT_TRUE(ui::same_thresholds(panel, run));
  ui::ThresholdSettings changed = panel;
  changed.stretch = 0.2;
  EXPECT_FALSE(ui::same_thresholds(changed, run));
  changed = panel;
  changed.valence = 20;
  EXPECT_FALSE(ui::same_thresholds(changed, run));
  changed = panel;
  changed.tolerance *= 2;
  EXPECT_FALSE(ui::same_thresholds(changed, run));
  changed = panel;
  changed.subdivide = false;
  EXPECT_FALSE(ui::same_thresholds(changed, run));
  changed = panel;
  changed.sizing_mode = ui::SizingMode::kRegion;
  changed.region_spec = "box:0,0,0,1,1,1,5";
  EXPECT_FALSE(ui::same_thresholds(changed, run));
  SimplifyParams region_run;
  ASSERT_TRUE(ui::to_simplify_params(changed, &region_run, &error)) << error;
  EXPECT_TRUE(ui::same_thresholds(changed, region_run));
  changed.region_spec = "box:0,0,0,1,1,2,5";
  EXPECT_FALSE(ui::same_thresholds(changed, region_run));
  changed = panel;
  changed.stretch = 5;  // no parameters at all: not the run's
  EXPECT_FALSE(ui::same_thresholds(changed, run));
}

// The simplifier's errors name the command line's flags; the panel names its own
// controls instead.
TEST(SimplifyErrorText, NamesThePanelsControlsNotTheFlags) {
  EXPECT_EQ(ui::simplify_error_text("size 0.001 would subdivide the mesh into about 90000000000 "
                                    "tets (limit 40000000); choose a larger size or "
                                    "--no-subdivide"),
            "size 0.001 would subdivide the mesh into about 90000000000 tets (limit 40000000); "
            "choose a larger size or untick \"Subdivide first\" above");
  EXPECT_EQ(ui::simplify_error_text("no size limit given (set --size)"),
            "no size limit given (set the size)");
  EXPECT_EQ(ui::simplify_error_text("stretch 5 must lie strictly between 0 and 1"),
            "stretch 5 must lie strictly between 0 and 1");
  // A script's error names the script's words.
  EXPECT_EQ(ui::script_error_text("size 0.001 would subdivide the mesh into about 9 tets; "
                                  "choose a larger size or --no-subdivide"),
            "size 0.001 would subdivide the mesh into about 9 tets; choose a larger size or "
            "'thresholds subdivide=0'");
  EXPECT_EQ(ui::script_error_text("no size limit given (set --size)"),
            "no size limit given (set 'thresholds size=S')");
  // The region rules' errors (parse_size_field() names --size-field).
  EXPECT_EQ(ui::simplify_error_text("thresholds: --size-field: unknown rule 'ball:1'"),
            "thresholds: the region rules: unknown rule 'ball:1'");
  EXPECT_EQ(ui::script_error_text("thresholds: --size-field box:0,0,0,1,1,1,-2: size"),
            "thresholds: region box:0,0,0,1,1,1,-2: size");
}

// A failed open says what goes on running: a solve too (it said only a simplification).
TEST(StillRunningText, NamesWhatGoesOn) {
  EXPECT_EQ(ui::still_running_text(false, false), "");
  EXPECT_EQ(ui::still_running_text(true, false), "; the running simplification goes on");
  EXPECT_EQ(ui::still_running_text(false, true), "; the running solve goes on");
  EXPECT_EQ(ui::still_running_text(true, true), "; the running simplification and solve go on");
}

}  // namespace
}  // namespace tetlod
