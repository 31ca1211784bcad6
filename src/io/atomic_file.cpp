#include <scantling/core/error.hpp>
#include <scantling/io/atomic_file.hpp>
#include <scantling/io/file_path.hpp>

#include <filesystem>
#include <system_error>

namespace scantling::io {
namespace {

// A temporary left by a killed process whose pid was reused is skipped, not overwritten.
constexpr int kCreateAttempts = 16;

void remove_quietly(const std::string& path) {
    std::error_code ignored;
    std::filesystem::remove(path, ignored);
}

}  // namespace

AtomicFileWriter::AtomicFileWriter(std::string path) : path_(std::move(path)) {
    std::error_code ec;
    if (std::filesystem::is_directory(path_, ec)) {
        throw FileError(path_, "cannot write: the path is a directory");
    }
    for (int attempt = 0; attempt < kCreateAttempts; ++attempt) {
        temporary_path_ = temporary_sibling(path_, "tmp");
        out_ = std::make_unique<CheckedOutputFile>(temporary_path_, /*exclusive=*/true);
        if (out_->error() != std::errc::file_exists) break;
    }
    if (const std::error_code error = out_->error()) {
        out_.reset();
        throw FileError(path_,
                        "cannot create temporary file " + temporary_path_ + ": " + error.message());
    }
}

AtomicFileWriter::~AtomicFileWriter() {
    if (finished_) return;
    out_->close();
    remove_quietly(temporary_path_);
}

void AtomicFileWriter::commit() {
    if (finished_) throw FileError(path_, "commit() called twice");
    const bool stream_ok = static_cast<bool>(out_->stream());
    const std::error_code error = out_->close();
    if (error || !stream_ok) {
        remove_quietly(temporary_path_);
        finished_ = true;  // the temporary is gone: nothing left for the destructor
        throw FileError(path_,
                        "write failed: " + (error ? error.message() : std::string("stream error")));
    }
    std::error_code ec;
    std::filesystem::rename(temporary_path_, path_, ec);
    if (ec) {
        remove_quietly(temporary_path_);
        finished_ = true;
        throw FileError(path_, "cannot rename " + temporary_path_ + " over it: " + ec.message());
    }
    finished_ = true;
}

void write_file_atomically(const std::string& path,
                           const std::function<void(std::ostream&)>& write) {
    AtomicFileWriter writer(path);
    write(writer.stream());
    writer.commit();
}

}  // namespace scantling::io
