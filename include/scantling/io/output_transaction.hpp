#pragma once
/// @file
/// All the outputs of a command, or none: each output is written to a temporary beside its
/// destination (temporary_sibling), and only `commit()`, once everything was written, moves
/// them into place. A failure on the second of three files (disk full, a bad folder, an
/// exception while computing the third) therefore leaves none of them, and earlier files of
/// the same names are untouched.
///
/// Limits: the moves of `commit()` are renames in one folder each (atomic one by one, not as a
/// set); a process killed during them (microseconds, after all the writing) can leave some
/// outputs moved. Replaced outputs are kept as "<name>.old-<pid>-<n>" until every move
/// succeeded, so a failing move rolls the earlier ones back. No fsync (see atomic_file.hpp).

#include <cstddef>
#include <functional>
#include <ostream>
#include <string>
#include <vector>

namespace scantling::io {

class OutputTransaction {
  public:
    /// Decides whether an existing, non-empty folder may be replaced by a staged folder:
    /// returns to accept, throws (FileError naming the reason) to refuse.
    using ReplaceCheck = std::function<void(const std::string& existing_folder)>;

    OutputTransaction() = default;
    /// Without a successful commit: removes every staged temporary (files and folders).
    ~OutputTransaction();

    OutputTransaction(const OutputTransaction&) = delete;
    OutputTransaction& operator=(const OutputTransaction&) = delete;
    OutputTransaction(OutputTransaction&&) = delete;
    OutputTransaction& operator=(OutputTransaction&&) = delete;

    /// Registers the file `path` as an output and returns the temporary to write it at (in
    /// the same folder, with the same extension, so writers that pick the format from it work
    /// unchanged). Throws FileError when `path` is a folder, its folder does not exist, or it
    /// is already an output of this transaction.
    std::string stage_file(const std::string& path);

    /// Stages `path` and calls `write(staged_path)` with any writer that takes a path
    /// (write_cloud, write_tum, write_file_atomically, ...). A FileError about the staged
    /// path is rethrown naming `path`, so messages name the file the user asked for.
    void write(const std::string& path, const std::function<void(const std::string&)>& write);

    /// Writes the bytes `write` puts on the stream to `path` (staged, checked for disk full).
    void write_stream(const std::string& path, const std::function<void(std::ostream&)>& write);

    /// Creates the folder `path` and its missing parents for outputs to go in; the folders it
    /// created are removed again (when still empty) unless the transaction commits. Throws
    /// FileError naming `path` and the OS reason.
    void create_folder(const std::string& path);

    /// Creates an empty temporary folder beside the folder `path` (its parents are created)
    /// and returns it; `commit()` renames it to `path`. A symlink at `path` is followed (the
    /// folder it points to is replaced). `path` may be absent, an empty folder, or a
    /// non-empty folder that `replace_check` accepts (none: refused). Checked now, so that a
    /// refusal costs no work, and again at commit.
    std::string stage_folder(const std::string& path, const ReplaceCheck& replace_check = {});

    /// Moves every staged output into place (in the order staged), replacing what was there,
    /// then deletes the replaced files and folders. Throws FileError naming the output and
    /// the OS reason when an output was staged but not written, a destination became
    /// unacceptable, or a move fails; the moves already made are then rolled back. Call once.
    void commit();

    /// Number of staged outputs.
    std::size_t size() const { return outputs_.size(); }

  private:
    struct Output {
        std::string destination;
        std::string temporary;
        bool is_folder = false;
        ReplaceCheck replace_check;
        std::string backup;   // the replaced destination, while commit() runs
        bool placed = false;  // temporary renamed onto destination
    };
    void check_not_staged(const std::string& destination) const;
    void place(Output& output);
    void roll_back();

    void remove_created_folders();

    std::vector<Output> outputs_;
    std::vector<std::string> created_folders_;  // by create_folder, deepest last
    bool finished_ = false;
};

}  // namespace scantling::io
