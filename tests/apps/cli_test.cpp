// `scantling` subcommands on good input: reports, conversions and their files.
#include "cli_fixture.hpp"

#include <fstream>
#include <limits>
#include <string>
#include <vector>

#include <scantling/core/point_cloud.hpp>
#include <scantling/io/cloud_io.hpp>
#include <scantling/io/ply.hpp>

namespace scantling::cli_test {
namespace {

/// Clouds go through float32 files: coordinates below 10 m keep ~1e-6 m.
constexpr double kFloatToleranceM = 1e-5;

TEST_F(Cli, VersionPrintsNameAndProjectVersion) {
    const CliRun result = run("--version");
    EXPECT_EQ(result.exit_code, 0);
    EXPECT_EQ(result.out, std::string("scantling ") + SCANTLING_VERSION + "\n");
}

TEST_F(Cli, HelpListsSubcommandsAndExitsZero) {
    const CliRun result = run("--help");
    EXPECT_EQ(result.exit_code, 0);
    for (const char* word : {"info", "convert", "downsample", "--threads", "--verbose"}) {
        EXPECT_NE(result.out.find(word), std::string::npos) << word;
    }
    EXPECT_EQ(run("downsample --help").exit_code, 0);
}

TEST_F(Cli, InfoOnPcdPrintsCountFieldsAndBounds) {
    scantling::io::write_cloud(path("grid.pcd"), make_grid());
    const CliRun result = run("info " + quoted(path("grid.pcd")));
    EXPECT_EQ(result.exit_code, 0) << result.err;
    EXPECT_EQ(result.out,
              "points: 100\n"
              "fields: x y z normal_x normal_y normal_z intensity\n"
              "bounds: 0.000000 0.000000 0.000000 0.900000 0.400000 0.100000\n");
    EXPECT_EQ(result.err, "");
}

TEST_F(Cli, VerboseLogsGoToStderrAndLeaveTheReportUnchanged) {
    scantling::io::write_cloud(path("grid.pcd"), make_grid());
    const CliRun quiet = run("info " + quoted(path("grid.pcd")));
    const CliRun verbose = run("info " + quoted(path("grid.pcd")) + " -v");
    EXPECT_EQ(verbose.exit_code, 0) << verbose.err;
    EXPECT_EQ(verbose.out, quiet.out);
    EXPECT_NE(verbose.err.find("debug"), std::string::npos) << verbose.err;
}

TEST_F(Cli, InfoCountsNonFinitePointsAndKeepsThemOutOfTheBounds) {
    scantling::PointCloud cloud;
    cloud.points = {
        {1.0, 2.0, 3.0}, {std::numeric_limits<double>::quiet_NaN(), 0.0, 0.0}, {-1.0, 0.5, 2.0}};
    scantling::io::write_cloud(path("nan.pcd"), cloud);
    const CliRun result = run("info " + quoted(path("nan.pcd")));
    EXPECT_EQ(result.exit_code, 0) << result.err;
    EXPECT_EQ(result.out,
              "points: 3\nfields: x y z\n"
              "bounds: -1.000000 0.500000 2.000000 1.000000 2.000000 3.000000\n"
              "non_finite: 1\n");
}

TEST_F(Cli, InfoOnPlyWithFacesPrintsAMeshReport) {
    scantling::PointCloud vertices;
    vertices.points = {{0, 0, 0}, {2, 0, 0}, {2, 1, 0}, {0, 1, 0}};
    const std::vector<Eigen::Vector3i> faces = {{0, 1, 2}, {0, 2, 3}};
    scantling::io::write_ply(path("quad.ply"), vertices, faces);
    const CliRun result = run("info " + quoted(path("quad.ply")));
    EXPECT_EQ(result.exit_code, 0) << result.err;
    EXPECT_EQ(result.out,
              "vertices: 4\ntriangles: 2\n"
              "bounds: 0.000000 0.000000 0.000000 2.000000 1.000000 0.000000\n"
              "area_m2: 2.000000\n");
}

/// Unit tetrahedron: three right triangles of 0.5 m² and one of sqrt(3) / 2 m².
const char* const kTetrahedronReport =
    "vertices: 4\ntriangles: 4\n"
    "bounds: 0.000000 0.000000 0.000000 1.000000 1.000000 1.000000\n"
    "area_m2: 2.366025\n";

TEST_F(Cli, InfoOnObjPrintsAMeshReport) {
    std::ofstream(path("tetra.obj")) << "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\n"
                                        "f 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n";
    const CliRun result = run("info " + quoted(path("tetra.obj")));
    EXPECT_EQ(result.exit_code, 0) << result.err;
    EXPECT_EQ(result.out, kTetrahedronReport);
}

TEST_F(Cli, InfoOnAsciiStlPrintsAMeshReport) {
    const std::vector<std::vector<const char*>> facets = {{"0 0 0", "0 1 0", "1 0 0"},
                                                          {"0 0 0", "1 0 0", "0 0 1"},
                                                          {"0 0 0", "0 0 1", "0 1 0"},
                                                          {"1 0 0", "0 1 0", "0 0 1"}};
    std::ofstream stl(path("tetra.stl"));
    stl << "solid tetra\n";
    for (const auto& corners : facets) {
        stl << "facet normal 0 0 0\nouter loop\n";
        for (const char* corner : corners) stl << "vertex " << corner << "\n";
        stl << "endloop\nendfacet\n";
    }
    stl << "endsolid tetra\n";
    stl.close();
    const CliRun result = run("info " + quoted(path("tetra.stl")));
    EXPECT_EQ(result.exit_code, 0) << result.err;
    EXPECT_EQ(result.out, kTetrahedronReport);
}

TEST_F(Cli, ConvertRoundTripThroughEveryFormatKeepsPoints) {
    const scantling::PointCloud original = make_grid();
    scantling::io::write_cloud(path("a.pcd"), original);
    const CliRun to_ply = run("convert " + quoted(path("a.pcd")) + " " + quoted(path("b.ply")));
    EXPECT_EQ(to_ply.exit_code, 0) << to_ply.err;
    EXPECT_EQ(to_ply.out, path("a.pcd") + ": 100 points -> " + path("b.ply") + ": 100 points\n");
    EXPECT_EQ(run("convert " + quoted(path("b.ply")) + " " + quoted(path("c.bin"))).exit_code, 0);
    EXPECT_EQ(run("convert " + quoted(path("c.bin")) + " " + quoted(path("d.pcd")) + " --ascii")
                  .exit_code,
              0);
    const scantling::PointCloud back = scantling::io::read_cloud(path("d.pcd"));
    ASSERT_EQ(back.size(), original.size());
    ASSERT_EQ(back.intensities.size(), original.size());
    for (std::size_t i = 0; i < original.size(); ++i) {
        EXPECT_LT((back.points[i] - original.points[i]).norm(), kFloatToleranceM) << i;
        EXPECT_EQ(back.intensities[i], original.intensities[i]) << i;
    }
    EXPECT_NE(read_text(path("d.pcd")).find("DATA ascii"), std::string::npos);
}

TEST_F(Cli, ConvertWithVoxelKeepsOnePointPerOccupiedVoxel) {
    // 10 × 10 points at 0.05 + 0.1 i: a 0.2 m voxel holds 2 × 2 of them, far from its faces.
    scantling::PointCloud cloud;
    for (int i = 0; i < 10; ++i) {
        for (int j = 0; j < 10; ++j)
            cloud.points.emplace_back(0.05 + 0.1 * i, 0.05 + 0.1 * j, 0.05);
    }
    scantling::io::write_cloud(path("in.pcd"), cloud);
    const CliRun result =
        run("convert " + quoted(path("in.pcd")) + " " + quoted(path("out.ply")) + " --voxel 0.2");
    EXPECT_EQ(result.exit_code, 0) << result.err;
    EXPECT_EQ(result.out, path("in.pcd") + ": 100 points -> " + path("out.ply") + ": 25 points\n");
    EXPECT_EQ(scantling::io::read_cloud(path("out.ply")).size(), 25u);
}

TEST_F(Cli, DownsampleDropsNonFinitePointsAndSaysSo) {
    scantling::PointCloud cloud;
    cloud.points = {{0.01, 0.01, 0.01},
                    {std::numeric_limits<double>::quiet_NaN(), 0.0, 0.0},
                    {0.02, 0.02, 0.02},
                    {1.01, 0.01, 0.01}};
    scantling::io::write_cloud(path("in.pcd"), cloud);
    const CliRun result = run("downsample " + quoted(path("in.pcd")) + " " +
                              quoted(path("out.pcd")) + " --voxel 0.5");
    EXPECT_EQ(result.exit_code, 0) << result.err;
    EXPECT_EQ(result.out, path("in.pcd") + ": 4 points -> " + path("out.pcd") +
                              ": 2 points (1 non-finite dropped)\n");
}

TEST_F(Cli, DownsampleGivesTheSameCloudForOneAndTwoThreads) {
    scantling::io::write_cloud(path("in.pcd"), make_grid());
    const std::string in = quoted(path("in.pcd"));
    const CliRun one =
        run("downsample " + in + " " + quoted(path("one.pcd")) + " --voxel 0.25 --threads 1");
    const CliRun two =
        run("--threads 2 downsample " + in + " " + quoted(path("two.pcd")) + " --voxel 0.25");
    EXPECT_EQ(one.exit_code, 0) << one.err;
    EXPECT_EQ(two.exit_code, 0) << two.err;
    // x: 10 points in 4 voxels, y: 5 in 2, z: 2 in 1.
    EXPECT_EQ(one.out, path("in.pcd") + ": 100 points -> " + path("one.pcd") + ": 8 points\n");
    EXPECT_EQ(read_text(path("one.pcd")), read_text(path("two.pcd")));
}

TEST_F(Cli, InfoOnRealScanAndHullMatchesTheLibrary) {
    const fs::path data = SCANTLING_SHARED_DATA_DIR;
    const fs::path scan = data / "lidar-scans" / "000000.pcd";
    const fs::path tank = data / "meshes" / "storage-tank-cylinder.stl";
    if (!fs::exists(scan) || !fs::exists(tank)) {
        GTEST_SKIP() << "real data not found under " << data
                     << " (see /work/shared/data/README.md)";
    }
    const CliRun scan_info = run("info " + quoted(scan.string()));
    EXPECT_EQ(scan_info.exit_code, 0) << scan_info.err;
    const auto expected_points = scantling::io::read_cloud(scan.string()).size();
    EXPECT_EQ(scan_info.out.rfind("points: " + std::to_string(expected_points) + "\n", 0), 0u)
        << scan_info.out;
    const CliRun tank_info = run("info " + quoted(tank.string()));
    EXPECT_EQ(tank_info.exit_code, 0) << tank_info.err;
    EXPECT_NE(tank_info.out.find("triangles: 1832\n"), std::string::npos) << tank_info.out;
}

}  // namespace
}  // namespace scantling::cli_test
