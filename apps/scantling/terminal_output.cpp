// Escaped terminal output of the app (terminal_output.hpp).
#include "scantling/terminal_output.hpp"

#include <spdlog/sinks/sink.h>
#include <spdlog/sinks/stdout_color_sinks.h>
#include <spdlog/spdlog.h>

#include <memory>
#include <string_view>
#include <utility>

#include <scantling/core/text_escape.hpp>

namespace scantling::app {
namespace {

/// Passes each message to `inner` with its text escaped. The formatter of `inner` adds the
/// level, the logger name and the newline after this, so those are not escaped.
class EscapingSink final : public spdlog::sinks::sink {
  public:
    explicit EscapingSink(spdlog::sink_ptr inner) : inner_(std::move(inner)) {}
    void log(const spdlog::details::log_msg& msg) override {
        const std::string text =
            escape_control_characters(std::string_view(msg.payload.data(), msg.payload.size()));
        spdlog::details::log_msg escaped = msg;
        escaped.payload = spdlog::string_view_t(text.data(), text.size());
        inner_->log(escaped);
    }
    void flush() override { inner_->flush(); }
    void set_pattern(const std::string& pattern) override { inner_->set_pattern(pattern); }
    void set_formatter(std::unique_ptr<spdlog::formatter> formatter) override {
        inner_->set_formatter(std::move(formatter));
    }

  private:
    spdlog::sink_ptr inner_;
};

}  // namespace

void set_up_logging(bool verbose) {
    // Libraries never print; the app logs to stderr so that stdout stays the report.
    auto sink =
        std::make_shared<EscapingSink>(std::make_shared<spdlog::sinks::stderr_color_sink_mt>());
    auto logger = std::make_shared<spdlog::logger>("scantling", std::move(sink));
    logger->set_level(verbose ? spdlog::level::debug : spdlog::level::warn);
    spdlog::set_default_logger(std::move(logger));
}

EscapingBuffer::int_type EscapingBuffer::overflow(int_type c) {
    if (traits_type::eq_int_type(c, traits_type::eof())) return traits_type::not_eof(c);
    const char byte = traits_type::to_char_type(c);
    return xsputn(&byte, 1) == 1 ? c : traits_type::eof();
}

std::streamsize EscapingBuffer::xsputn(const char* text, std::streamsize count) {
    pending_.append(text, static_cast<std::size_t>(count));
    // Up to the last newline: a multi-byte character written in pieces is not split.
    const std::size_t last_newline = pending_.rfind('\n');
    if (last_newline != std::string::npos && !forward(last_newline + 1)) return 0;
    return count;
}

int EscapingBuffer::sync() { return forward(pending_.size()) && sink_->pubsync() == 0 ? 0 : -1; }

bool EscapingBuffer::forward(std::size_t length) {
    const std::string text =
        escape_control_characters(std::string_view(pending_).substr(0, length), "\n\t");
    pending_.erase(0, length);
    const auto size = static_cast<std::streamsize>(text.size());
    return sink_->sputn(text.data(), size) == size;
}

}  // namespace scantling::app
