// sl::printable: what every error line echoes of user input (file names, keys, values) is one line and cannot
// drive the terminal (bad-input probe S28-S30), while well-formed non-ASCII names stay readable.
#include "core/Error.h"

#include <gtest/gtest.h>

namespace sl
{
namespace
{

TEST(Printable, EscapesControlCharactersAndKeepsPlainText)
{
  EXPECT_EQ(printable("scene.json"), "scene.json");
  EXPECT_EQ(printable("a\nb\rc\td"), "a\\nb\\rc\\td");
  EXPECT_EQ(printable("\x1b[31mred\x1b[0m"), "\\x1b[31mred\\x1b[0m");
  EXPECT_EQ(printable(std::string("nul\0byte", 8)), "nul\\x00byte");
  EXPECT_EQ(printable("del\x7f"), "del\\x7f");
}

TEST(Printable, KeepsWellFormedUtf8AndEscapesEverythingElse)
{
  EXPECT_EQ(printable("sc\xc3\xa8ne-\xe5\x9c\xba\xe6\x99\xaf-\xf0\x9f\x8c\x92.json"), "sc\xc3\xa8ne-\xe5\x9c\xba\xe6\x99\xaf-\xf0\x9f\x8c\x92.json");
  EXPECT_EQ(printable("\xff\xfe"), "\\xff\\xfe");                 // not UTF-8 at all
  EXPECT_EQ(printable("\xc3"), "\\xc3");                          // cut short
  EXPECT_EQ(printable("\xc0\xaf"), "\\xc0\\xaf");                 // overlong '/'
  EXPECT_EQ(printable("\xed\xa0\x80"), "\\xed\\xa0\\x80");         // a UTF-16 surrogate
  EXPECT_EQ(printable("\xc2\x9b" "31m"), "\\xc2\\x9b31m");         // C1 CSI: an escape for some terminals
  EXPECT_EQ(printable("\xc2\xa0"), "\xc2\xa0");                   // U+00A0 is printable
}

} // namespace
} // namespace sl
