#pragma once
/// @file
/// The input of the recording fuzzer: a folder of files packed into one byte string, simple
/// enough for a mutator to edit and for a script to pack a real recording (make_seeds.sh):
///
///     @@ groundtruth.tum
///     0 0 0 0 0 0 0 1
///     @@ lidar/times.txt
///     0
///     @@ velodyne/
///
/// Each entry starts with a line "@@ <relative path>" at the start of the input or of a line;
/// its content is every byte up to the newline before the next such line (so binary content
/// keeps its exact size; a text file that should end with a newline has an empty line before
/// the next entry). A path ending in '/' makes an empty folder. Paths are 1 to 4 components of
/// [A-Za-z0-9_.-] other than "." and ".."; entries with any other path are ignored, so nothing is
/// written outside the folder.

#include <string>
#include <string_view>
#include <vector>

namespace scantling::fuzz {

struct ArchiveEntry {
    std::string path;  ///< relative, '/'-separated; ends with '/' for a folder
    std::string_view content;
};

/// The entries of `archive`, in order (at most kMaxArchiveEntries; bytes before the first
/// "@@ " line are ignored).
std::vector<ArchiveEntry> split_archive(std::string_view archive);

/// Writes the entries into `directory` (a later entry replaces an earlier one of the same
/// path); an entry whose path clashes with an existing file or folder is skipped.
void write_archive(const std::vector<ArchiveEntry>& entries, const std::string& directory);

inline constexpr std::size_t kMaxArchiveEntries = 64;

}  // namespace scantling::fuzz
