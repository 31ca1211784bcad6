#include "fuzz_support.hpp"

#include <cxxabi.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <memory>
#include <typeinfo>

namespace scantling::fuzz {
namespace {

namespace fs = std::filesystem;

/// Owns the scratch folder; its destructor (a normal exit) removes it.
class ScratchDirectory {
  public:
    ScratchDirectory()
        : path_((fs::temp_directory_path() / ("scantling-fuzz-" + std::to_string(::getpid())))
                    .string()) {
        fs::remove_all(path_);
        fs::create_directories(path_);
    }
    ~ScratchDirectory() {
        std::error_code ignored;  // a destructor must not throw; a leftover folder is harmless
        fs::remove_all(path_, ignored);
    }
    ScratchDirectory(const ScratchDirectory&) = delete;
    ScratchDirectory& operator=(const ScratchDirectory&) = delete;
    const std::string& path() const { return path_; }

  private:
    std::string path_;
};

std::string demangled(const char* name) {
    int status = 0;
    const std::unique_ptr<char, decltype(&std::free)> text(
        abi::__cxa_demangle(name, nullptr, nullptr, &status), &std::free);
    return status == 0 && text ? std::string(text.get()) : std::string(name);
}

}  // namespace

const std::string& scratch_directory() {
    static const ScratchDirectory directory;
    return directory.path();
}

std::string write_input_file(Bytes bytes, const std::string& name) {
    const std::string path = (fs::path(scratch_directory()) / name).string();
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    out.write(reinterpret_cast<const char*>(bytes.data()),
              static_cast<std::streamsize>(bytes.size()));
    if (!out) report_finding("harness could not write its input file", path);
    return path;
}

std::string fresh_directory(const std::string& name) {
    const fs::path path = fs::path(scratch_directory()) / name;
    fs::remove_all(path);
    fs::create_directories(path);
    return path.string();
}

void report_finding(std::string_view what, std::string_view detail) {
    std::fprintf(stderr, "\n==scantling-fuzz== FINDING: %.*s%s%.*s\n",
                 static_cast<int>(what.size()), what.data(), detail.empty() ? "" : ": ",
                 static_cast<int>(detail.size()), detail.data());
    std::fflush(stderr);
    std::abort();
}

void report_foreign_exception(const std::exception& e) {
    report_finding(
        "uncaught exception " + demangled(typeid(e).name()) + " (not a scantling::Error)",
        e.what());
}

}  // namespace scantling::fuzz
