#pragma once
/// @file
/// Escaping of text that came from files (names, header tokens, YAML values) before it reaches
/// a terminal: a crafted file must not be able to clear the screen, retitle the window or move
/// the cursor through an error message, a warning or a report.

#include <string>
#include <string_view>

namespace scantling {

/// `text` with every byte a terminal could act on replaced by a visible `\xHH` escape (HH the
/// byte in lower-case hex): the C0 controls (0x00–0x1F) except those listed in `keep`, DEL
/// (0x7F), the C1 controls U+0080–U+009F (UTF-8 `\xc2\x80`–`\xc2\x9f`, the 8-bit CSI among
/// them) and every byte that is not part of a valid UTF-8 sequence (a lone 0x9B is a CSI to an
/// 8-bit terminal). Valid UTF-8 text, including multi-byte characters such as "m²", is
/// returned unchanged; so is the backslash (the escape is for display, not for parsing back).
/// Pure, O(n), thread-safe.
std::string escape_control_characters(std::string_view text, std::string_view keep = {});

}  // namespace scantling
