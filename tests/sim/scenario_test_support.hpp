#pragma once
// Helpers shared by the scenario-runner tests: scratch recording folders and byte-exact
// snapshots of a recording for the determinism checks.

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>

namespace scantling::sim::test {

/// An empty scratch folder name, per test process: ctest runs tests concurrently.
inline std::filesystem::path scenario_temp_dir(const std::string& prefix, const std::string& name) {
    const std::filesystem::path dir =
        std::filesystem::path(testing::TempDir()) /
        ("scantling_" + prefix + "_" + name + "_" + std::to_string(::getpid()));
    std::filesystem::remove_all(dir);
    return dir;
}

/// Every file of a recording (relative path → bytes), except timing.json: wall time is the
/// one file that may differ between identical runs.
inline std::map<std::string, std::string> read_tree(const std::filesystem::path& dir) {
    std::map<std::string, std::string> files;
    for (const auto& entry : std::filesystem::recursive_directory_iterator(dir)) {
        if (!entry.is_regular_file()) continue;
        std::ifstream in(entry.path(), std::ios::binary);
        std::ostringstream bytes;
        bytes << in.rdbuf();
        files[std::filesystem::relative(entry.path(), dir).string()] = bytes.str();
    }
    files.erase("timing.json");
    return files;
}

}  // namespace scantling::sim::test
