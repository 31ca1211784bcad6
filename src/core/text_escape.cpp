#include <scantling/core/text_escape.hpp>

#include <cstddef>

namespace scantling {
namespace {

void append_hex_escape(std::string& out, unsigned char byte) {
    constexpr char kDigits[] = "0123456789abcdef";
    out += "\\x";
    out += kDigits[byte >> 4];
    out += kDigits[byte & 0x0F];
}

bool is_continuation(unsigned char byte) { return (byte & 0xC0) == 0x80; }

/// Length of the valid UTF-8 sequence of two or more bytes starting at `text[i]`, or 0 when
/// the bytes there are not one (RFC 3629: no overlong forms, no surrogates, at most U+10FFFF).
std::size_t utf8_sequence_length(std::string_view text, std::size_t i) {
    const auto at = [&](std::size_t k) { return static_cast<unsigned char>(text[i + k]); };
    const unsigned char lead = at(0);
    std::size_t length = 0;
    unsigned char second_min = 0x80, second_max = 0xBF;
    if (lead >= 0xC2 && lead <= 0xDF) {
        length = 2;
    } else if (lead >= 0xE0 && lead <= 0xEF) {
        length = 3;
        if (lead == 0xE0) second_min = 0xA0;  // overlong
        if (lead == 0xED) second_max = 0x9F;  // surrogates
    } else if (lead >= 0xF0 && lead <= 0xF4) {
        length = 4;
        if (lead == 0xF0) second_min = 0x90;  // overlong
        if (lead == 0xF4) second_max = 0x8F;  // above U+10FFFF
    } else {
        return 0;
    }
    if (text.size() - i < length || at(1) < second_min || at(1) > second_max) return 0;
    for (std::size_t k = 2; k < length; ++k) {
        if (!is_continuation(at(k))) return 0;
    }
    return length;
}

/// U+0080–U+009F: the C1 controls, encoded as 0xC2 0x80–0x9F.
bool is_c1_control(std::string_view sequence) {
    return sequence.size() == 2 && static_cast<unsigned char>(sequence[0]) == 0xC2 &&
           static_cast<unsigned char>(sequence[1]) <= 0x9F;
}

bool is_ascii_control(unsigned char byte, std::string_view keep) {
    return (byte < 0x20 || byte == 0x7F) && keep.find(static_cast<char>(byte)) == keep.npos;
}

/// Appends the character starting at `text[i]`, escaped when a terminal could act on it;
/// returns its length in bytes.
std::size_t append_character(std::string& out, std::string_view text, std::size_t i,
                             std::string_view keep) {
    const auto byte = static_cast<unsigned char>(text[i]);
    if (byte < 0x80) {
        if (is_ascii_control(byte, keep)) {
            append_hex_escape(out, byte);
        } else {
            out += static_cast<char>(byte);
        }
        return 1;
    }
    const std::size_t length = utf8_sequence_length(text, i);
    if (length == 0) {  // not UTF-8: the byte alone
        append_hex_escape(out, byte);
        return 1;
    }
    const std::string_view sequence = text.substr(i, length);
    if (is_c1_control(sequence)) {
        for (const char c : sequence) append_hex_escape(out, static_cast<unsigned char>(c));
    } else {
        out += sequence;
    }
    return length;
}

}  // namespace

std::string escape_control_characters(std::string_view text, std::string_view keep) {
    std::string out;
    out.reserve(text.size());
    for (std::size_t i = 0; i < text.size();) i += append_character(out, text, i, keep);
    return out;
}

}  // namespace scantling
