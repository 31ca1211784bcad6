#include <scantling/io/checked_output_file.hpp>

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <streambuf>
#include <vector>

namespace scantling::io {
namespace {

constexpr std::size_t kBufferBytes = 64 * 1024;

}  // namespace

/// A streambuf over a POSIX file descriptor that records the errno of the first failing call.
class CheckedOutputFile::Buffer : public std::streambuf {
  public:
    Buffer(const std::string& path, bool exclusive) : storage_(kBufferBytes) {
        const int flags = O_WRONLY | O_CREAT | O_CLOEXEC | (exclusive ? O_EXCL : O_TRUNC);
        fd_ = ::open(path.c_str(), flags, 0666);
        if (fd_ < 0) record(errno);
        reset_put_area();
    }
    ~Buffer() override {
        if (fd_ >= 0) ::close(fd_);
    }
    Buffer(const Buffer&) = delete;
    Buffer& operator=(const Buffer&) = delete;

    std::error_code close() {
        if (fd_ < 0) return error_;
        drain();
        if (::close(fd_) != 0) record(errno);  // NFS and quotas may report only here
        fd_ = -1;
        return error_;
    }
    std::error_code error() const { return error_; }

  protected:
    int_type overflow(int_type c) override {
        if (!drain()) return traits_type::eof();
        if (!traits_type::eq_int_type(c, traits_type::eof())) {
            *pptr() = traits_type::to_char_type(c);
            pbump(1);
        }
        return traits_type::not_eof(c);
    }

    std::streamsize xsputn(const char* data, std::streamsize count) override {
        // Blocks larger than the buffer go straight to the file instead of through it.
        if (count < static_cast<std::streamsize>(kBufferBytes)) {
            return std::streambuf::xsputn(data, count);
        }
        if (!drain() || !write_all(data, static_cast<std::size_t>(count))) return 0;
        return count;
    }

    int sync() override { return drain() ? 0 : -1; }

  private:
    void reset_put_area() { setp(storage_.data(), storage_.data() + storage_.size()); }

    bool drain() {
        const bool ok = write_all(pbase(), static_cast<std::size_t>(pptr() - pbase()));
        reset_put_area();
        return ok;
    }

    bool write_all(const char* data, std::size_t count) {
        if (error_) return false;  // the first failure is the one reported; drop the rest
        if (count > 0 && fd_ < 0) return record(EBADF);
        while (count > 0) {
            const ssize_t written = ::write(fd_, data, count);
            if (written < 0 && errno == EINTR) continue;
            if (written < 0) return record(errno);
            if (written == 0) return record(EIO);  // no progress: would loop forever
            data += written;
            count -= static_cast<std::size_t>(written);
        }
        return true;
    }

    bool record(int error_number) {
        if (!error_) error_ = std::error_code(error_number, std::generic_category());
        return false;
    }

    std::vector<char> storage_;
    int fd_ = -1;
    std::error_code error_;
};

CheckedOutputFile::CheckedOutputFile(const std::string& path, bool exclusive)
    : path_(path), buffer_(std::make_unique<Buffer>(path, exclusive)), stream_(buffer_.get()) {
    if (buffer_->error()) stream_.setstate(std::ios::badbit);
}

CheckedOutputFile::~CheckedOutputFile() = default;

std::error_code CheckedOutputFile::close() {
    stream_.flush();
    return buffer_->close();
}

std::error_code CheckedOutputFile::error() const { return buffer_->error(); }

}  // namespace scantling::io
