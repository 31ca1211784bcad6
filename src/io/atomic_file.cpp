#include <scantling/core/error.hpp>
#include <scantling/io/atomic_file.hpp>

#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <filesystem>
#include <system_error>

namespace scantling::io {
namespace {

std::string os_reason(int error_number) {
    return std::error_code(error_number, std::generic_category()).message();
}

// pid + process-wide counter: unique across processes and across writers in this process.
std::string make_temporary_path(const std::string& path) {
    static std::atomic<std::uint64_t> counter{0};
    return path + ".tmp-" + std::to_string(::getpid()) + "-" + std::to_string(counter++);
}

void remove_quietly(const std::string& path) {
    std::error_code ignored;
    std::filesystem::remove(path, ignored);
}

}  // namespace

AtomicFileWriter::AtomicFileWriter(std::string path)
    : path_(std::move(path)), temporary_path_(make_temporary_path(path_)) {
    if (std::filesystem::is_directory(path_)) {
        throw FileError(path_, "cannot write: the path is a directory");
    }
    errno = 0;
    out_.open(temporary_path_, std::ios::binary | std::ios::trunc);
    if (!out_) {
        const int error_number = errno;
        remove_quietly(temporary_path_);
        throw FileError(path_, "cannot create temporary file " + temporary_path_ + ": " +
                                   (error_number ? os_reason(error_number) : "unknown error"));
    }
}

AtomicFileWriter::~AtomicFileWriter() {
    if (committed_) return;
    out_.close();
    remove_quietly(temporary_path_);
}

void AtomicFileWriter::commit() {
    if (committed_) throw FileError(path_, "commit() called twice");
    errno = 0;
    out_.flush();
    const bool write_ok = static_cast<bool>(out_);
    const int error_number = errno;
    out_.close();
    if (!write_ok || out_.fail()) {
        remove_quietly(temporary_path_);
        throw FileError(
            path_, "write failed: " + (error_number ? os_reason(error_number) : "stream error"));
    }
    std::error_code ec;
    std::filesystem::rename(temporary_path_, path_, ec);
    if (ec) {
        remove_quietly(temporary_path_);
        throw FileError(path_, "cannot rename " + temporary_path_ + " over it: " + ec.message());
    }
    committed_ = true;
}

void write_file_atomically(const std::string& path,
                           const std::function<void(std::ostream&)>& write) {
    AtomicFileWriter writer(path);
    write(writer.stream());
    writer.commit();
}

}  // namespace scantling::io
