#include "recording_archive.hpp"

#include <algorithm>
#include <filesystem>
#include <fstream>

namespace scantling::fuzz {
namespace {

namespace fs = std::filesystem;

constexpr std::string_view kMarker = "@@ ";
constexpr std::size_t kMaxComponents = 4;
constexpr std::size_t kMaxPathLength = 128;

bool is_name_char(char c) {
    return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_' ||
           c == '.' || c == '-';
}

bool is_safe_component(std::string_view name) {
    if (name.empty() || name == "." || name == "..") return false;
    for (const char c : name) {
        if (!is_name_char(c)) return false;
    }
    return true;
}

/// Relative, 1..kMaxComponents safe components; a trailing '/' (a folder) is allowed.
bool is_safe_path(std::string_view path) {
    if (path.empty() || path.size() > kMaxPathLength) return false;
    if (path.back() == '/') path.remove_suffix(1);
    std::size_t components = 0;
    while (true) {
        const std::size_t slash = path.find('/');
        if (!is_safe_component(path.substr(0, slash)) || ++components > kMaxComponents)
            return false;
        if (slash == std::string_view::npos) return true;
        path.remove_prefix(slash + 1);
    }
}

/// Offset of the next "@@ " at the start of a line at or after `from`, or npos.
std::size_t next_marker(std::string_view archive, std::size_t from) {
    if (from == 0 && archive.starts_with(kMarker)) return 0;
    const std::size_t found = archive.find("\n@@ ", from == 0 ? 0 : from - 1);
    return found == std::string_view::npos ? found : found + 1;
}

void write_entry(const ArchiveEntry& entry, const fs::path& directory) {
    std::error_code ec;  // a clash (a file where a folder should be) only skips the entry
    const fs::path target = directory / entry.path;
    if (entry.path.back() == '/') {
        fs::create_directories(target, ec);
        return;
    }
    fs::create_directories(target.parent_path(), ec);
    if (ec || fs::is_directory(target, ec)) return;
    std::ofstream(target, std::ios::binary | std::ios::trunc)
        .write(entry.content.data(), static_cast<std::streamsize>(entry.content.size()));
}

}  // namespace

std::vector<ArchiveEntry> split_archive(std::string_view archive) {
    std::vector<ArchiveEntry> entries;
    std::size_t at = next_marker(archive, 0);
    while (at != std::string_view::npos && entries.size() < kMaxArchiveEntries) {
        const std::size_t name_begin = at + kMarker.size();
        const std::size_t name_end = std::min(archive.find('\n', name_begin), archive.size());
        const std::size_t content_begin = std::min(name_end + 1, archive.size());
        const std::size_t next = next_marker(archive, content_begin);
        const std::string_view path = archive.substr(name_begin, name_end - name_begin);
        // The newline before the next marker separates; it is not part of the content.
        const std::size_t content_end =
            next == std::string_view::npos ? archive.size() : std::max(content_begin, next - 1);
        if (is_safe_path(path)) {
            entries.push_back(
                {std::string(path), archive.substr(content_begin, content_end - content_begin)});
        }
        at = next;
    }
    return entries;
}

void write_archive(const std::vector<ArchiveEntry>& entries, const std::string& directory) {
    for (const ArchiveEntry& entry : entries) write_entry(entry, directory);
}

}  // namespace scantling::fuzz
