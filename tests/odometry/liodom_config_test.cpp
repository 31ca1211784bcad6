// Config files: presets and overrides from YAML, errors naming file, line and key.
#include <gtest/gtest.h>

#include <unistd.h>
#include <filesystem>
#include <fstream>

#include <scantling/core/error.hpp>
#include <scantling/odometry/liodom.hpp>

namespace scantling::odometry {
namespace {

namespace fs = std::filesystem;

fs::path write_temp(const std::string& name, const std::string& text) {
    const fs::path dir =
        fs::temp_directory_path() / ("scantling_liodom_config_" + std::to_string(::getpid()));
    fs::create_directories(dir);
    const fs::path p = dir / name;
    std::ofstream(p) << text;
    return p;
}

TEST(LiodomConfigFile, PresetPlusOverrides) {
    const auto p = write_temp("a.yaml",
                              "preset: confined\nfeatures:\n  max_range_m: 12.5\nlocal_map:\n  "
                              "num_recent_sweeps: 2\n");
    const LiodomConfig c = load_liodom_config(p.string());
    EXPECT_DOUBLE_EQ(c.features.max_range_m, 12.5);
    EXPECT_EQ(c.local_map.num_recent_sweeps, 2);
    // Everything else is the confined preset.
    EXPECT_DOUBLE_EQ(c.map.cell_size_xy_m, liodom_preset("confined").map.cell_size_xy_m);
}

TEST(LiodomConfigFile, PlanarPointsAndRefitAreKeysAndOneThreadCountSetsAllThree) {
    const auto p = write_temp("e.yaml",
                              "preset: confined\nfeatures:\n  max_planes_per_sector: 3\n"
                              "registration:\n  refit_distance_m: 0.02\n  plane_eigen_ratio: 4\n");
    LiodomConfig c = load_liodom_config(p.string());
    EXPECT_EQ(c.features.max_planes_per_sector, 3);
    EXPECT_DOUBLE_EQ(c.registration.refit_distance_m, 0.02);
    EXPECT_DOUBLE_EQ(c.registration.plane_eigen_ratio, 4.0);
    // The library default is LiODOM's edges-only method; the kitti preset adds planar points.
    EXPECT_EQ(LiodomConfig{}.features.max_planes_per_sector, 0);
    EXPECT_DOUBLE_EQ(LiodomConfig{}.registration.refit_distance_m, 0.0);
    EXPECT_GT(liodom_preset("kitti").features.max_planes_per_sector, 0);
    c.set_num_threads(1);
    EXPECT_EQ(c.parallel.num_threads, 1);
    EXPECT_EQ(c.features.parallel.num_threads, 1);
    EXPECT_EQ(c.registration.parallel.num_threads, 1);
    const auto bad = write_temp("f.yaml", "registration:\n  refit_distance_m: -1\n");
    EXPECT_THROW(load_liodom_config(bad.string()), Error);
    const auto flat = write_temp("g.yaml", "registration:\n  plane_eigen_ratio: 0.5\n");
    EXPECT_THROW(load_liodom_config(flat.string()), Error);
    const auto recent = write_temp("h.yaml", "plane_recent_sweeps: 2\n");
    EXPECT_EQ(load_liodom_config(recent.string()).plane_recent_sweeps, 2);
    c.plane_recent_sweeps = -1;
    EXPECT_THROW(c.validate(), ConfigError);
    fs::remove_all(p.parent_path());
}

TEST(LiodomConfigFile, ErrorsNameFileLineAndKey) {
    const auto unknown = write_temp("b.yaml", "features:\n  max_rnge_m: 3\n");
    try {
        load_liodom_config(unknown.string());
        FAIL();
    } catch (const ParseError& e) {
        const std::string what = e.what();
        EXPECT_NE(what.find("b.yaml"), std::string::npos) << what;
        EXPECT_NE(what.find("line 2"), std::string::npos) << what;
        EXPECT_NE(what.find("features.max_rnge_m"), std::string::npos) << what;
    }
    const auto bad_preset = write_temp("c.yaml", "preset: lidar9000\n");
    EXPECT_THROW(load_liodom_config(bad_preset.string()), ParseError);
    const auto impossible =
        write_temp("d.yaml", "features:\n  min_range_m: 50\n  max_range_m: 10\n");
    try {
        load_liodom_config(impossible.string());
        FAIL();
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("d.yaml"), std::string::npos) << e.what();
    }
    EXPECT_THROW(load_liodom_config("/nonexistent/odometry.yaml"), FileError);
    fs::remove_all(unknown.parent_path());
}

}  // namespace
}  // namespace scantling::odometry
