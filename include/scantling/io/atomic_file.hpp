#pragma once
/// @file
/// Crash-safe file output: data goes to a temporary file in the target's directory, which is
/// renamed over the target only once everything was written. Readers therefore see either the
/// old file or the complete new one, never a partial write.

#include <functional>
#include <memory>
#include <ostream>
#include <string>

#include <scantling/io/checked_output_file.hpp>

namespace scantling::io {

/// Writes `path` atomically. Open with the constructor, write to `stream()`, then `commit()`.
/// Without a successful `commit()` (exception, early return) the destructor removes the
/// temporary and `path` is untouched.
///
/// The temporary is "<path>.tmp-<pid>-<counter>" (temporary_sibling: same directory, so the
/// rename stays on one file system and is atomic on POSIX; a name too long for NAME_MAX is
/// shortened with a hash). It is created exclusively (O_EXCL), so distinct writers (even for the
/// same path, even in other processes) never share a temporary. Not thread-safe: one writer per
/// thread. Every write is checked where it happens (CheckedOutputFile), so a full disk is
/// reported with its OS reason ("No space left on device").
/// @note No fsync: atomic with respect to readers and to a crash of this process, not to a
/// power loss (the renamed file may then be empty on some file systems).
class AtomicFileWriter {
  public:
    /// Creates the temporary. Throws FileError naming `path` and the OS reason (missing or
    /// unwritable directory, `path` is a directory, ...).
    explicit AtomicFileWriter(std::string path);
    ~AtomicFileWriter();

    AtomicFileWriter(const AtomicFileWriter&) = delete;
    AtomicFileWriter& operator=(const AtomicFileWriter&) = delete;
    AtomicFileWriter(AtomicFileWriter&&) = delete;
    AtomicFileWriter& operator=(AtomicFileWriter&&) = delete;

    /// The stream to write to (the temporary file).
    std::ostream& stream() { return out_->stream(); }

    /// Flushes, checks every write and the close, and renames the temporary over `path`.
    /// Throws FileError naming `path` and the OS reason ("write failed: No space left on
    /// device", ...); the temporary is removed in that case too. Call at most once.
    void commit();

    const std::string& path() const { return path_; }
    const std::string& temporary_path() const { return temporary_path_; }

  private:
    std::string path_;
    std::string temporary_path_;
    std::unique_ptr<CheckedOutputFile> out_;
    bool finished_ = false;
};

/// Convenience: opens an AtomicFileWriter for `path`, calls `write(stream)` and commits.
/// If `write` throws, nothing is left behind and the exception propagates unchanged.
void write_file_atomically(const std::string& path,
                           const std::function<void(std::ostream&)>& write);

}  // namespace scantling::io
