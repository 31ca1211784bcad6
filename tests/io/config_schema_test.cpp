#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>
#include <string_view>
#include <vector>

#include <unistd.h>

#include <scantling/core/error.hpp>
#include <scantling/io/config_schema.hpp>

namespace scantling::io {
namespace {

enum class Method { kIcp, kGicp, kNdt };

struct ThreadsConfig {
    int num_threads = 0;
    bool pin = false;
};

struct SensorConfig {
    std::string name = "lidar";
    double rate_hz = 10.0;
};

struct TestConfig {
    double voxel_size_m = 0.05;
    float weight = 1.5f;
    int min_iterations = 1;
    int max_iterations = 30;
    unsigned seed = 7;
    bool verbose = false;
    std::string name = "default";
    Method method = Method::kIcp;
    Eigen::Vector3d gravity_mps2{0.0, 0.0, -9.81};
    std::vector<double> weights{1.0, 2.0};
    ThreadsConfig parallel;
    std::vector<SensorConfig> sensors;

    void validate(std::string_view prefix) const {
        if (max_iterations < min_iterations) {
            throw ConfigError(std::string(prefix) + ".max_iterations = " +
                              std::to_string(max_iterations) + ", expected >= min_iterations");
        }
    }
};

ConfigSchema<TestConfig> test_schema() {
    ConfigSchema<ThreadsConfig> threads;
    threads.field("num_threads", &ThreadsConfig::num_threads, "0 = all", Range{.min = 0})
        .field("pin", &ThreadsConfig::pin);
    ConfigSchema<SensorConfig> sensor;
    sensor.field("name", &SensorConfig::name)
        .field("rate_hz", &SensorConfig::rate_hz, "", Range{.min = 0, .min_exclusive = true});
    ConfigSchema<TestConfig> schema;
    schema
        .field("voxel_size_m", &TestConfig::voxel_size_m, "voxel edge",
               Range{.min = 0, .min_exclusive = true})
        .field("weight", &TestConfig::weight, "", Range{.min = 0, .max = 10})
        .field("min_iterations", &TestConfig::min_iterations)
        .field("max_iterations", &TestConfig::max_iterations, "", Range{.min = 1})
        .field("seed", &TestConfig::seed)
        .field("verbose", &TestConfig::verbose)
        .field("name", &TestConfig::name)
        .enum_field("method", &TestConfig::method,
                    {{"icp", Method::kIcp}, {"gicp", Method::kGicp}, {"ndt", Method::kNdt}})
        .field("gravity_mps2", &TestConfig::gravity_mps2)
        .field("weights", &TestConfig::weights, "", Range{.min = 0})
        .section("parallel", &TestConfig::parallel, threads, "threads")
        .list("sensors", &TestConfig::sensors, sensor);
    return schema;
}

/// Per process: ctest runs tests concurrently, and other builds may run this suite too.
std::filesystem::path temp_dir() {
    return std::filesystem::path(testing::TempDir()) /
           ("scantling_config_schema_test_" + std::to_string(::getpid()));
}

/// Removes the temp directory once all tests of the process have run.
class TempDirCleanup : public testing::Environment {
    void TearDown() override { std::filesystem::remove_all(temp_dir()); }
};
[[maybe_unused]] testing::Environment* const kCleanup =
    testing::AddGlobalTestEnvironment(new TempDirCleanup);

std::string yaml_path(const std::string& name) {
    std::filesystem::create_directories(temp_dir());
    return (temp_dir() / name).string();
}

/// Writes `text` to a fresh file named `name` in the test temp directory.
std::string write_yaml(const std::string& name, const std::string& text) {
    std::string path = yaml_path(name);
    std::ofstream(path) << text;
    return path;
}

/// The message of the ParseError that loading `text` throws ("" and a failure if none).
std::string load_error(const std::string& name, const std::string& text) {
    const std::string path = write_yaml(name, text);
    try {
        (void)load_config(path, test_schema());
    } catch (const ParseError& e) {
        EXPECT_EQ(e.path(), path);
        return e.what();
    }
    ADD_FAILURE() << "no ParseError for " << name;
    return "";
}

/// Asserts the message starts with "<file>: line L: key '<key>'".
void expect_located(const std::string& message, const std::string& name, int line,
                    const std::string& key) {
    const std::string expected =
        yaml_path(name) + ": line " + std::to_string(line) + ": key '" + key + "'";
    EXPECT_EQ(message.rfind(expected, 0), 0u) << message << "\nexpected prefix: " << expected;
}

TEST(ConfigSchema, AppliesEveryFieldTypeFromAValidFile) {
    const std::string path = write_yaml("valid.yaml", R"(# comment
voxel_size_m: 0.1
weight: 2.5
max_iterations: 50
seed: 42
verbose: true
name: "tank 3"
method: gicp
gravity_mps2: [0.1, -0.2, -9.8]
weights:
  - 0.5
  - 1.5
  - 3
parallel:
  num_threads: 4
  pin: yes
sensors:
  - name: front
    rate_hz: 20
  - rate_hz: 5.5
)");
    const TestConfig config = load_config(path, test_schema());
    EXPECT_EQ(config.voxel_size_m, 0.1);
    EXPECT_EQ(config.weight, 2.5f);
    EXPECT_EQ(config.max_iterations, 50);
    EXPECT_EQ(config.seed, 42u);
    EXPECT_TRUE(config.verbose);
    EXPECT_EQ(config.name, "tank 3");
    EXPECT_EQ(config.method, Method::kGicp);
    EXPECT_EQ(config.gravity_mps2, Eigen::Vector3d(0.1, -0.2, -9.8));
    EXPECT_EQ(config.weights, (std::vector<double>{0.5, 1.5, 3.0}));
    EXPECT_EQ(config.parallel.num_threads, 4);
    EXPECT_TRUE(config.parallel.pin);
    ASSERT_EQ(config.sensors.size(), 2u);
    EXPECT_EQ(config.sensors[0].name, "front");
    EXPECT_EQ(config.sensors[0].rate_hz, 20.0);
    EXPECT_EQ(config.sensors[1].name, "lidar");  // item default
    EXPECT_EQ(config.sensors[1].rate_hz, 5.5);
}

TEST(ConfigSchema, MissingKeysKeepTheStructDefaults) {
    const std::string path = write_yaml("partial.yaml", "parallel:\n  pin: true\n");
    const TestConfig config = load_config(path, test_schema());
    const TestConfig defaults;
    EXPECT_EQ(config.voxel_size_m, defaults.voxel_size_m);
    EXPECT_EQ(config.max_iterations, defaults.max_iterations);
    EXPECT_EQ(config.name, defaults.name);
    EXPECT_EQ(config.method, defaults.method);
    EXPECT_EQ(config.gravity_mps2, defaults.gravity_mps2);
    EXPECT_EQ(config.weights, defaults.weights);
    EXPECT_EQ(config.parallel.num_threads, defaults.parallel.num_threads);
    EXPECT_TRUE(config.parallel.pin);
}

TEST(ConfigSchema, EmptyFileAndEmptySectionKeepDefaults) {
    EXPECT_EQ(load_config(write_yaml("empty.yaml", ""), test_schema()).max_iterations, 30);
    const std::string path = write_yaml("empty_section.yaml", "parallel:\n  # pin: true\n");
    EXPECT_FALSE(load_config(path, test_schema()).parallel.pin);
}

TEST(ConfigSchema, UnknownKeyNamesLineKeyPathAndValidKeys) {
    const std::string message =
        load_error("unknown.yaml", "voxel_size_m: 0.1\nparallel:\n  pin: true\n  threads: 2\n");
    expect_located(message, "unknown.yaml", 4, "parallel.threads");
    EXPECT_NE(message.find("valid keys: num_threads, pin"), std::string::npos) << message;
}

TEST(ConfigSchema, WrongTypeNamesTheOffendingText) {
    const std::string message = load_error("type.yaml", "name: a\nmax_iterations: abc\n");
    expect_located(message, "type.yaml", 2, "max_iterations");
    EXPECT_NE(message.find("expected an integer, got 'abc'"), std::string::npos) << message;
    expect_located(load_error("real.yaml", "\n\nvoxel_size_m: [1]\n"), "real.yaml", 3,
                   "voxel_size_m");
    expect_located(load_error("bool.yaml", "verbose: maybe\n"), "bool.yaml", 1, "verbose");
    expect_located(load_error("frac.yaml", "seed: 1.5\n"), "frac.yaml", 1, "seed");
    expect_located(load_error("str.yaml", "name:\n  a: 1\n"), "str.yaml", 1, "name");
}

TEST(ConfigSchema, OutOfRangeValueNamesValueAndBound) {
    const std::string message = load_error("range.yaml", "seed: 1\nvoxel_size_m: -0.1\n");
    expect_located(message, "range.yaml", 2, "voxel_size_m");
    EXPECT_NE(message.find("= -0.1, expected > 0"), std::string::npos) << message;
    const std::string nested = load_error("nested_range.yaml", "parallel:\n  num_threads: -1\n");
    expect_located(nested, "nested_range.yaml", 2, "parallel.num_threads");
    EXPECT_NE(nested.find("expected >= 0"), std::string::npos) << nested;
    const std::string unsigned_negative = load_error("unsigned.yaml", "seed: -3\n");
    expect_located(unsigned_negative, "unsigned.yaml", 1, "seed");
    const std::string both = load_error("both.yaml", "weight: 11\n");
    EXPECT_NE(both.find("expected in [0, 10]"), std::string::npos) << both;
}

TEST(ConfigSchema, BadEnumValueListsTheChoices) {
    const std::string message = load_error("enum.yaml", "seed: 1\n\nmethod: lm\n");
    expect_located(message, "enum.yaml", 3, "method");
    EXPECT_NE(message.find("expected one of icp, gicp, ndt, got 'lm'"), std::string::npos)
        << message;
}

TEST(ConfigSchema, NonFiniteNumbersAreRejected) {
    expect_located(load_error("nan.yaml", "voxel_size_m: .nan\n"), "nan.yaml", 1, "voxel_size_m");
    expect_located(load_error("inf.yaml", "weights: [1, -.inf]\n"), "inf.yaml", 1, "weights[1]");
    expect_located(load_error("huge.yaml", "voxel_size_m: 1e999\n"), "huge.yaml", 1,
                   "voxel_size_m");
    expect_located(load_error("nan_word.yaml", "\n\ngravity_mps2: [0, nan, 1]\n"), "nan_word.yaml",
                   3, "gravity_mps2[1]");
}

TEST(ConfigSchema, WrongSequenceLengthAndNonMapsAreErrors) {
    const std::string message = load_error("len.yaml", "gravity_mps2: [0, 0]\n");
    expect_located(message, "len.yaml", 1, "gravity_mps2");
    EXPECT_NE(message.find("expected a sequence of 3 numbers, got 2 items"), std::string::npos);
    expect_located(load_error("section.yaml", "seed: 2\nparallel: 4\n"), "section.yaml", 2,
                   "parallel");
    expect_located(load_error("list.yaml", "sensors:\n  - name: a\n  - rate_hz: 0\n"), "list.yaml",
                   3, "sensors[1].rate_hz");
    const std::string root = load_error("root.yaml", "- 1\n- 2\n");
    EXPECT_NE(root.find("root.yaml: line 1: document: expected a map"), std::string::npos) << root;
}

TEST(ConfigSchema, ValidateRunsAfterApplyAndNamesTheFile) {
    const std::string path = write_yaml("validate.yaml", "min_iterations: 10\nmax_iterations: 5\n");
    try {
        (void)load_config(path, test_schema(), "icp");
        FAIL() << "no ConfigError";
    } catch (const ConfigError& e) {
        EXPECT_EQ(std::string(e.what()),
                  path + ": icp.max_iterations = 5, expected >= min_iterations");
    }
}

TEST(ConfigSchema, MissingFileIsAFileErrorNamingThePath) {
    const std::string path = write_yaml("exists.yaml", "") + ".missing";
    try {
        (void)load_config(path, test_schema());
        FAIL() << "no FileError";
    } catch (const FileError& e) {
        EXPECT_EQ(e.path(), path);
        EXPECT_NE(std::string(e.what()).find(path), std::string::npos);
    }
}

TEST(ConfigSchema, DescribeDumpsDefaultsAndDocs) {
    const std::string text = test_schema().describe();
    EXPECT_NE(text.find("voxel_size_m: 0.05  # voxel edge (> 0)\n"), std::string::npos) << text;
    EXPECT_NE(text.find("method: icp  # (one of: icp, gicp, ndt)\n"), std::string::npos) << text;
    EXPECT_NE(text.find("parallel:  # threads\n  num_threads: 0  # 0 = all (>= 0)\n"),
              std::string::npos)
        << text;
    EXPECT_NE(text.find("gravity_mps2: [0.0, 0.0, -9.81]\n"), std::string::npos) << text;
    EXPECT_NE(text.find("name: \"default\"\n"), std::string::npos) << text;
    // The dump is itself a valid config that reproduces the defaults.
    const TestConfig round_trip = load_config(write_yaml("dump.yaml", text), test_schema());
    EXPECT_EQ(round_trip.gravity_mps2, TestConfig{}.gravity_mps2);
    EXPECT_EQ(round_trip.weight, TestConfig{}.weight);
}

TEST(ConfigSchema, RegisteringAKeyTwiceIsRejected) {
    ConfigSchema<ThreadsConfig> schema;
    schema.field("pin", &ThreadsConfig::pin);
    EXPECT_THROW(schema.field("pin", &ThreadsConfig::pin), ConfigError);
}

}  // namespace
}  // namespace scantling::io
