#pragma once
/// @file
/// An output file that keeps the OS reason of its first failure. std::ofstream only says
/// "failed": a full disk fails in the middle of the writes, and by the time the stream is
/// checked errno has long been overwritten (or reset), so a full disk was reported as a bare
/// "stream error". Here every write(2) and close(2) is checked where it happens.

#include <memory>
#include <ostream>
#include <string>
#include <system_error>

namespace scantling::io {

/// Writes `path` through a 64 KiB buffer. Open with the constructor, write to `stream()`,
/// then `close()` and check its result. The stream goes bad at the first failure (later
/// writes are dropped), and that failure's reason is what `error()` and `close()` return.
/// Not thread-safe. No fsync: the data reaches the OS, not necessarily the disk.
class CheckedOutputFile {
  public:
    /// Opens `path` for writing (created with mode 0666 & ~umask). With `exclusive` the file
    /// must not exist yet (O_EXCL); otherwise an existing file is truncated. A failure to
    /// open is reported by `error()` (the stream is then bad).
    CheckedOutputFile(const std::string& path, bool exclusive);
    /// Closes without reporting (use `close()` to learn whether everything was written).
    ~CheckedOutputFile();

    CheckedOutputFile(const CheckedOutputFile&) = delete;
    CheckedOutputFile& operator=(const CheckedOutputFile&) = delete;
    CheckedOutputFile(CheckedOutputFile&&) = delete;
    CheckedOutputFile& operator=(CheckedOutputFile&&) = delete;

    std::ostream& stream() { return stream_; }

    /// Flushes and closes (once; later calls return the same result). Returns the first error
    /// of open, write, flush or close, e.g. std::errc::no_space_on_device, or {} when every
    /// byte written to the stream reached the file.
    std::error_code close();

    /// The first error so far ({} when none).
    std::error_code error() const;

    const std::string& path() const { return path_; }

  private:
    class Buffer;
    std::string path_;
    std::unique_ptr<Buffer> buffer_;
    std::ostream stream_;
};

}  // namespace scantling::io
