#pragma once
/// @file Small path helpers shared by the readers, writers and the CLI.

#include <cstddef>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

namespace scantling::io {

/// Longest file name (one path component) the file systems we write to accept, in bytes
/// (NAME_MAX of ext4, xfs, btrfs and tmpfs).
inline constexpr std::size_t kMaxFileNameBytes = 255;

/// Extension of `path` with its dot, lower-cased ("scan.PCD" → ".pcd"; "" when none).
std::string lower_extension(const std::string& path);

/// A path next to `path` for temporary output: same folder, so that renaming it onto `path`
/// stays on one file system and is atomic. The name is "<name>.<tag>-<pid>-<n>" (n counts per
/// process), or with `keep_extension` "<stem>.<tag>-<pid>-<n><ext>" for writers that pick the
/// format from the extension. When that would exceed kMaxFileNameBytes, the name part is cut
/// (at a UTF-8 character boundary) and a 64-bit hash of the whole name appended, so a long
/// name still gets a valid temporary that differs from those of other long names.
/// Thread-safe (the counter is atomic).
std::string temporary_sibling(const std::string& path, std::string_view tag,
                              bool keep_extension = false);

/// Throws FileError naming `path` when it cannot be an output file: it is a folder, or its
/// folder does not exist. Commands call it before their work, so a bad --out costs nothing.
void check_output_file(const std::string& path);

/// `path` made absolute by std::filesystem::weakly_canonical (symlinks, "." and ".." resolved
/// as far as the path exists), without a trailing separator: spellings of one file compare
/// equal ("rec/", "./rec", a symlink to rec).
std::filesystem::path resolved_path(const std::string& path);

/// Refuses an output that would overwrite or replace one of the `inputs`: throws FileError
/// naming `output` and the input when they are the same file, when the output lies inside an
/// input folder (a recording, a folder of scans) or when an input lies inside the output (a
/// folder that would be replaced). Paths are compared after std::filesystem::weakly_canonical
/// (so "./a", "dir/../a" and symlinks match) and, for existing files, by identity (hard links).
/// Empty input strings are ignored.
void ensure_output_distinct(const std::string& output, const std::vector<std::string>& inputs);

}  // namespace scantling::io
