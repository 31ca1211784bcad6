#pragma once
/// @file
/// What the app prints reaches a terminal, and much of it quotes files: names, header tokens,
/// YAML values. Every message and report is passed through escape_control_characters
/// (core/text_escape.hpp) on its way out, so a crafted file cannot send escape sequences.

#include <cstddef>
#include <ostream>
#include <streambuf>
#include <string>

namespace scantling::app {

/// Installs the default spdlog logger: stderr (coloured), level warn (debug when `verbose`),
/// every message escaped (the line's final newline, added by the formatter, stays).
void set_up_logging(bool verbose);

/// A streambuf that forwards whole lines to `sink` with control characters other than '\n'
/// and '\t' and invalid UTF-8 escaped.
class EscapingBuffer final : public std::streambuf {
  public:
    explicit EscapingBuffer(std::streambuf* sink) : sink_(sink) {}
    EscapingBuffer(const EscapingBuffer&) = delete;
    EscapingBuffer& operator=(const EscapingBuffer&) = delete;
    ~EscapingBuffer() override { forward(pending_.size()); }
    std::streambuf* sink() const { return sink_; }

  protected:
    int_type overflow(int_type c) override;
    std::streamsize xsputn(const char* text, std::streamsize count) override;
    int sync() override;

  private:
    /// Escapes and writes the first `length` bytes held; false when the sink did not take them.
    bool forward(std::size_t length);
    std::streambuf* sink_;
    std::string pending_;  ///< bytes after the last newline forwarded
};

/// Routes `stream` through an EscapingBuffer until destroyed (then flushes and restores it).
class EscapedOutput {
  public:
    explicit EscapedOutput(std::ostream& stream) : stream_(stream), buffer_(stream.rdbuf()) {
        stream_.rdbuf(&buffer_);
    }
    EscapedOutput(const EscapedOutput&) = delete;
    EscapedOutput& operator=(const EscapedOutput&) = delete;
    ~EscapedOutput() {
        stream_.flush();
        stream_.rdbuf(buffer_.sink());
    }

  private:
    std::ostream& stream_;
    EscapingBuffer buffer_;
};

}  // namespace scantling::app
