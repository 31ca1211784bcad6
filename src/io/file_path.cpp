#include <scantling/io/file_path.hpp>

#include <algorithm>
#include <cctype>
#include <filesystem>

namespace scantling::io {

std::string lower_extension(const std::string& path) {
    std::string ext = std::filesystem::path(path).extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    return ext;
}

}  // namespace scantling::io
