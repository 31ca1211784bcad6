// Hostile files through the CLI (issue 10): a lying header is one error line and exit 2, never
// a signal; a mesh with NaN/inf vertices is reported like a cloud; one hostile sweep in a folder
// is the per-sweep warning of `odometry`, not the end of the run.
#include <cstdio>
#include <fstream>

#include <scantling/io/kitti.hpp>
#include <scantling/io/pcd.hpp>

#include "cli_fixture.hpp"

namespace scantling::cli_test {
namespace {

/// The example of issue 10: COUNT wraps point_step to 0 (SIGFPE before the fix).
std::string wrapping_pcd() {
    return "VERSION 0.7\nFIELDS x y z foo\nSIZE 4 4 4 4\nTYPE F F F U\n"
           "COUNT 1 1 1 4611686018427387901\nWIDTH 4\nHEIGHT 1\nPOINTS 4\nDATA binary\n" +
           std::string(48, '\0');
}

TEST_F(Cli, InfoOnAPcdHeaderThatWrapsThePointStepIsOneErrorLine) {
    std::ofstream(path("a.pcd"), std::ios::binary) << wrapping_pcd();
    const CliRun result = run("info " + quoted(path("a.pcd")));
    expect_one_error_line(result, path("a.pcd") + ": line 5: field 'foo'");
}

// Before: "bounds: ... inf" and "area_m2: nan".
TEST_F(Cli, InfoOnAMeshWithNonFiniteVerticesCountsThemOutsideBoundsAndArea) {
    std::ofstream(path("tetra.ply"))
        << "ply\nformat ascii 1.0\nelement vertex 5\nproperty float x\nproperty float y\n"
           "property float z\nelement face 3\nproperty list uchar int vertex_indices\n"
           "end_header\n0 0 0\n1 0 0\n0 1 0\nnan 0 1\n0 0 inf\n3 0 1 2\n3 0 1 3\n3 0 4 2\n";
    const CliRun result = run("info " + quoted(path("tetra.ply")));
    EXPECT_EQ(result.exit_code, 0) << result.err;
    EXPECT_EQ(result.err, "");
    EXPECT_EQ(result.out,
              "vertices: 5\ntriangles: 3\n"
              "bounds: 0.000000 0.000000 0.000000 1.000000 1.000000 0.000000\n"
              "area_m2: 0.500000\nnon_finite: 2\nnon_finite_triangles: 2\n");
}

const char* const kShortFlight = R"(world: {type: ballast_tank_mockup}
vehicle:
  type: scripted
  trajectory:
    type: waypoints
    waypoints:
      yaw_mode: face_travel
      max_speed_mps: 0.5
      waypoints:
        - {position_m: [0.8, 1.4, 0.9]}
        - {position_m: [2.2, 1.5, 1.0]}
sensors:
  - {type: spinning_lidar, preset: os1_64, columns: 1024, rate_hz: 10}
duration_s: 1.5
export: {world: false}
)";

// Before: the hostile sweep raised SIGFPE and killed the whole run.
TEST_F(Cli, OdometryOverPcdSweepsWarnsAboutAHostileSweepAndGoesOn) {
    std::ofstream(path("s.yaml")) << kShortFlight;
    const CliRun sim =
        run("sim " + quoted(path("s.yaml")) + " --out " + quoted(path("rec")) + " --no-progress");
    ASSERT_EQ(sim.exit_code, 0) << sim.err;
    fs::create_directories(path("scans"));
    constexpr int kSweeps = 10;
    constexpr int kHostile = 6;
    for (int i = 0; i < kSweeps; ++i) {
        char name[32];
        std::snprintf(name, sizeof(name), "%06d", i);
        const std::string dst = path("scans/") + name + ".pcd";
        if (i == kHostile) {
            std::ofstream(dst, std::ios::binary) << wrapping_pcd();
        } else {
            io::write_pcd(dst, io::read_kitti_bin(path("rec/lidar/") + name + ".bin"));
        }
    }
    const CliRun r = run("odometry " + quoted(path("scans")) + " --out " + quoted(path("t.txt")) +
                         " --preset confined --no-progress");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_NE(r.err.find("warning: sweep 6"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("000006.pcd: line 5"), std::string::npos) << r.err;
    EXPECT_NE(r.out.find("status_unreadable: 1"), std::string::npos) << r.out;
}

}  // namespace
}  // namespace scantling::cli_test
