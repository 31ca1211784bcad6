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

/// Rejects absurd row counts (more rows than bytes left) before anything is allocated;
/// ordinary truncation is reported where the data actually ends.
inline void check_rows_fit(const PlyElement& element, std::size_t remaining,
                           const std::string& path, const FileLocation& where) {
    if (element.count <= remaining || element.properties.empty()) return;
    throw ParseError(path, where,
                     "element '" + element.name + "' declares " + std::to_string(element.count) +
                         " rows, but only " + std::to_string(remaining) +
                         " bytes follow the header (truncated file or wrong count)");
}

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

    void check_room(const PlyElement& element) const {
        check_rows_fit(element, size_ - pos_, path_, location());
    }

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

class AsciiPlySource {
  public:
    AsciiPlySource(const std::string& bytes, std::size_t start, int first_line,
                   const std::string& path)
        : reader_(bytes, start, first_line), remaining_(bytes.size() - start), path_(path) {
        line_.number = first_line - 1;
    }

    PlyRowContext context;

    void check_room(const PlyElement& element) const {
        check_rows_fit(element, remaining_, path_, location());
    }

    void begin_row() {
        if (!next_non_empty()) fail("file ends before " + context.describe());
        split_tokens(line_.text, tokens_);
        next_ = 0;
    }

    void end_row() {
        if (next_ < tokens_.size()) {
            fail("found " + std::to_string(tokens_.size()) + " values for " + context.describe() +
                 ", expected " + std::to_string(next_));
        }
    }

    double scalar(ScalarType type) {
        if (next_ >= tokens_.size()) {
            fail("too few values for " + context.describe() + ": found " +
                 std::to_string(tokens_.size()));
        }
        const std::string_view token = tokens_[next_++];
        const LineContext where{path_, line_};
        if (type == ScalarType::kF32) {
            // A float property holds the float nearest to the text, not the nearest double.
            return static_cast<float>(parse_double(token, where, NonFinite::kAllow));
        }
        if (type == ScalarType::kF64) return parse_double(token, where, NonFinite::kAllow);
        return static_cast<double>(parse_int(token, where));
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

    [[noreturn]] void fail(const std::string& what) const {
        throw ParseError(path_, location(), what);
    }

    LineReader reader_;
    TextLine line_;
    std::vector<std::string_view> tokens_;
    std::size_t next_ = 0;
    std::size_t remaining_;  // bytes after the header; bounds the plausible row counts
    const std::string& path_;
};

}  // namespace scantling::io::detail
