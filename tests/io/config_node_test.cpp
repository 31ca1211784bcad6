#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include <unistd.h>

#include <scantling/core/error.hpp>
#include <scantling/io/config_node.hpp>

namespace scantling::io {
namespace {

std::filesystem::path temp_dir() {
    return std::filesystem::path(testing::TempDir()) /
           ("scantling_config_node_test_" + std::to_string(::getpid()));
}

/// Removes the temp directory once all tests of the process have run.
class TempDirCleanup : public testing::Environment {
    void TearDown() override { std::filesystem::remove_all(temp_dir()); }
};
[[maybe_unused]] testing::Environment* const kCleanup =
    testing::AddGlobalTestEnvironment(new TempDirCleanup);

/// Writes `text` to a fresh file named `name` in a per-process temp directory.
std::string write_yaml(const std::string& name, const std::string& text) {
    const auto dir = temp_dir();
    std::filesystem::create_directories(dir);
    std::string path = (dir / name).string();
    std::ofstream(path) << text;
    return path;
}

TEST(ConfigNode, KeepsMapOrderAndPositions) {
    const ConfigNode root = parse_yaml_string("b: 1\na:\n  - x\n  - {k: v}\n", "mem");
    ASSERT_TRUE(root.is_map());
    ASSERT_EQ(root.map.size(), 2u);
    EXPECT_EQ(root.map[0].first, "b");
    EXPECT_EQ(root.map[1].first, "a");
    const ConfigNode* a = root.find("a");
    ASSERT_NE(a, nullptr);
    ASSERT_TRUE(a->is_sequence());
    EXPECT_EQ(a->line, 2);
    EXPECT_EQ(a->sequence[0].scalar, "x");
    EXPECT_EQ(a->sequence[0].line, 3);
    EXPECT_EQ(a->sequence[0].column, 5);
    EXPECT_EQ(a->sequence[1].find("k")->scalar, "v");
    EXPECT_EQ(a->sequence[1].file, "mem");
    EXPECT_EQ(root.find("c"), nullptr);
}

TEST(ConfigNode, MalformedYamlGivesLineAndColumn) {
    const std::string path = write_yaml("malformed.yaml", "seed: 1\nname: [a, b\nverbose: true\n");
    try {
        (void)parse_yaml_file(path);
        FAIL() << "no ParseError";
    } catch (const ParseError& e) {
        EXPECT_EQ(e.path(), path);
        ASSERT_TRUE(e.location().line.has_value());
        EXPECT_EQ(*e.location().line, 3);
        EXPECT_EQ(std::string(e.what()).rfind(path + ": line 3, column", 0), 0u) << e.what();
    }
}

TEST(ConfigNode, DuplicateKeyIsAParseErrorAtTheSecondKey) {
    const std::string path =
        write_yaml("dup.yaml", "seed: 1\nparallel:\n  pin: true\n  pin: false\n");
    try {
        (void)parse_yaml_file(path);
        FAIL() << "no ParseError";
    } catch (const ParseError& e) {
        EXPECT_EQ(std::string(e.what()), path + ": line 4, column 3: duplicate key 'pin'");
    }
}

TEST(ConfigNode, ScalarsKeepTheirTextAndNullsAreNull) {
    const ConfigNode root = parse_yaml_string("a: '0.50'\nb:\nc: ~\nd: \"\"\n");
    EXPECT_EQ(root.find("a")->scalar, "0.50");
    EXPECT_TRUE(root.find("b")->is_null());
    EXPECT_TRUE(root.find("c")->is_null());
    EXPECT_TRUE(root.find("d")->is_scalar());
    EXPECT_EQ(root.find("a")->file, "<string>");
    EXPECT_EQ(describe_kind(*root.find("a")), "'0.50'");
    EXPECT_EQ(describe_kind(*root.find("b")), "an empty value");
}

TEST(ConfigNode, NonScalarKeysAndSeveralDocumentsAreRejected) {
    EXPECT_THROW(parse_yaml_string("? [1, 2]\n: 3\n"), ParseError);
    EXPECT_THROW(parse_yaml_string("a: 1\n---\nb: 2\n"), ParseError);
}

TEST(ConfigNode, AliasesAreCopiedAndRecursiveAliasesRejected) {
    const ConfigNode root = parse_yaml_string("a: &x {k: 1}\nb: *x\n");
    EXPECT_EQ(root.find("b")->find("k")->scalar, "1");
    EXPECT_THROW(parse_yaml_string("a: &x [1, *x]\n"), ParseError);
}

TEST(ConfigNode, MissingFileOrDirectoryIsAFileError) {
    const std::string path = write_yaml("exists.yaml", "a: 1\n");
    EXPECT_EQ(parse_yaml_file(path).find("a")->scalar, "1");
    EXPECT_THROW(parse_yaml_file(path + ".missing"), FileError);
    EXPECT_THROW(parse_yaml_file(std::filesystem::path(path).parent_path().string()), FileError);
}

}  // namespace
}  // namespace scantling::io
