// The viewer's font (ui/viewer_ui.h, add_name_glyphs()): names from mesh files show
// their Greek, Cyrillic and Latin Extended letters, not '?'. The atlas is built on
// the CPU: no window or GL context is needed.
#include <gtest/gtest.h>

#include <imgui.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

#include "ui/viewer_ui.h"

namespace tetlod::ui {
namespace {

// A fresh ImGui context for one test.
struct Context {
  Context() { ImGui::CreateContext(); }
  ~Context() { ImGui::DestroyContext(); }
};

bool has_glyph(ImWchar c) {
  ImFontAtlas* fonts = ImGui::GetIO().Fonts;
  if (!fonts->IsBuilt() && !fonts->Build()) return false;
  return fonts->Fonts[0]->FindGlyphNoFallback(c) != nullptr;
}

TEST(NameGlyphs, GreekCyrillicAndLatinExtendedLettersAreInTheFont) {
  // scripts/setup.sh installs it; a machine set up otherwise may lack it (in CI, where
  // setup.sh ran, that is a failure).
  if (!std::filesystem::exists(kNameGlyphFont)) {
    const char* ci = std::getenv("CI");
    if (ci && std::string(ci) == "true") FAIL() << kNameGlyphFont << " is missing in CI";
    GTEST_SKIP() << kNameGlyphFont << " is missing";
  }
  Context context;
  ASSERT_TRUE(add_name_glyphs(kNameGlyphFont));
  EXPECT_EQ(ImGui::GetIO().Fonts->Fonts.Size, 1);  // merged into the default font
  for (ImWchar c : {ImWchar('A'), ImWchar(0xfc), ImWchar(0x3bc), ImWchar(0x416), ImWchar(0x142)})
    EXPECT_TRUE(has_glyph(c)) << "U+" << std::hex << c;  // A, u-umlaut, mu, Zhe, l-stroke
}

TEST(NameGlyphs, WithoutTheFontFileTheDefaultFontStays) {
  Context context;
  const std::string missing = std::string(TETLOD_TEST_OUTPUT_DIR) + "/no_such_font.ttf";
  EXPECT_FALSE(add_name_glyphs(missing));
  EXPECT_TRUE(has_glyph('A'));
  EXPECT_TRUE(has_glyph(0xfc));  // Latin-1: the default font's own
  EXPECT_FALSE(has_glyph(0x3bc));
}

}  // namespace
}  // namespace tetlod::ui
