#pragma once
// Shared helpers for line-based text formats (PCD/PLY headers and ascii bodies, KITTI poses,
// TUM trajectories): whole-file reads, line iteration with line numbers, strict number parsing.

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace scantling::io::detail {

/// The whole file as bytes. Throws FileError for a missing file, a directory or a read error.
std::string read_whole_file(const std::string& path);

/// One line of a text buffer, without its terminator ("\n" or "\r\n").
struct TextLine {
    std::string_view text;
    int number = 0;          ///< 1-based
    std::size_t offset = 0;  ///< byte offset of the line's first character
};

/// Iterates over the lines of `text`, starting at byte `start` (line number `first_line`).
class LineReader {
  public:
    explicit LineReader(std::string_view text, std::size_t start = 0, int first_line = 1)
        : text_(text), pos_(start), next_number_(first_line) {}

    /// Next line into `line`; false at the end of the text.
    bool next(TextLine& line);
    /// Byte offset just after the last line returned (start of the next one).
    std::size_t position() const { return pos_; }

  private:
    std::string_view text_;
    std::size_t pos_;
    int next_number_;
};

/// Where a token came from, for error messages ("<path>: line 3, column 7: ...").
struct LineContext {
    const std::string& path;
    const TextLine& line;
};

std::string_view trim(std::string_view text);

/// The whitespace-separated tokens of one line, one at a time and without storing them: a line
/// of a hostile file may hold millions of tokens, and a vector of views costs 16 bytes each.
class TokenCursor {
  public:
    explicit TokenCursor(std::string_view text = {}) : text_(text) {}

    /// Next token into `token`; false when the line holds no more.
    bool next(std::string_view& token);
    /// Characters not yet consumed; k more tokens need at least 2k - 1 of them.
    std::size_t remaining_chars() const { return text_.size() - pos_; }

  private:
    std::string_view text_;
    std::size_t pos_ = 0;
};

/// Number of whitespace-separated tokens in `text` (no allocation).
std::size_t count_tokens(std::string_view text);

/// Whitespace-separated tokens (spaces, tabs, '\r').
std::vector<std::string_view> split_tokens(std::string_view text);
/// Same, into a reused vector (no allocation once it has grown).
void split_tokens(std::string_view text, std::vector<std::string_view>& tokens);
/// Exactly `expected` tokens of `text` into `tokens`; a line holding another number is refused
/// (expect_token_count) before anything is stored, so an absurdly long line costs no memory.
void split_exactly(std::string_view text, std::vector<std::string_view>& tokens,
                   std::size_t expected, const LineContext& where, std::string_view what);

/// `text` up to the first `marker` (comments), trimmed.
std::string_view strip_comment(std::string_view text, char marker = '#');

enum class NonFinite { kReject, kAllow };

/// The whole token as a double (std::from_chars; an optional leading '+' is accepted).
/// Throws ParseError naming file, line, column and the token for "1.0abc", "", "0x1p3" or,
/// with NonFinite::kReject, "nan"/"inf".
double parse_double(std::string_view token, const LineContext& where,
                    NonFinite non_finite = NonFinite::kReject);
std::int64_t parse_int(std::string_view token, const LineContext& where);
std::uint64_t parse_uint(std::string_view token, const LineContext& where);

/// Throws ParseError naming file, line, column and the token: "invalid token '<token>',
/// expected <expected>".
[[noreturn]] void throw_bad_token(std::string_view token, const LineContext& where,
                                  std::string_view expected);

/// Throws ParseError at `where` unless `found` (the number of tokens) equals `expected`.
void expect_token_count(std::size_t found, std::size_t expected, const LineContext& where,
                        std::string_view what);
void expect_token_count(const std::vector<std::string_view>& tokens, std::size_t expected,
                        const LineContext& where, std::string_view what);

/// Shortest text that parses back to exactly `value` (std::to_chars), appended to `out`.
void append_number(std::string& out, double value);
void append_number(std::string& out, float value);

}  // namespace scantling::io::detail
