#pragma once
/// @file
/// What every libFuzzer target shares (docs/fuzzing.md): a scratch folder of its own, the input
/// bytes written as a file, and the one rule the readers must keep on hostile bytes: throw a
/// scantling::Error (the expected answer) and nothing else.
///
/// Anything else is a finding: a crash or sanitizer report, an allocation above libFuzzer's
/// -malloc_limit_mb, a timeout, or any other exception (std::bad_alloc, std::length_error,
/// std::out_of_range, a yaml-cpp or std::filesystem exception), which is printed with its type
/// and aborts the process so that libFuzzer saves the input.

#include <cstddef>
#include <cstdint>
#include <exception>
#include <span>
#include <string>
#include <string_view>

#include <scantling/core/error.hpp>

namespace scantling::fuzz {

/// The input of one libFuzzer run.
using Bytes = std::span<const std::uint8_t>;

/// The bytes as text (YAML, poses, archives).
inline std::string_view as_text(Bytes bytes) {
    return {reinterpret_cast<const char*>(bytes.data()), bytes.size()};
}

/// This process's folder under $TMPDIR (scantling-fuzz-<pid>), created on first use and removed
/// at a normal exit. A pid of its own keeps libFuzzer's -fork/-jobs workers apart.
const std::string& scratch_directory();

/// Writes `bytes` to scratch_directory()/`name` (replacing an earlier input) and returns its path.
/// Every target writes its input before reading it: after a hang (killed from outside) the
/// scratch folder holds the input (scripts/run-fuzzers.sh keeps it).
std::string write_input_file(Bytes bytes, const std::string& name);

/// An empty folder scratch_directory()/`name` (its earlier content removed), for inputs that
/// are a folder of files.
std::string fresh_directory(const std::string& name);

/// Prints "<what>: <detail>" as a finding and aborts (libFuzzer saves the input as a crash).
[[noreturn]] void report_finding(std::string_view what, std::string_view detail);

/// Reports an exception other than scantling::Error with its demangled type and message.
[[noreturn]] void report_foreign_exception(const std::exception& e);

/// Runs `read`; swallows scantling::Error (the documented answer to a malformed input) and
/// reports any other exception as a finding.
template <class Read>
void expect_only_scantling_errors(Read&& read) {
    try {
        read();
    } catch (const scantling::Error&) {
        // Expected: the reader refused the input with a message naming the file.
    } catch (const std::exception& e) {
        report_foreign_exception(e);
    } catch (...) {
        report_finding("exception of a type not derived from std::exception", "");
    }
}

}  // namespace scantling::fuzz
