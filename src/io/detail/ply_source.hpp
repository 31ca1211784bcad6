#pragma once
// Value sources for PLY bodies. Both expose the same interface so the element readers are
// written once as templates: begin_row(), scalar(type), end_row(), finish(), location().

#include <scantling/core/error.hpp>

#include <bit>
#include <string>
#include <vector>

#include "binary_scalar.hpp"
#include "ply_header.hpp"
#include "text_lines.hpp"

namespace scantling::io::detail {

/// Names the element and row being read, for error messages.
struct PlyRowContext {
    const PlyElement* element = nullptr;
    std::size_t row = 0;

    std::string describe() const {
        return element ? "element '" + element->name + "' row " + std::to_string(row) + " of " +
                             std::to_string(element->count)
                       : std::string("data");
    }
};

class BinaryPlySource {
  public:
    BinaryPlySource(const std::string& bytes, std::size_t start, std::endian order,
                    const std::string& path)
        : data_(reinterpret_cast<const unsigned char*>(bytes.data())),
          size_(bytes.size()),
          pos_(start),
          order_(order),
          path_(path) {}

    PlyRowContext context;

    void begin_row() {}
    void end_row() {}

    /// How many values of `type` the rest of the data can hold (bounds a list length).
    std::size_t max_items(ScalarType type) const { return (size_ - pos_) / scalar_size(type); }

    double scalar(ScalarType type) {
        const std::size_t n = scalar_size(type);
        if (size_ - pos_ < n) {
            throw ParseError(path_, location(),
                             "file ends inside " + context.describe() + ", expected " +
                                 std::to_string(n) +
                                 " more bytes (truncated file or counts in "
                                 "the header larger than the data)");
        }
        const double value = load_as_double(data_ + pos_, type, order_);
        pos_ += n;
        return value;
    }

    /// Bytes left after the last element mean the header's counts disagree with the data;
    /// trailing whitespace (a newline some writers add) is tolerated.
    void finish() const {
        for (std::size_t i = pos_; i < size_; ++i) {
            const unsigned char c = data_[i];
            if (c != '\n' && c != '\r' && c != ' ') {
                throw ParseError(path_, location(),
                                 std::to_string(size_ - pos_) +
                                     " bytes after the last element: the element counts in "
                                     "the header disagree with the data");
            }
        }
    }

    FileLocation location() const { return {pos_, std::nullopt, std::nullopt}; }

  private:
    const unsigned char* data_;
    std::size_t size_;
    std::size_t pos_;
    std::endian order_;
    const std::string& path_;
};

/// One row per line; tokens are taken one at a time (TokenCursor), so a hostile line of
/// millions of values costs no memory.
class AsciiPlySource {
  public:
    AsciiPlySource(const std::string& bytes, std::size_t start, int first_line,
                   const std::string& path)
        : reader_(bytes, start, first_line), path_(path) {
        line_.number = first_line - 1;
    }

    PlyRowContext context;

    void begin_row() {
        if (!next_non_empty()) fail("file ends before " + context.describe());
        cursor_ = TokenCursor(line_.text);
        taken_ = 0;
    }

    void end_row() {
        std::string_view extra;
        if (!cursor_.next(extra)) return;
        fail("found " + std::to_string(taken_ + 1 + count_tokens_left()) + " values for " +
             context.describe() + ", expected " + std::to_string(taken_));
    }

    /// How many more values the rest of the line can hold (bounds a list length).
    std::size_t max_items(ScalarType) const { return (cursor_.remaining_chars() + 1) / 2; }

    double scalar(ScalarType type) {
        std::string_view token;
        if (!cursor_.next(token)) {
            fail("too few values for " + context.describe() + ": found " + std::to_string(taken_));
        }
        ++taken_;
        const LineContext where{path_, line_};
        if (type == ScalarType::kF32) {
            // A float property holds the float nearest to the text, not the nearest double.
            return static_cast<float>(parse_double(token, where, NonFinite::kAllow));
        }
        if (type == ScalarType::kF64) return parse_double(token, where, NonFinite::kAllow);
        return parse_integer(token, type, where);
    }

    void finish() {
        if (next_non_empty())
            fail(
                "data after the last element: the element counts in the "
                "header disagree with the data");
    }

    FileLocation location() const { return {std::nullopt, line_.number, std::nullopt}; }

  private:
    bool next_non_empty() {
        while (reader_.next(line_)) {
            if (!trim(line_.text).empty()) return true;
        }
        return false;
    }

    std::size_t count_tokens_left() const {
        TokenCursor rest = cursor_;
        std::size_t n = 0;
        for (std::string_view token; rest.next(token);) ++n;
        return n;
    }

    /// An integer the declared type can hold ("uchar" with 300 is a lying header).
    static double parse_integer(std::string_view token, ScalarType type, const LineContext& where) {
        if (type == ScalarType::kU64) return static_cast<double>(parse_uint(token, where));
        const std::int64_t value = parse_int(token, where);
        if (!integer_fits(type, value)) {
            throw_bad_token(token, where,
                            std::string("a value that fits ") + scalar_type_name(type));
        }
        return static_cast<double>(value);
    }

    [[noreturn]] void fail(const std::string& what) const {
        throw ParseError(path_, location(), what);
    }

    LineReader reader_;
    TextLine line_;
    TokenCursor cursor_;
    std::size_t taken_ = 0;  // values taken from the current row
    const std::string& path_;
};

}  // namespace scantling::io::detail
