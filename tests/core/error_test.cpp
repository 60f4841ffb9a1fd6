// The one-line error policy's text (core/error.h): what a problem may quote of a file.
#include "core/error.h"

#include <gtest/gtest.h>

#include <string>

namespace photovr {
namespace {

TEST(PrintableLine, KeepsTextAndWellFormedUtf8) {
  const std::string text = "accessor 3: caf\xc3\xa9, \xe2\x82\xac and \xf0\x9f\x99\x82 ~";
  EXPECT_EQ(printableLine(text), text);
}

TEST(PrintableLine, EscapesControlCharactersAndBytesThatAreNotUtf8) {
  EXPECT_EQ(printableLine("a\nb\tc\x7f"), "a\\x0ab\\x09c\\x7f");
  EXPECT_EQ(printableLine(std::string("nul\0", 4)), "nul\\x00");
  EXPECT_EQ(printableLine("\xff\x80"), "\\xff\\x80");           // never a lead byte; a lone tail
  EXPECT_EQ(printableLine("\xc0\xaf"), "\\xc0\\xaf");           // overlong '/' (RFC 3629 sec. 10)
  EXPECT_EQ(printableLine("\xed\xa0\x80"), "\\xed\\xa0\\x80");  // a UTF-16 surrogate
  EXPECT_EQ(printableLine("\xf4\x90\x80\x80"), "\\xf4\\x90\\x80\\x80");  // above U+10FFFF
  EXPECT_EQ(printableLine("end \xe2\x82"), "end \\xe2\\x82");            // cut off at the end
}

TEST(InputError, NamesTheFileAndQuotesTheProblemPrintably) {
  EXPECT_STREQ(InputError("scene.glb", "last read: '\xff'").what(),
               "scene.glb: last read: '\\xff'");
  EXPECT_STREQ(InputError("", "two\nlines").what(), "two\\x0alines");
}

}  // namespace
}  // namespace photovr
