// escape_control_characters: nothing a terminal acts on survives; valid UTF-8 text does.
#include <scantling/core/text_escape.hpp>

#include <gtest/gtest.h>

#include <string>

namespace scantling {
namespace {

TEST(TextEscape, PrintableAsciiAndUtf8PassUnchanged) {
    EXPECT_EQ(escape_control_characters("cloud.pcd: line 3: expected 4 numbers"),
              "cloud.pcd: line 3: expected 4 numbers");
    EXPECT_EQ(escape_control_characters("m² and rad², 90°, Überlauf, ✓, 😀"),
              "m² and rad², 90°, Überlauf, ✓, 😀");
    EXPECT_EQ(escape_control_characters("C:\\path\\x1b"), "C:\\path\\x1b");  // text, not a byte
    EXPECT_EQ(escape_control_characters(""), "");
}

TEST(TextEscape, TerminalEscapeSequencesLoseTheirEscapeByte) {
    EXPECT_EQ(escape_control_characters("FIELDS x y z \x1b[2J"), "FIELDS x y z \\x1b[2J");
    EXPECT_EQ(escape_control_characters("a\x1b]0;title\x07.pcd"), "a\\x1b]0;title\\x07.pcd");
    EXPECT_EQ(escape_control_characters("del\x7f"), "del\\x7f");
}

TEST(TextEscape, EveryC0ControlIsEscapedUnlessKept) {
    for (int c = 0; c < 0x20; ++c) {
        const std::string text(1, static_cast<char>(c));
        const std::string escaped = escape_control_characters(text);
        EXPECT_EQ(escaped.size(), 4u) << c;
        EXPECT_EQ(escaped.rfind("\\x", 0), 0u) << c;
    }
    EXPECT_EQ(escape_control_characters("a\nb\tc\r", "\n\t"), "a\nb\tc\\x0d");
    EXPECT_EQ(escape_control_characters(std::string("nul\0byte", 8)), "nul\\x00byte");
}

TEST(TextEscape, C1ControlsAndInvalidUtf8AreEscapedBytewise) {
    EXPECT_EQ(escape_control_characters("\xc2\x9b"
                                        "2J"),
              "\\xc2\\x9b2J");  // UTF-8 encoded CSI
    EXPECT_EQ(escape_control_characters("\x9b"
                                        "2J"),
              "\\x9b2J");                                          // 8-bit CSI
    EXPECT_EQ(escape_control_characters("\xc2\xa0"), "\xc2\xa0");  // U+00A0 is printable
    EXPECT_EQ(escape_control_characters("\xff\xfe"), "\\xff\\xfe");
    EXPECT_EQ(escape_control_characters("\xc0\xaf"), "\\xc0\\xaf");           // overlong '/'
    EXPECT_EQ(escape_control_characters("\xed\xa0\x80"), "\\xed\\xa0\\x80");  // surrogate
    EXPECT_EQ(escape_control_characters("\xf4\x90\x80\x80"), "\\xf4\\x90\\x80\\x80");
    EXPECT_EQ(escape_control_characters("\xe2\x9c"), "\\xe2\\x9c");  // truncated sequence
}

}  // namespace
}  // namespace scantling
