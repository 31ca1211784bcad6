// Hostile YAML (issue 10): alias bombs, oversized files and deep nesting are refused with a
// ParseError naming the file and the limit, before memory or the stack run out.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

#include <scantling/core/error.hpp>
#include <scantling/io/config_node.hpp>

namespace scantling::io {
namespace {

namespace fs = std::filesystem;

fs::path temp_dir() {
    return fs::path(testing::TempDir()) /
           ("scantling_config_budget_test_" + std::to_string(::getpid()));
}

class TempDirCleanup : public testing::Environment {
    void TearDown() override { fs::remove_all(temp_dir()); }
};
[[maybe_unused]] testing::Environment* const kCleanup =
    testing::AddGlobalTestEnvironment(new TempDirCleanup);

std::string write_file(const std::string& name, const std::string& bytes) {
    fs::create_directories(temp_dir());
    const std::string path = (temp_dir() / name).string();
    std::ofstream(path, std::ios::binary) << bytes;
    return path;
}

/// "Billion laughs": 9 levels of 9 aliases, about 400 bytes, expanding to 9^9 (3.9e8)
/// scalars: the converter without a node budget tried to build all of them (tens of GB).
std::string alias_bomb() {
    std::string text = "a: &a [x, x, x, x, x, x, x, x, x]\n";
    for (char level = 'b'; level <= 'i'; ++level) {
        const char previous = static_cast<char>(level - 1);
        text += std::string(1, level) + ": &" + level + " [";
        for (int i = 0; i < 9; ++i) text += std::string(i > 0 ? ", " : "") + "*" + previous;
        text += "]\n";
    }
    return text;
}

/// The message of the ParseError `parse` throws (empty, and a test failure, when none).
template <class Parse>
std::string parse_error_of(Parse&& parse) {
    try {
        parse();
    } catch (const ParseError& e) {
        return e.what();
    }
    ADD_FAILURE() << "no ParseError";
    return "";
}

TEST(ConfigBudget, AliasBombIsRefusedWithinTheDefaultNodeBudget) {
    const std::string bomb = alias_bomb();
    ASSERT_LT(bomb.size(), 500u);
    const std::string path = write_file("bomb.yaml", bomb);
    const std::string what = parse_error_of([&] { (void)parse_yaml_file(path); });
    EXPECT_EQ(what.rfind(path + ": line ", 0), 0u) << what;
    EXPECT_NE(what.find("more than 1000000 nodes"), std::string::npos) << what;
}

TEST(ConfigBudget, EachExpansionOfAnAliasCountsItsWholeSubtree) {
    // root map 1 + a (1 + 2) + b (1 + 3 x 3) = 14 nodes.
    const std::string text = "a: &a [x, x]\nb: [*a, *a, *a]\n";
    EXPECT_NO_THROW((void)parse_yaml_string(text, "ok.yaml", YamlLimits{.max_nodes = 14}));
    const std::string what = parse_error_of(
        [&] { (void)parse_yaml_string(text, "tight.yaml", YamlLimits{.max_nodes = 13}); });
    EXPECT_EQ(what.rfind("tight.yaml: line ", 0), 0u) << what;
    EXPECT_NE(what.find("more than 13 nodes"), std::string::npos) << what;
}

TEST(ConfigBudget, FileOverTheByteCapIsRefusedBeforeYamlCppReadsIt) {
    // Unbalanced brackets: yaml-cpp would report a syntax error, the size check comes first.
    const std::size_t cap = YamlLimits{}.max_bytes;
    const std::string path = write_file("big.yaml", std::string(cap + 1, '['));
    const std::string what = parse_error_of([&] { (void)parse_yaml_file(path); });
    EXPECT_EQ(what, path + ": " + std::to_string(cap + 1) +
                        " bytes is more than the 1 MiB a YAML config or scenario may have; "
                        "refusing to parse it");
    // A file at the cap is parsed (a comment of cap bytes).
    const std::string at_cap = write_file("at_cap.yaml", "#" + std::string(cap - 1, 'x'));
    EXPECT_TRUE(parse_yaml_file(at_cap).is_null());
}

TEST(ConfigBudget, TextOverTheByteCapIsRefused) {
    const std::string what = parse_error_of(
        [] { (void)parse_yaml_string("seed: 12345\n", "mem.yaml", YamlLimits{.max_bytes = 8}); });
    EXPECT_EQ(what.rfind("mem.yaml: 12 bytes is more than the 8 bytes", 0), 0u) << what;
}

// yaml-cpp's LoadAll yields endless empty documents for a stray top-level ',' (the old code
// hung here, growing memory; found by fuzz/config_fuzz).
TEST(ConfigBudget, StrayTopLevelCommaIsAParseErrorNotAnEndlessDocumentStream) {
    for (const char* text : {",", "seed: 1\n,\n", "a: 1\n---\nb: 2\n"}) {
        try {
            (void)parse_yaml_string(text, "comma.yaml");
            ADD_FAILURE() << "accepted: " << text;
        } catch (const ParseError& e) {
            EXPECT_NE(std::string(e.what()).find("comma.yaml"), std::string::npos) << e.what();
        }
    }
    EXPECT_EQ(parse_yaml_string("seed: 1\n", "one.yaml").kind, ConfigNode::Kind::kMap);
}

TEST(ConfigBudget, DeepNestingIsAParseErrorNamingTheDepth) {
    // yaml-cpp's own recursion guard stops at 2000 levels (its message was "bad file").
    const std::string flow(100'000, '[');
    const std::string deep = flow + std::string(flow.size(), ']');
    const std::string what = parse_error_of([&] { (void)parse_yaml_string(deep, "deep.yaml"); });
    EXPECT_NE(what.find("nesting deeper than 2000 levels"), std::string::npos) << what;
    // Below yaml-cpp's guard, the converter's own depth limit names its bound.
    const std::string hundred = std::string(100, '[') + std::string(100, ']');
    const std::string what_100 =
        parse_error_of([&] { (void)parse_yaml_string(hundred, "deep100.yaml"); });
    EXPECT_NE(what_100.find("nesting deeper than 64 levels"), std::string::npos) << what_100;
}

TEST(ConfigBudget, DeviceFilesAreNotRead) {
    // /dev/zero never ends: it must be refused without reading.
    EXPECT_THROW((void)parse_yaml_file("/dev/zero"), FileError);
}

}  // namespace
}  // namespace scantling::io
