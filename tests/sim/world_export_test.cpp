#include <scantling/core/error.hpp>
#include <scantling/io/mesh_io.hpp>
#include <scantling/io/ply.hpp>
#include <scantling/io/structural_map.hpp>
#include <scantling/sim/world_builders.hpp>
#include <scantling/sim/world_export.hpp>

#include <gtest/gtest.h>
#include <unistd.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

namespace scantling::sim {
namespace {

namespace fs = std::filesystem;

// A fresh directory under the system temp dir, removed at the end of the test.
class TempDir {
  public:
    TempDir() {
        const auto* test = ::testing::UnitTest::GetInstance()->current_test_info();
        path_ = fs::temp_directory_path() /
                (std::string("scantling_sim_") + test->name() + "_" + std::to_string(getpid()));
        fs::remove_all(path_);
    }
    ~TempDir() { fs::remove_all(path_); }
    const fs::path& path() const { return path_; }

  private:
    fs::path path_;
};

nlohmann::json read_json(const fs::path& path) {
    std::ifstream in(path);
    std::stringstream text;
    text << in.rdbuf();
    return nlohmann::json::parse(text.str());
}

TEST(WorldExport, MetadataJsonListsEverythingAndReadsBackExactly) {
    const World world = build_ballast_tank_mockup();
    const std::string text = io::structural_map_to_json(world.metadata, world.surface_tags);
    EXPECT_EQ(text,
              io::structural_map_to_json(world.metadata, world.surface_tags));  // deterministic
    const nlohmann::json j = nlohmann::json::parse(text);
    EXPECT_EQ(j["name"], "ballast_tank_mockup");
    EXPECT_EQ(j["compartments"].size(), 2u);
    EXPECT_EQ(j["connections"][0]["kind"], "manhole");
    EXPECT_EQ(j["connections"][1]["compartment_b"], -1);
    EXPECT_EQ(j["frames"].size(), 3u);
    EXPECT_EQ(j["longitudinals"].size(), 13u);
    EXPECT_EQ(j["landmarks"].size(), world.metadata.landmarks.size());
    EXPECT_EQ(j["landmarks"][0]["kind"], "frame_longitudinal");
    ASSERT_EQ(j["defects"].size(), 4u);
    const Defect& d = world.metadata.defects[2];
    EXPECT_EQ(j["defects"][2]["centre"][0].get<double>(), d.centre.x());  // bit-exact
    EXPECT_EQ(j["defects"][2]["radius_m"].get<double>(), d.radius_m);
    EXPECT_EQ(j["defects"][2]["kind"], std::string(to_string(d.kind)));
    std::size_t tagged = 0;
    for (const auto& run : j["triangle_surface_tags"]) tagged += run[1].get<std::size_t>();
    EXPECT_EQ(tagged, world.mesh.num_triangles());
    EXPECT_EQ(j["surfaces"][j["triangle_surface_tags"][0][0].get<int>()]["name"], "bottom");
    EXPECT_FALSE(nlohmann::json::parse(io::structural_map_to_json(world.metadata))
                     .contains("triangle_surface_tags"));
}

TEST(WorldExport, WritesMapMeshAndMetadataIntoADirectory) {
    const TempDir dir;
    const World world = build_ballast_tank_mockup();
    WorldExportConfig config;
    config.map_spacing_m = 0.1;
    write_world((dir.path() / "world").string(), world, config);
    const io::PlyData map = io::read_ply((dir.path() / "world" / "map.ply").string());
    const double expected = surface_area(world.mesh) / (0.1 * 0.1);
    EXPECT_NEAR(static_cast<double>(map.cloud.size()), expected, 1.0);
    ASSERT_TRUE(map.cloud.has_normals());
    for (std::size_t i = 0; i < map.cloud.size(); i += 97) {
        EXPECT_NEAR(map.cloud.normals[i].norm(), 1.0, 1e-6);  // stored as float
        EXPECT_TRUE(map.cloud.points[i].x() >= -1e-6 && map.cloud.points[i].x() <= 5.3 + 1e-6);
    }
    const TriangleMesh mesh = io::read_mesh((dir.path() / "world" / "mesh.ply").string());
    EXPECT_EQ(mesh.num_triangles(), world.mesh.num_triangles());
    const nlohmann::json j = read_json(dir.path() / "world" / "metadata.json");
    EXPECT_EQ(j["landmarks"].size(), world.metadata.landmarks.size());
}

TEST(WorldExport, ExportedMetadataReadsBackAsTheSameStructuralMap) {
    const TempDir dir;
    const World world = build_ballast_tank_mockup();
    write_world((dir.path() / "world").string(), world, {.map_spacing_m = 0.1});
    const io::StructuralMap map =
        io::read_structural_map((dir.path() / "world" / "metadata.json").string());
    EXPECT_EQ(map, world.metadata);
    // The mock-up's layout, as the localisation will query it.
    ASSERT_EQ(map.compartments.size(), 2u);
    EXPECT_EQ(io::compartment_at(map, {1.0, 1.5, 0.9}), 0);
    EXPECT_EQ(io::compartment_at(map, {4.0, 1.5, 0.9}), 1);
    EXPECT_EQ(io::nearest_frame(map, {2.5, 2.1, 0.85}), 1);  // at the web frame's manhole
    EXPECT_EQ(map.defects, world.metadata.defects);
}

TEST(WorldExport, MapSamplingIsDeterministicPerSeed) {
    const World world = build_cylinder();
    const PointCloud a = sample_map(world, 0.05, 3);
    const PointCloud b = sample_map(world, 0.05, 3);
    const PointCloud c = sample_map(world, 0.05, 4);
    ASSERT_EQ(a.size(), b.size());
    EXPECT_EQ(a.points[10], b.points[10]);
    EXPECT_NE(a.points[10], c.points[10]);
}

TEST(WorldExport, RejectsBadSpacingAndUnwritableDirectories) {
    const World world = build_plate();
    const TempDir dir;
    EXPECT_THROW(write_world(dir.path().string(), world, {.map_spacing_m = 0.0}), ConfigError);
    fs::create_directories(dir.path());
    std::ofstream(dir.path() / "file") << "x";
    EXPECT_THROW(write_world((dir.path() / "file" / "world").string(), world), FileError);
    World broken = world;
    broken.surface_tags.pop_back();
    EXPECT_THROW(write_world((dir.path() / "w").string(), broken), InputError);
}

}  // namespace
}  // namespace scantling::sim
