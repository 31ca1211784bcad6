#pragma once
/// @file
/// One error policy for the whole stack (CONVENTIONS §9): contract violations throw a typed
/// `scantling::Error`; algorithmic outcomes ("did not converge") are data in result structs.

#include <cstdint>
#include <optional>
#include <stdexcept>
#include <string>

namespace scantling {

/// Base class of every exception scantling throws. `what()` is one complete line.
class Error : public std::runtime_error {
  public:
    using std::runtime_error::runtime_error;
};

/// A configuration value is impossible: names the field, the value and the expectation.
/// Example message: "registration.voxel_size_m = -0.1, expected > 0".
class ConfigError : public Error {
  public:
    using Error::Error;
};

/// Input data violates a contract (empty cloud, NaN point, mismatched field sizes).
class InputError : public Error {
  public:
    using Error::Error;
};

/// An application refuses to pass on an estimate that did not converge (the libraries return
/// that as data: RegistrationResult::converged); names the method, why and what to try.
class NotConvergedError : public Error {
  public:
    using Error::Error;
};

/// A file cannot be opened, read, created or renamed (missing, unwritable, ...).
class FileError : public Error {
  public:
    FileError(std::string path, const std::string& what);
    const std::string& path() const { return path_; }

  private:
    std::string path_;
};

/// Where in a file a parse error happened: a byte offset (binary data) or a line (text).
struct FileLocation {
    std::optional<std::uint64_t> byte_offset;  ///< 0-based offset into the file
    std::optional<int> line;                   ///< 1-based line number
    std::optional<int> column;                 ///< 1-based column number
};

/// A file's content is malformed: names the file, the location and what was expected.
/// Message: "<path>: line 12: <what>" or "<path>: byte 4096: <what>".
class ParseError : public Error {
  public:
    ParseError(std::string path, FileLocation location, const std::string& what);
    const std::string& path() const { return path_; }
    const FileLocation& location() const { return location_; }

  private:
    std::string path_;
    FileLocation location_;
};

}  // namespace scantling
