// No silent wrong answer from the CLI: a registration that did not converge writes nothing and
// says why, a trajectory evaluated against itself prints exact zeros, out-of-range numbers are
// refused naming the option, and no byte from a file reaches the terminal as an escape.
#include <fmt/format.h>

#include <Eigen/Geometry>
#include <cmath>
#include <fstream>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include <scantling/core/point_cloud.hpp>
#include <scantling/io/cloud_io.hpp>

#include "cli_fixture.hpp"

namespace scantling::cli_test {
namespace {

/// Uniform random points on the rectangle spanned from `origin` by `u` and `v`.
void add_rectangle(PointCloud& cloud, const Eigen::Vector3d& origin, const Eigen::Vector3d& u,
                   const Eigen::Vector3d& v, int count, std::mt19937& rng) {
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    for (int i = 0; i < count; ++i) cloud.points.push_back(origin + unit(rng) * u + unit(rng) * v);
}

/// A 4 × 3 × 2.5 m room with a box in one corner, moved by `offset`.
PointCloud make_room(unsigned seed, const Eigen::Vector3d& offset) {
    std::mt19937 rng(seed);
    PointCloud room;
    const Eigen::Vector3d o = offset, x(4, 0, 0), y(0, 3, 0), z(0, 0, 2.5);
    add_rectangle(room, o, x, y, 3000, rng);
    add_rectangle(room, o + z, x, y, 3000, rng);
    add_rectangle(room, o, x, z, 2000, rng);
    add_rectangle(room, o + y, x, z, 2000, rng);
    add_rectangle(room, o, y, z, 1500, rng);
    add_rectangle(room, o + x, y, z, 1500, rng);
    add_rectangle(room, o + Eigen::Vector3d(0.5, 0.4, 1.0), {0.8, 0, 0}, {0, 0.6, 0}, 300, rng);
    add_rectangle(room, o + Eigen::Vector3d(0.5, 0.4, 0.0), {0.8, 0, 0}, {0, 0, 1.0}, 300, rng);
    return room;
}

/// Points uniform in a 2 m cube: nothing in them matches a room.
PointCloud make_noise(unsigned seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> coordinate(-1.0, 1.0);
    PointCloud cloud;
    for (int i = 0; i < 2000; ++i) {
        cloud.points.emplace_back(coordinate(rng), coordinate(rng), coordinate(rng));
    }
    return cloud;
}

/// The number after "key:" on its own line of `text` (NaN when absent).
double value_of(const std::string& text, const std::string& key) {
    const std::size_t at = text.find("\n" + key + ":");
    if (at == std::string::npos) return std::nan("");
    return std::stod(text.substr(at + key.size() + 2));
}

class CliWrongAnswer : public Cli {
  protected:
    CliRun run_register(const std::string& source, const std::string& method) const {
        return run("register " + quoted(path(source)) + " " + quoted(path("target.pcd")) +
                   " --method " + method + " --out " + quoted(path("T.txt")));
    }
    /// A KITTI pose file as a "%.6f" writer leaves it: rotations orthonormal only to ~1e-6.
    void write_rounded_kitti_poses(const std::string& name) const {
        std::ofstream out(path(name));
        for (int i = 0; i < 300; ++i) {
            const double s = 2.0 * i;
            const Eigen::Matrix3d R =
                (Eigen::AngleAxisd(0.004 * s, Eigen::Vector3d::UnitY()) *
                 Eigen::AngleAxisd(0.05 * std::sin(s / 70.0), Eigen::Vector3d::UnitX()))
                    .toRotationMatrix();
            const Eigen::Vector3d t(20.0 * std::sin(s / 150.0), 0.5 * std::sin(s / 30.0), s);
            for (int r = 0; r < 3; ++r) {
                out << fmt::format("{:.6f} {:.6f} {:.6f} {:.6f}{}", R(r, 0), R(r, 1), R(r, 2), t(r),
                                   r < 2 ? " " : "\n");
            }
        }
    }
};

TEST_F(CliWrongAnswer, LocalRegistrationThatDidNotConvergeWritesNothingAndSaysWhy) {
    io::write_cloud(path("target.pcd"), make_room(1, Eigen::Vector3d::Zero()));
    // 100 m away: no source point has a target point within reach, so no step can be taken.
    io::write_cloud(path("far.pcd"), make_room(2, Eigen::Vector3d(100, 0, 0)));
    for (const std::string method : {"icp", "p2plane", "gicp", "stein"}) {
        const CliRun r = run_register("far.pcd", method);
        expect_one_error_line(r, "--method " + method + ": did not converge");
        EXPECT_NE(r.err.find("fitness"), std::string::npos) << r.err;
        EXPECT_NE(r.err.find("--max-distance"), std::string::npos) << r.err;  // what to try
        EXPECT_NE(r.err.find("T.txt was not written"), std::string::npos) << r.err;
        expect_files({"target.pcd", "far.pcd"});
    }
}

TEST_F(CliWrongAnswer, GlobalRegistrationOfUnrelatedCloudsWritesNothing) {
    io::write_cloud(path("target.pcd"), make_room(1, Eigen::Vector3d::Zero()));
    io::write_cloud(path("noise.pcd"), make_noise(3));
    for (const std::string method : {"fpfh-teaser", "fpfh-ransac"}) {
        const CliRun r = run_register("noise.pcd", method);
        expect_one_error_line(r, "--method " + method + ": did not converge");
        EXPECT_NE(r.err.find("overlap"), std::string::npos) << r.err;
        expect_files({"target.pcd", "noise.pcd"});
    }
}

TEST_F(CliWrongAnswer, EvalOfRoundedKittiPosesAgainstThemselvesPrintsExactZeros) {
    write_rounded_kitti_poses("poses.txt");
    const std::string args =
        "eval --gt " + quoted(path("poses.txt")) + " --est " + quoted(path("poses.txt"));
    const CliRun text = run(args + " --no-plots");
    ASSERT_EQ(text.exit_code, 0) << text.err;
    ASSERT_GT(value_of(text.out, "kitti_segments"), 0.0) << text.out;
    for (const char* key : {"rte_percent", "rre_deg_per_100m", "ate_rmse_m", "ate_max_m",
                            "rpe_10m_trans_rmse_m", "rpe_10m_rot_mean_deg"}) {
        EXPECT_EQ(value_of(text.out, key), 0.0) << key << "\n" << text.out;
    }
    const CliRun json = run(args + " --no-plots --json");
    ASSERT_EQ(json.exit_code, 0) << json.err;
    for (const char* key : {"\"rre_deg_per_100m\": 0.0,", "\"ate_rmse_m\": 0.0,",
                            "\"ate_max_m\": 0.0,", "\"rpe_10m_rot_mean_deg\": 0.0,"}) {
        EXPECT_NE(json.out.find(key), std::string::npos) << key << "\n" << json.out;
    }
}

TEST_F(CliWrongAnswer, IntegersOutOfRangeAreRefusedNamingTheOption) {
    const std::string missing = quoted(path("missing"));
    // Checked while parsing: the option is named before any file is looked at.
    expect_one_error_line(run("sim " + missing + " --out " + missing + " --seed -1"), "--seed");
    expect_one_error_line(
        run("sim " + missing + " --out " + missing + " --seed 99999999999999999999999"), "--seed");
    expect_one_error_line(run("odometry " + missing + " --out " + missing + " --max-frames -1"),
                          "--max-frames");
    expect_one_error_line(run("odometry " + missing + " --out " + missing + " --max-frames 0"),
                          "--max-frames");
    expect_one_error_line(run("info " + missing + " --threads -5"), "--threads");
    expect_one_error_line(run("--threads 99999999999 info " + missing), "--threads");
    expect_one_error_line(run("info " + missing + " --threads 0x10"), "--threads");
    expect_one_error_line(run("info " + missing + " --threads 2.5"), "--threads");
    expect_files({});
}

TEST_F(CliWrongAnswer, NonFiniteOrNegativeRealsAreRefusedNamingTheOption) {
    const std::string missing = quoted(path("missing"));
    expect_one_error_line(run("odometry " + missing + " --out " + missing + " --period nan"),
                          "--period");
    expect_one_error_line(run("odometry " + missing + " --out " + missing + " --period -0.1"),
                          "--period");
    expect_one_error_line(run("eval --gt " + missing + " --est " + missing + " --max-dt inf"),
                          "--max-dt");
    const std::string reg = "register " + missing + " " + missing + " --out " + missing;
    expect_one_error_line(run(reg + " --method icp --max-distance nan"), "--max-distance");
    expect_one_error_line(run(reg + " --method icp --voxel inf"), "--voxel");
    expect_one_error_line(run("convert " + missing + " " + missing + " --voxel 0x1p-3"), "--voxel");
    expect_files({});
}

TEST_F(CliWrongAnswer, BytesFromFilesReachTheTerminalEscaped) {
    // A header token that clears the screen, quoted by the error message.
    std::ofstream(path("clear.pcd")) << "VERSION 0.7\nFIELDS x y z\nSIZE 4 4 4\n"
                                        "TYPE F F \x1b[2J\nCOUNT 1 1 1\nWIDTH 1\nHEIGHT 1\n"
                                        "POINTS 1\nDATA ascii\n1 2 3\n";
    const CliRun header = run("info " + quoted(path("clear.pcd")));
    expect_one_error_line(header, "\\x1b[2J");
    EXPECT_EQ(header.err.find('\x1b'), std::string::npos) << header.err;
    // A file name that retitles the terminal window.
    const std::string retitle = path("a\x1b]0;owned\x07.pcd");
    const CliRun name = run("info " + quoted(retitle));
    expect_one_error_line(name, "a\\x1b]0;owned\\x07.pcd");
    EXPECT_EQ(name.err.find('\x1b'), std::string::npos) << name.err;
    // Reports on stdout quote file names too (eval prints the paths of its plots).
    write_rounded_kitti_poses("poses.txt");
    const std::string est = path("est\x1b[2J.txt");
    fs::copy_file(path("poses.txt"), est);
    const CliRun report = run("eval --gt " + quoted(path("poses.txt")) + " --est " + quoted(est));
    ASSERT_EQ(report.exit_code, 0) << report.err;
    EXPECT_NE(report.out.find("est\\x1b[2J_top.svg"), std::string::npos) << report.out;
    EXPECT_EQ(report.out.find('\x1b'), std::string::npos) << report.out;
    EXPECT_EQ(report.err, "");
}

TEST_F(CliWrongAnswer, SuccessfulRunsPrintNothingOnStderr) {
    // Meshes go through assimp, whose logger must stay silent.
    std::ofstream(path("tri.obj")) << "v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 1\nf 1//1 2//1 3//1\n";
    std::ofstream(path("tri.stl")) << "solid t\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\n"
                                      "vertex 1 0 0\nvertex 0 1 0\nendloop\nendfacet\nendsolid t\n";
    for (const char* mesh : {"tri.obj", "tri.stl"}) {
        const CliRun r = run("info " + quoted(path(mesh)));
        EXPECT_EQ(r.exit_code, 0) << mesh << ": " << r.err;
        EXPECT_EQ(r.err, "") << mesh;
    }
    io::write_cloud(path("target.pcd"), make_room(1, Eigen::Vector3d::Zero()));
    io::write_cloud(path("source.pcd"), make_room(2, Eigen::Vector3d(0.05, -0.03, 0.0)));
    const CliRun r = run_register("source.pcd", "p2plane");
    EXPECT_EQ(r.exit_code, 0) << r.err;
    EXPECT_EQ(r.err, "");
}

}  // namespace
}  // namespace scantling::cli_test
