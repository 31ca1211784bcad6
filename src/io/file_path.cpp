#include <scantling/core/error.hpp>
#include <scantling/io/file_path.hpp>

#include <fmt/format.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cctype>
#include <cstdint>
#include <filesystem>
#include <system_error>

namespace scantling::io {
namespace {

namespace fs = std::filesystem;

constexpr std::size_t kHashBytes = 17;  // "~" + 16 hex digits

std::uint64_t fnv1a_64(std::string_view bytes) {
    std::uint64_t hash = 0xcbf29ce484222325ULL;
    for (const char c : bytes) {
        hash ^= static_cast<unsigned char>(c);
        hash *= 0x100000001b3ULL;
    }
    return hash;
}

/// The first `max_bytes` of `name`, shortened further so that no UTF-8 sequence is split.
std::string_view cut_at_character(std::string_view name, std::size_t max_bytes) {
    std::size_t end = std::min(max_bytes, name.size());
    while (end > 0 && end < name.size() && (static_cast<unsigned char>(name[end]) & 0xC0) == 0x80) {
        --end;
    }
    return name.substr(0, end);
}

/// `base + suffix`, with `base` cut and the hash of `whole` inserted when too long.
std::string fit_name(std::string_view base, const std::string& suffix, std::string_view whole) {
    if (base.size() + suffix.size() <= kMaxFileNameBytes) return std::string(base) + suffix;
    const std::string hash = fmt::format("~{:016x}", fnv1a_64(whole));
    const std::size_t room =
        kMaxFileNameBytes - std::min(kMaxFileNameBytes, suffix.size() + kHashBytes);
    return std::string(cut_at_character(base, room)) + hash + suffix;
}

/// `path` with a file name: "rec/" → "rec", "." or ".." → the absolute folder they name.
fs::path named_path(const std::string& path) {
    fs::path p(path);
    if (!p.has_filename()) p = p.parent_path();
    if (p.filename() == "." || p.filename() == "..") p = fs::absolute(p).lexically_normal();
    if (!p.has_filename()) p = p.parent_path();
    return p;
}

/// True when `inner` is `outer` or lies below it (component-wise, not by string prefix).
bool is_within(const fs::path& inner, const fs::path& outer) {
    const auto mismatch = std::mismatch(outer.begin(), outer.end(), inner.begin(), inner.end());
    return mismatch.first == outer.end();
}

bool same_file(const std::string& a, const std::string& b) {
    std::error_code ec;
    return fs::equivalent(a, b, ec) && !ec;
}

void check_against(const std::string& output, const fs::path& output_c, const std::string& input) {
    const fs::path input_c = resolved_path(input);
    std::error_code ec;
    if (output_c == input_c || same_file(output, input)) {
        throw FileError(output, "is also the input '" + input + "', expected another output path");
    }
    if (is_within(output_c, input_c) && fs::is_directory(input_c, ec)) {
        throw FileError(output, "lies inside the input folder '" + input +
                                    "', expected an output outside the inputs");
    }
    if (is_within(input_c, output_c)) {
        throw FileError(output, "would replace the folder holding the input '" + input +
                                    "', expected an output outside the inputs");
    }
}

}  // namespace

std::string lower_extension(const std::string& path) {
    std::string ext = std::filesystem::path(path).extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    return ext;
}

fs::path resolved_path(const std::string& path) {
    std::error_code ec;
    // absolute() first: weakly_canonical leaves a relative path relative when none of it exists.
    fs::path result = fs::weakly_canonical(fs::absolute(path, ec), ec);
    if (ec) result = fs::absolute(path, ec).lexically_normal();  // e.g. a path too long
    if (!result.has_filename() && result.has_parent_path()) result = result.parent_path();
    return result;
}

std::string temporary_sibling(const std::string& path, std::string_view tag, bool keep_extension) {
    // pid + process-wide counter: unique across processes and across callers in this process.
    static std::atomic<std::uint64_t> counter{0};
    const fs::path p = named_path(path);
    const std::string name = p.filename().string();
    const std::string unique = fmt::format(".{}-{}-{}", tag, ::getpid(), counter++);
    std::string extension = keep_extension ? p.extension().string() : std::string();
    // An extension too long to keep beside the hash is no format any writer knows anyway.
    if (unique.size() + extension.size() + kHashBytes >= kMaxFileNameBytes) extension.clear();
    const std::string base = extension.empty() ? name : p.stem().string();
    return (p.parent_path() / fit_name(base, unique + extension, name)).string();
}

void check_output_file(const std::string& path) {
    std::error_code ec;
    if (fs::is_directory(path, ec)) throw FileError(path, "cannot write: the path is a folder");
    const fs::path parent = fs::path(path).parent_path();
    if (!parent.empty() && !fs::is_directory(parent, ec)) {
        throw FileError(path, "cannot write: its folder '" + parent.string() + "' does not exist");
    }
}

void ensure_output_distinct(const std::string& output, const std::vector<std::string>& inputs) {
    const fs::path output_c = resolved_path(output);
    for (const std::string& input : inputs) {
        if (!input.empty()) check_against(output, output_c, input);
    }
}

}  // namespace scantling::io
