// Fails when a module includes a module above it in the order of DEVELOPERS.md:
// core → io → mapping → registration → perception → odometry → localization → safety →
// planning → control → mission → apps; `sim` needs only core and io; only `mission` (and the
// apps) may join the simulator with the algorithms.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <map>
#include <optional>
#include <regex>
#include <set>
#include <string>
#include <vector>

namespace fs = std::filesystem;

namespace {

const std::vector<std::string> kOrder = {"core",       "io",       "mapping",      "registration",
                                         "perception", "odometry", "localization", "safety",
                                         "planning",   "control",  "mission"};

std::optional<int> rank_of(const std::string& module) {
    const auto it = std::find(kOrder.begin(), kOrder.end(), module);
    if (it == kOrder.end()) return std::nullopt;
    return static_cast<int>(it - kOrder.begin());
}

/// May code of module `from` include the public headers of module `to`?
bool allowed(const std::string& from, const std::string& to) {
    if (from == to) return true;
    // The CLI and downstream consumers (tests/consumer) sit on top of everything.
    if (from == "apps" || from == "consumer") return true;
    if (from == "sim") return to == "core" || to == "io";
    if (to == "sim") return from == "mission";
    const auto rank_from = rank_of(from);
    const auto rank_to = rank_of(to);
    if (!rank_from || !rank_to) return false;  // unknown module: must be added to the order
    return *rank_to < *rank_from;
}

struct Violation {
    std::string file;
    int line;
    std::string included;
};

/// Scans `<root>/<tree>/<module>/...` and returns every include of a higher module.
std::vector<Violation> scan(const fs::path& root, const std::string& tree) {
    static const std::regex include_re(R"(^\s*#\s*include\s*[<"]scantling/([a-z_]+)/)");
    std::vector<Violation> violations;
    const fs::path base = root / tree;
    if (!fs::exists(base)) return violations;
    for (const auto& entry : fs::recursive_directory_iterator(base)) {
        if (!entry.is_regular_file()) continue;
        const auto ext = entry.path().extension();
        if (ext != ".hpp" && ext != ".cpp" && ext != ".h") continue;
        const std::string module = fs::relative(entry.path(), base).begin()->string();
        std::ifstream in(entry.path());
        std::string text;
        int line_no = 0;
        while (std::getline(in, text)) {
            ++line_no;
            std::smatch m;
            if (std::regex_search(text, m, include_re) && !allowed(module, m[1])) {
                violations.push_back({entry.path().string(), line_no, m[1]});
            }
        }
    }
    return violations;
}

}  // namespace

TEST(ModuleOrder, RuleAllowsLowerAndRejectsHigherModules) {
    EXPECT_TRUE(allowed("io", "core"));
    EXPECT_TRUE(allowed("mission", "sim"));
    EXPECT_TRUE(allowed("sim", "io"));
    EXPECT_FALSE(allowed("core", "io"));
    EXPECT_FALSE(allowed("registration", "odometry"));
    EXPECT_FALSE(allowed("sim", "registration"));
    EXPECT_FALSE(allowed("odometry", "sim"));
    EXPECT_FALSE(allowed("unknown_module", "core"));
    EXPECT_TRUE(allowed("apps", "sim"));
}

TEST(ModuleOrder, NoModuleIncludesAHigherOne) {
    const fs::path root = SCANTLING_SOURCE_DIR;
    ASSERT_TRUE(fs::exists(root / "include" / "scantling" / "core"));
    std::vector<Violation> all;
    for (const std::string tree : {"include/scantling", "src", "tests"}) {
        const auto v = scan(root, tree);
        all.insert(all.end(), v.begin(), v.end());
    }
    for (const auto& v : all) {
        ADD_FAILURE() << v.file << ":" << v.line << " includes scantling/" << v.included
                      << "/, a module that its own module may not depend on";
    }
}

TEST(ModuleOrder, EveryModuleFolderIsAKnownModule) {
    const fs::path root = SCANTLING_SOURCE_DIR;
    for (const auto& entry : fs::directory_iterator(root / "include" / "scantling")) {
        if (!entry.is_directory()) continue;
        const std::string name = entry.path().filename().string();
        EXPECT_TRUE(rank_of(name) || name == "sim") << "unknown module folder " << name;
    }
}
