// Text for the bitmap font (render/image.h): names from mesh files are UTF-8, the
// legend's font has printable ASCII only.
#include <gtest/gtest.h>

#include <string>

#include "render/image.h"

namespace tetlod::render {
namespace {

TEST(AsciiLabel, FoldsLatinLettersAndMarksOthersOncePerCharacter) {
  EXPECT_EQ(ascii_label("air gap", 32), "air gap");
  EXPECT_EQ(ascii_label("K\xc3\xbchlkanal", 32), "Kuhlkanal");  // u-umlaut
  EXPECT_EQ(ascii_label("Stra\xc3\x9f"
                        "e \xc3\x86\xc3\x98",
                        32),
            "Strasse AEO");                                            // sharp s
  EXPECT_EQ(ascii_label("\xce\xbc-metal \xc2\xb5", 32), "u-metal u");  // Greek mu, micro
  // Cyrillic and Greek are romanised: "Медь" (copper), "Щит-Ёж", "Ωμέγα" (a mu in a
  // Greek word is m, an accented epsilon e).
  EXPECT_EQ(ascii_label("\xd0\x9c\xd0\xb5\xd0\xb4\xd1\x8c", 32), "Med'");
  EXPECT_EQ(ascii_label("\xd0\xa9\xd0\xb8\xd1\x82-\xd0\x81\xd0\xb6", 32), "Shchit-Yozh");
  EXPECT_EQ(ascii_label("\xd0\xaf\xd0\xbc\xd0\xb0 \xd0\x87\xd1\x96", 32), "Yama Yii");
  EXPECT_EQ(ascii_label("\xce\xa9\xce\xbc\xce\xad\xce\xb3\xce\xb1", 32), "Omega");
  EXPECT_EQ(ascii_label("\xce\xb5_r \xce\x98\xcf\x88\xcf\x82", 32), "e_r Thpss");
  EXPECT_EQ(ascii_label("\xe7\x94\xb5\xe6\x9c\xba", 32), "??");   // two CJK characters
  EXPECT_EQ(ascii_label("\xf0\x9f\x94\xa9 bolt", 32), "? bolt");  // four bytes, one '?'
  EXPECT_EQ(ascii_label("tab\there", 32), "tab?here");
  // Not UTF-8: a stray continuation byte, an overlong '/', a cut sequence.
  EXPECT_EQ(ascii_label("a\x80"
                        "b",
                        32),
            "a?b");
  EXPECT_EQ(ascii_label("\xc0\xaf", 32), "??");
  EXPECT_EQ(ascii_label("end\xc3", 32), "end?");
}

TEST(AsciiLabel, CutsByCharactersNotBytes) {
  // By the characters drawn: a romanised letter may be several.
  EXPECT_EQ(ascii_label("\xd0\xa9\xd0\xa9\xd0\xa9", 8), "ShchShch...");
  EXPECT_EQ(ascii_label("\xd0\xa9\xd0\xa9", 8), "ShchShch");
  EXPECT_EQ(ascii_label("abcdef", 6), "abcdef");
  EXPECT_EQ(ascii_label("abcdefg", 6), "abcdef...");
  // Six two-byte letters fit in six characters; a byte cut would have split one.
  EXPECT_EQ(ascii_label("\xc3\xa4\xc3\xa4\xc3\xa4\xc3\xa4\xc3\xa4\xc3\xa4", 6), "aaaaaa");
  EXPECT_EQ(ascii_label("\xc3\xa4\xc3\xa4\xc3\xa4\xc3\xa4\xc3\xa4\xc3\xa4x", 6), "aaaaaa...");
}

}  // namespace
}  // namespace tetlod::render
