#include "detail/text_lines.hpp"

#include <scantling/core/error.hpp>

#include <cerrno>
#include <charconv>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <system_error>

namespace scantling::io::detail {
namespace {

bool is_space(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\v' || c == '\f'; }

FileLocation location_of(std::string_view token, const LineContext& where) {
    const auto column = token.data() - where.line.text.data();
    const bool inside = column >= 0 && static_cast<std::size_t>(column) <= where.line.text.size();
    return {std::nullopt, where.line.number,
            inside ? std::optional<int>(static_cast<int>(column) + 1) : std::nullopt};
}

std::string_view without_plus(std::string_view token) {
    if (token.size() > 1 && token[0] == '+' && token[1] != '-' && token[1] != '+') {
        return token.substr(1);
    }
    return token;
}

template <typename Int>
Int parse_integer(std::string_view token, const LineContext& where, std::string_view expected) {
    const std::string_view digits = without_plus(token);
    Int value{};
    const auto [end, ec] = std::from_chars(digits.data(), digits.data() + digits.size(), value);
    if (ec != std::errc() || end != digits.data() + digits.size() || digits.empty()) {
        throw_bad_token(token, where, expected);
    }
    return value;
}

}  // namespace

void throw_bad_token(std::string_view token, const LineContext& where, std::string_view expected) {
    throw ParseError(
        where.path, location_of(token, where),
        "invalid token '" + std::string(token) + "', expected " + std::string(expected));
}

std::string read_whole_file(const std::string& path) {
    std::error_code ec;
    if (std::filesystem::is_directory(path, ec)) {
        throw FileError(path, "cannot read: the path is a directory");
    }
    errno = 0;
    std::ifstream in(path, std::ios::binary);
    if (!in) {
        const int error_number = errno ? errno : ENOENT;
        throw FileError(path, "cannot open for reading: " +
                                  std::error_code(error_number, std::generic_category()).message());
    }
    in.seekg(0, std::ios::end);
    const auto size = in.tellg();
    in.seekg(0, std::ios::beg);
    std::string bytes(size > 0 ? static_cast<std::size_t>(size) : 0, '\0');
    if (size < 0 || !in.read(bytes.data(), static_cast<std::streamsize>(bytes.size()))) {
        throw FileError(path, "read error");
    }
    return bytes;
}

bool LineReader::next(TextLine& line) {
    if (pos_ >= text_.size()) return false;
    const std::size_t end = text_.find('\n', pos_);
    const std::size_t stop = end == std::string_view::npos ? text_.size() : end;
    std::string_view text = text_.substr(pos_, stop - pos_);
    if (!text.empty() && text.back() == '\r') text.remove_suffix(1);
    line = {text, next_number_++, pos_};
    pos_ = end == std::string_view::npos ? text_.size() : end + 1;
    return true;
}

std::string_view trim(std::string_view text) {
    while (!text.empty() && is_space(text.front())) text.remove_prefix(1);
    while (!text.empty() && is_space(text.back())) text.remove_suffix(1);
    return text;
}

bool TokenCursor::next(std::string_view& token) {
    while (pos_ < text_.size() && is_space(text_[pos_])) ++pos_;
    const std::size_t start = pos_;
    while (pos_ < text_.size() && !is_space(text_[pos_])) ++pos_;
    token = text_.substr(start, pos_ - start);
    return pos_ > start;
}

std::size_t count_tokens(std::string_view text) {
    TokenCursor cursor(text);
    std::size_t count = 0;
    for (std::string_view token; cursor.next(token);) ++count;
    return count;
}

void split_tokens(std::string_view text, std::vector<std::string_view>& tokens) {
    tokens.clear();
    TokenCursor cursor(text);
    for (std::string_view token; cursor.next(token);) tokens.push_back(token);
}

void split_exactly(std::string_view text, std::vector<std::string_view>& tokens,
                   std::size_t expected, const LineContext& where, std::string_view what) {
    expect_token_count(count_tokens(text), expected, where, what);
    split_tokens(text, tokens);
}

std::vector<std::string_view> split_tokens(std::string_view text) {
    std::vector<std::string_view> tokens;
    split_tokens(text, tokens);
    return tokens;
}

std::string_view strip_comment(std::string_view text, char marker) {
    return trim(text.substr(0, text.find(marker)));
}

double parse_double(std::string_view token, const LineContext& where, NonFinite non_finite) {
    const std::string_view digits = without_plus(token);
    double value = 0.0;
    const auto [end, ec] = std::from_chars(digits.data(), digits.data() + digits.size(), value);
    const bool complete = ec == std::errc() && end == digits.data() + digits.size();
    if (!complete || digits.empty()) throw_bad_token(token, where, "a decimal number");
    if (non_finite == NonFinite::kReject && !std::isfinite(value)) {
        throw_bad_token(token, where, "a finite number");
    }
    return value;
}

std::int64_t parse_int(std::string_view token, const LineContext& where) {
    return parse_integer<std::int64_t>(token, where, "an integer");
}

std::uint64_t parse_uint(std::string_view token, const LineContext& where) {
    return parse_integer<std::uint64_t>(token, where, "a non-negative integer");
}

void expect_token_count(std::size_t found, std::size_t expected, const LineContext& where,
                        std::string_view what) {
    if (found == expected) return;
    throw ParseError(where.path, {std::nullopt, where.line.number, std::nullopt},
                     "found " + std::to_string(found) + " values, expected " +
                         std::to_string(expected) + " (" + std::string(what) + ")");
}

void expect_token_count(const std::vector<std::string_view>& tokens, std::size_t expected,
                        const LineContext& where, std::string_view what) {
    expect_token_count(tokens.size(), expected, where, what);
}

void append_number(std::string& out, double value) {
    char buffer[64];
    const auto result = std::to_chars(buffer, buffer + sizeof(buffer), value);
    out.append(buffer, result.ptr);
}

void append_number(std::string& out, float value) {
    char buffer[64];
    const auto result = std::to_chars(buffer, buffer + sizeof(buffer), value);
    out.append(buffer, result.ptr);
}

}  // namespace scantling::io::detail
