#include <scantling/core/error.hpp>

#include <utility>

namespace scantling {
namespace {

std::string format_location(const FileLocation& location) {
    std::string text;
    if (location.line) {
        text += ": line " + std::to_string(*location.line);
        if (location.column) text += ", column " + std::to_string(*location.column);
    }
    if (location.byte_offset) text += ": byte " + std::to_string(*location.byte_offset);
    return text;
}

}  // namespace

FileError::FileError(std::string path, const std::string& what)
    : Error(path + ": " + what), path_(std::move(path)) {}

ParseError::ParseError(std::string path, FileLocation location, const std::string& what)
    : Error(path + format_location(location) + ": " + what),
      path_(std::move(path)),
      location_(location) {}

}  // namespace scantling
