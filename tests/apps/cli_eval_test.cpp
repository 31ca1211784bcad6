// `scantling eval`: metrics of synthetic trajectories with known error (KITTI and TUM files),
// SiMpLE's published KITTI figure from the real files, the plots, --json, and bad input failing
// with one line and nothing written.
#include "cli_fixture.hpp"

#include <Eigen/Geometry>
#include <cmath>
#include <regex>
#include <string>
#include <vector>

#include <scantling/io/kitti.hpp>
#include <scantling/io/tum.hpp>

namespace scantling::cli_test {
namespace {

/// "key: 1.2345" (text) or "\"key\": 1.2345" (JSON) → 1.2345; NaN when absent or not a number.
double value_of(const std::string& text, const std::string& key) {
    std::smatch m;
    const std::regex pattern("\"?" + key + "\"?: (-?[0-9.eE+-]+)");
    return std::regex_search(text, m, pattern) ? std::stod(m[1]) : std::nan("");
}

/// A 300 m drive (1 m a frame) with a gentle weave, in the KITTI camera frame (x right, z ahead).
std::vector<Eigen::Isometry3d> drive(int num_frames) {
    std::vector<Eigen::Isometry3d> poses;
    for (int i = 0; i < num_frames; ++i) {
        Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
        T.translation() = Eigen::Vector3d(5.0 * std::sin(i / 80.0), 0.2 * std::sin(i / 25.0), i);
        poses.push_back(T);
    }
    return poses;
}

/// The same path with every step 1 % longer: 1 % scale drift.
std::vector<Eigen::Isometry3d> scaled(const std::vector<Eigen::Isometry3d>& gt, double scale) {
    std::vector<Eigen::Isometry3d> est = gt;
    for (Eigen::Isometry3d& T : est) T.translation() *= scale;
    return est;
}

class CliEval : public Cli {
  protected:
    void write_kitti_pair(int num_frames = 300) {
        const auto gt = drive(num_frames);
        io::write_kitti_poses(path("gt.txt"), gt);
        io::write_kitti_poses(path("est.txt"), scaled(gt, 1.01));
    }

    /// Ground truth at 100 Hz, estimates at 10 Hz 5 ms later, both on the same 30 m path.
    void write_tum_pair() {
        std::vector<io::StampedPose> gt, est;
        auto at = [](double t) {
            io::StampedPose p;
            p.stamp_s = t;
            p.T_world_body.translation() = Eigen::Vector3d(3.0 * t, std::sin(t), 1.0);
            p.T_world_body.linear() = Eigen::AngleAxisd(0.1 * t, Eigen::Vector3d::UnitZ()).matrix();
            return p;
        };
        for (int i = 0; i <= 1000; ++i) gt.push_back(at(0.01 * i));
        for (int i = 0; i < 100; ++i) est.push_back(at(0.1 * i + 0.005));
        est.push_back(at(30.0));  // no ground truth there: unmatched
        io::write_tum(path("gt.tum"), gt);
        io::write_tum(path("est.tum"), est);
    }
};

TEST_F(CliEval, KittiFilesWithOnePercentScaleDriftReportOnePercentAndWritePlotsBesideEst) {
    write_kitti_pair();
    const CliRun r =
        run("eval --gt " + quoted(path("gt.txt")) + " --est " + quoted(path("est.txt")));
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_EQ(r.err, "");
    EXPECT_NE(r.out.find("format: kitti\n"), std::string::npos) << r.out;
    EXPECT_EQ(value_of(r.out, "num_poses"), 300.0);
    // Segments end at most one frame beyond their 100–200 m length: 1 % × (L + ~1) / L.
    EXPECT_GT(value_of(r.out, "rte_percent"), 0.99);
    EXPECT_LT(value_of(r.out, "rte_percent"), 1.02);
    EXPECT_LT(value_of(r.out, "rre_deg_per_100m"), 1e-3);
    EXPECT_GT(value_of(r.out, "ate_rmse_m"), 0.1);  // a scaled path cannot be aligned away
    EXPECT_NEAR(value_of(r.out, "rpe_10m_trans_mean_m"), 0.1, 0.01);  // 1 % of ~10 m
    EXPECT_NE(r.out.find("kitti_100m: "), std::string::npos);
    EXPECT_NE(r.out.find("plot_top: " + path("est_top.svg")), std::string::npos);
    expect_files({"gt.txt", "est.txt", "est_top.svg", "est_errors.svg"});
    const std::string top = read_text(path("est_top.svg"));
    EXPECT_EQ(top.rfind("<?xml", 0), 0u);
    EXPECT_NE(top.find(">ground truth</text>"), std::string::npos);
    EXPECT_NE(top.find(">x [m]</text>"), std::string::npos);  // KITTI's ground plane: x–z
    EXPECT_NE(top.find(">z [m]</text>"), std::string::npos);
    EXPECT_NE(read_text(path("est_errors.svg")).find("<polyline"), std::string::npos);
}

TEST_F(CliEval, TumFilesAreMatchedByTimeAndShortPathsSayNotAvailable) {
    write_tum_pair();
    const CliRun r = run("eval --gt " + quoted(path("gt.tum")) + " --est " +
                         quoted(path("est.tum")) + " --plots " + quoted(path("plots")));
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_NE(r.out.find("format: tum\n"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("matched: 100 of 101 estimated poses"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("rte_percent: n/a (path shorter than 100 m)"), std::string::npos);
    // The estimate is the truth at its own stamp; interpolating the ground truth recovers it to
    // the curvature of the path over 10 ms (~1e-5 m).
    EXPECT_LT(value_of(r.out, "ate_rmse_m"), 1e-3);
    EXPECT_LT(value_of(r.out, "rpe_10m_trans_rmse_m"), 1e-3);
    expect_files({"gt.tum", "est.tum", "plots"});
    EXPECT_TRUE(fs::exists(path("plots/est_top.svg")));
    EXPECT_TRUE(fs::exists(path("plots/est_errors.svg")));
}

TEST_F(CliEval, JsonIsOneObjectWithNullWhereAMetricIsNotAvailable) {
    write_tum_pair();
    const CliRun r = run("eval --gt " + quoted(path("gt.tum")) + " --est " +
                         quoted(path("est.tum")) + " --json --no-plots");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    ASSERT_FALSE(r.out.empty());
    EXPECT_EQ(r.out.front(), '{');
    EXPECT_EQ(r.out.substr(r.out.size() - 2), "}\n");
    EXPECT_NE(r.out.find("\"rte_percent\": null"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("\"plots\": null"), std::string::npos);
    EXPECT_EQ(value_of(r.out, "num_poses"), 100.0);
    EXPECT_LT(value_of(r.out, "ate_rmse_m"), 1e-3);
    expect_files({"gt.tum", "est.tum"});
}

TEST_F(CliEval, ReproducesSimplesPublishedFigureOnKitti05) {
    const std::string dir = std::string(SCANTLING_SHARED_DATA_DIR) + "/kitti-poses";
    if (!fs::exists(dir + "/groundtruth/05.txt")) {
        GTEST_SKIP() << "shared data not found: " << dir << " (set SCANTLING_SHARED_DATA_DIR)";
    }
    const CliRun r =
        run("eval --gt " + quoted(dir + "/groundtruth/05.txt") + " --est " +
            quoted(dir + "/simple-estimates/05.txt") + " --plots " + quoted(path("plots")));
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_NE(r.out.find("rte_percent: 0.3372\n"), std::string::npos) << r.out;
    EXPECT_EQ(value_of(r.out, "num_poses"), 2761.0);
    EXPECT_TRUE(fs::exists(path("plots/05_top.svg")));
}

TEST_F(CliEval, BadInputFailsWithOneLineAndWritesNothing) {
    write_kitti_pair();
    const std::string gt = quoted(path("gt.txt")), est = quoted(path("est.txt"));
    expect_one_error_line(run("eval --gt " + gt + " --est " + quoted(path("missing.txt"))),
                          "missing.txt");
    expect_one_error_line(run("eval --gt " + gt + " --est " + est + " --format bogus"), "bogus");
    expect_one_error_line(run("eval --gt " + gt + " --est " + est + " --max-dt -1"), "--max-dt");

    io::write_kitti_poses(path("short.txt"), drive(120));
    expect_one_error_line(run("eval --gt " + gt + " --est " + quoted(path("short.txt"))),
                          "has 300 poses but --est");

    std::ofstream(path("five.txt")) << "1 2 3 4 5\n";
    expect_one_error_line(run("eval --gt " + gt + " --est " + quoted(path("five.txt"))),
                          "5 numbers, expected 12");

    write_tum_pair();
    expect_one_error_line(run("eval --gt " + gt + " --est " + quoted(path("est.tum"))),
                          "expected the same format");

    std::ofstream(path("nan.txt")) << "1 0 0 nan 0 1 0 0 0 0 1 0\n1 0 0 1 0 1 0 0 0 0 1 0\n";
    expect_one_error_line(
        run("eval --gt " + quoted(path("nan.txt")) + " --est " + quoted(path("nan.txt"))),
        "nan.txt");

    io::StampedPose late;
    late.stamp_s = 100.0;
    std::vector<io::StampedPose> far{late};
    late.stamp_s = 101.0;
    far.push_back(late);
    io::write_tum(path("far.tum"), far);
    expect_one_error_line(
        run("eval --gt " + quoted(path("gt.tum")) + " --est " + quoted(path("far.tum"))),
        "0 of 2 estimated poses");

    // --plots names an existing file: the folder cannot be created, nothing is written.
    expect_one_error_line(run("eval --gt " + gt + " --est " + est + " --plots " + gt), "gt.txt");
    expect_files(
        {"gt.txt", "est.txt", "short.txt", "five.txt", "gt.tum", "est.tum", "nan.txt", "far.tum"});
}

}  // namespace
}  // namespace scantling::cli_test
