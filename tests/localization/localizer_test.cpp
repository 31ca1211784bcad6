// The Localizer on a simulated flight through the ballast-tank mock-up (scenarios/
// ballast_mockup_l515.yaml: L515-class depth at 10 Hz, IMU, VIO), against its ground truth. The
// recording is made by the ctest fixture localization.simulate_mockup (tests/CMakeLists.txt).
#include <gtest/gtest.h>

#include <filesystem>
#include <functional>
#include <map>

#include <scantling/core/error.hpp>
#include <scantling/io/cloud_io.hpp>
#include <scantling/io/recording.hpp>
#include <scantling/io/structural_map.hpp>
#include <scantling/localization/localizer.hpp>

#include "recorded_truth.hpp"

namespace scantling::localization {
namespace {

namespace fs = std::filesystem;

class LocalizerTest : public ::testing::Test {
  protected:
    static void SetUpTestSuite() {
        dir_ = fs::temp_directory_path() / fmt_name();
        fs::remove_all(dir_);
        fs::create_directories(dir_);
        if (!fs::exists(fs::path(SCANTLING_LOCALIZATION_RECORDING) / "groundtruth.tum")) return;
        recording_ = new io::Recording(io::open_recording(SCANTLING_LOCALIZATION_RECORDING));
        map_ = std::make_shared<const LocalizationMap>(LocalizationMap::build(
            io::read_cloud(recording_->world_map_path()),
            io::read_structural_map(recording_->world_metadata_path()), LocalizationMapConfig{},
            // Each test runs in its own process: the descriptors are computed once, by the first.
            recording_->world_map_path() + ".fpfh"));
    }
    void SetUp() override {
        if (recording_ == nullptr) {
            GTEST_SKIP() << SCANTLING_LOCALIZATION_RECORDING
                         << " is missing: run the tests through ctest, whose fixture "
                            "localization.simulate_mockup simulates it";
        }
    }
    static void TearDownTestSuite() {
        delete recording_;
        recording_ = nullptr;
        map_.reset();
        fs::remove_all(dir_);
    }
    static std::string fmt_name() {
        return "scantling_localizer_test_" + std::to_string(::getpid());
    }

    struct Result {
        std::vector<FusedState> fused;
        std::vector<FrameEvent> events;
        std::vector<LocalizerWarning> warnings;
    };

    /// Feeds the recording in time order (frames `latency_s` after capture).
    static Result run(
        const LocalizerConfig& config, bool known_start, std::size_t max_frames = 1000,
        double latency_s = 0.1, const std::function<void(PointCloud&)>& edit = [](PointCloud&) {},
        const std::function<void(io::VioRecord&)>& edit_vio = [](io::VioRecord&) {}) {
        Localizer localizer(map_, config);
        const io::Recording& r = *recording_;
        if (known_start) {
            localizer.set_initial_pose({r.vio().front().stamp_s, truth_at(r.vio().front().stamp_s),
                                        Matrix6d::Identity() * 1e-3});
        }
        const Eigen::Isometry3d T_bs = *r.depth_T_body_sensor();
        std::size_t imu = 0, frame = 0;
        const std::size_t frames = std::min(max_frames, r.num_depth_frames());
        Result out;
        for (io::VioRecord v : r.vio()) {
            edit_vio(v);
            for (; imu < r.imu().size() && r.imu()[imu].stamp_s <= v.stamp_s; ++imu) {
                localizer.add_imu(r.imu()[imu]);
            }
            for (; frame < frames && r.depth_frames().stamps_s[frame] + latency_s <= v.stamp_s;
                 ++frame) {
                PointCloud cloud = r.read_depth_frame(frame);
                edit(cloud);
                localizer.add_depth_frame(frame, std::move(cloud), T_bs);
            }
            if (auto s = localizer.add_vio(v)) out.fused.push_back(*s);
        }
        localizer.finish();
        out.events = localizer.take_events();
        out.warnings = localizer.take_warnings();
        return out;
    }

    static Eigen::Isometry3d truth_at(double t) {
        return test::truth_at(recording_->ground_truth(), t);
    }

    static double mean_error(const std::vector<FusedState>& fused) {
        double sum = 0.0;
        for (const FusedState& s : fused) {
            sum += (s.T_world_body.translation() - truth_at(s.stamp_s).translation()).norm();
        }
        return fused.empty() ? INFINITY : sum / static_cast<double>(fused.size());
    }

    static std::map<std::string, int> gates(const std::vector<FrameEvent>& events) {
        std::map<std::string, int> out;
        for (const FrameEvent& e : events) {
            ++out[e.gate.empty() ? std::string(to_string(e.outcome)) : e.gate];
        }
        return out;
    }

    static inline fs::path dir_;
    static inline io::Recording* recording_ = nullptr;
    static inline std::shared_ptr<const LocalizationMap> map_;
};

TEST_F(LocalizerTest, TracksFromAKnownStartWithinCentimetres) {
    for (const FilterKind kind : {FilterKind::kEkf, FilterKind::kUkf}) {
        LocalizerConfig config;
        config.filter.kind = kind;
        const Result r = run(config, true);
        const auto counts = gates(r.events);
        EXPECT_GE(counts.count("registered") ? counts.at("registered") : 0,
                  static_cast<int>(0.9 * r.events.size()))
            << to_string(kind);
        EXPECT_LT(mean_error(r.fused), 0.02) << to_string(kind);
        for (const FusedState& s : r.fused) ASSERT_TRUE(s.covariance.allFinite());
    }
}

TEST_F(LocalizerTest, VioVelocityAloneTracksAndIgnoresTheVioPoseResets) {
    // The VIO's pose resets by 1 m at 5 s (a loop closure, a restart): the pose input sees a jump
    // and must re-localise; the velocity input never reads the pose.
    const auto reset = [](io::VioRecord& v) {
        if (v.stamp_s > 5.0) v.T_odom_body.translation() += Eigen::Vector3d(1.0, 0.0, 0.0);
    };
    LocalizerConfig config;
    config.odometry_input = OdometryInput::kVelocity;
    const Result velocity = run(
        config, true, 1000, 0.1, [](PointCloud&) {}, reset);
    EXPECT_LT(mean_error(velocity.fused), 0.02);
    EXPECT_TRUE(velocity.warnings.empty()) << velocity.warnings.front().message;
    const Result pose = run(
        LocalizerConfig{}, true, 1000, 0.1, [](PointCloud&) {}, reset);
    ASSERT_FALSE(pose.warnings.empty());
    EXPECT_NE(pose.warnings.front().message.find("jump"), std::string::npos);
}

TEST_F(LocalizerTest, FindsItselfFromAnUnknownStartAndStaysThere) {
    const Result r = run(LocalizerConfig{}, false);
    ASSERT_FALSE(r.fused.empty()) << "never relocalised";
    // After the first fix every fused pose is close to the truth: no wrong bay was accepted.
    double worst = 0.0;
    for (const FusedState& s : r.fused) {
        worst = std::max(worst,
                         (s.T_world_body.translation() - truth_at(s.stamp_s).translation()).norm());
    }
    EXPECT_LT(worst, 0.1);
    EXPECT_LT(mean_error(r.fused), 0.03);
}

TEST_F(LocalizerTest, EachGateRejectsWhatItShould) {
    // Clutter the map does not hold fills a third of the voxels (a 0.8 m cube of points
    // 0.5 m in front of the camera).
    auto board = [](PointCloud& frame) {
        frame.intensities.clear();
        for (int i = 0; i < 16; ++i) {
            for (int j = 0; j < 16; ++j) {
                for (int k = 0; k < 16; ++k) {
                    frame.points.emplace_back(-0.4 + 0.05 * i, -0.4 + 0.05 * j, 0.5 + 0.05 * k);
                }
            }
        }
    };
    LocalizerConfig config;
    const auto with_board = gates(run(config, true, 20, 0.1, board).events);
    EXPECT_GE(with_board.count("overlap") ? with_board.at("overlap") : 0, config.max_rejections);

    config = LocalizerConfig{};
    config.gates.speed.max_speed_mps = 1e-4;
    EXPECT_GT(gates(run(config, true, 20).events).count("speed"), 0u);

    config = LocalizerConfig{};
    config.gates.mahalanobis_threshold = 1e-3;
    EXPECT_GT(gates(run(config, true, 20).events).count("mahalanobis"), 0u);

    config = LocalizerConfig{};
    config.gates.attitude.max_difference_rad = 1e-5;
    EXPECT_GT(gates(run(config, true, 20).events).count("attitude"), 0u);
}

TEST_F(LocalizerTest, RestartsAfterRejectionsAndHonoursTheRegistrationRate) {
    LocalizerConfig config;
    config.registration_period_s = 1.0;  // at most one registration per second
    const Result r = run(config, true);
    const auto counts = gates(r.events);
    EXPECT_GT(counts.at("rate"), static_cast<int>(0.8 * r.events.size()));
    EXPECT_LT(mean_error(r.fused), 0.03);
}

TEST_F(LocalizerTest, ReLocalisesNearThePredictionAfterAVioDropoutAndJump) {
    // The VIO loses tracking for 1.5 s and holds its last pose (as a T265 does), then resumes
    // where its drifting estimate has got to: a dropout, then a jump.
    std::optional<Eigen::Isometry3d> held;
    auto dropout = [&held](io::VioRecord& v) {
        if (v.stamp_s > 6.0 && v.stamp_s < 7.5) {
            if (!held) held = v.T_odom_body;
            v.valid = false;
            v.T_odom_body = *held;
        }
    };
    LocalizerConfig config;
    config.registration_period_s = 1.0;  // sparse registrations: the dropout outlasts 0.5 s
    const Result r = run(
        config, true, 1000, 0.1, [](PointCloud&) {}, dropout);
    std::string warnings;
    for (const LocalizerWarning& w : r.warnings) warnings += w.message + "; ";
    EXPECT_NE(warnings.find("dropout"), std::string::npos) << warnings;
    EXPECT_NE(warnings.find("jump"), std::string::npos) << warnings;
    int relocalisations = 0;
    for (const FrameEvent& e : r.events) {
        if (e.mode == LocalizerMode::kRelocalization && e.outcome == FrameOutcome::kRegistered) {
            ++relocalisations;
            EXPECT_LT((e.T_world_body->translation() - truth_at(e.stamp_s).translation()).norm(),
                      0.05);
        }
    }
    EXPECT_GE(relocalisations, 1);  // fused with the prediction, not a restart
    EXPECT_LT(mean_error(r.fused), 0.05);
}

TEST_F(LocalizerTest, FramesWithoutReturnsAreSkippedAndFaultsWarned) {
    LocalizerConfig config;
    Localizer localizer(map_, config);
    const io::Recording& rec = *recording_;
    PointCloud empty;
    empty.stamp_s = rec.vio()[3].stamp_s - 0.01;
    empty.points.assign(100, Eigen::Vector3d::Constant(NAN));
    localizer.add_depth_frame(0, empty, *rec.depth_T_body_sensor());
    for (int k = 0; k < 5; ++k) localizer.add_vio(rec.vio()[k]);
    localizer.add_vio(rec.vio()[2]);  // time going backwards
    io::ImuRecord imu = rec.imu().front();
    localizer.add_imu(imu);
    imu.stamp_s += 1.0;  // a gap
    localizer.add_imu(imu);
    const auto events = localizer.take_events();
    ASSERT_EQ(events.size(), 1u);
    EXPECT_EQ(events[0].outcome, FrameOutcome::kSkipped);
    EXPECT_EQ(events[0].gate, "no_returns");
    const auto warnings = localizer.take_warnings();
    ASSERT_EQ(warnings.size(), 2u);
    EXPECT_EQ(warnings[0].source, "vio");
    EXPECT_EQ(warnings[1].source, "imu");
    EXPECT_FALSE(localizer.state().has_value());
}

TEST_F(LocalizerTest, DescriptorCacheIsReusedAndRebuiltWhenStaleOrCorrupt) {
    const PointCloud cloud = io::read_cloud(recording_->world_map_path());
    const std::string cache = (dir_ / "map.fpfh").string();
    fs::remove(cache);
    LocalizationMapConfig config;
    const auto first = LocalizationMap::build(cloud, std::nullopt, config, cache);
    EXPECT_EQ(first.descriptor_source(), DescriptorSource::kComputed);
    ASSERT_TRUE(fs::exists(cache));
    const auto second = LocalizationMap::build(cloud, std::nullopt, config, cache);
    EXPECT_EQ(second.descriptor_source(), DescriptorSource::kCache);
    EXPECT_TRUE(first.whole().descriptors.isApprox(second.whole().descriptors));
    fs::resize_file(cache, fs::file_size(cache) - 7);
    const auto third = LocalizationMap::build(cloud, std::nullopt, config, cache);
    EXPECT_EQ(third.descriptor_source(), DescriptorSource::kRecomputedStale);
    EXPECT_NE(third.cache_message().find("recomputed"), std::string::npos);
    config.fpfh.radius_m = 0.2;
    const auto fourth = LocalizationMap::build(cloud, std::nullopt, config, cache);
    EXPECT_EQ(fourth.descriptor_source(), DescriptorSource::kRecomputedStale);
}

TEST_F(LocalizerTest, MapsWithoutNormalsGetThemFacingTheFreeSide) {
    PointCloud cloud = io::read_cloud(recording_->world_map_path());
    ASSERT_TRUE(cloud.has_normals());
    const auto with = LocalizationMap::build(cloud, std::nullopt, LocalizationMapConfig{});
    cloud.normals.clear();
    const auto without = LocalizationMap::build(cloud, std::nullopt, LocalizationMapConfig{});
    // Each estimated normal agrees in sign with the nearest CAD normal (the free side).
    std::size_t agree = 0;
    const auto& a = without.whole().cloud;
    for (std::size_t i = 0; i < a.size(); ++i) {
        const auto nn = with.whole().tree->nearest(a.points[i]);
        if (nn && a.normals[i].dot(with.whole().cloud.normals[nn->index]) > 0.5) ++agree;
    }
    EXPECT_GT(static_cast<double>(agree) / a.size(), 0.8);
}

TEST_F(LocalizerTest, LandmarksCorrectTheVioAndFollowTheRobotThroughTheManhole) {
    LocalizerConfig config;
    config.tracking.method = TrackingMethod::kLandmarks;
    const Result r = run(config, true);
    const io::StructuralMap& structure = *map_->structure();
    int corrections = 0, compartment_changes = 0, previous = -2;
    for (const FrameEvent& e : r.events) {
        if (e.outcome != FrameOutcome::kRegistered || e.mode != LocalizerMode::kTracking) continue;
        ++corrections;
        // Every correction was made in the compartment the robot really is in (but for the
        // estimate's few centimetres about the manhole).
        const Eigen::Vector3d p = truth_at(e.stamp_s).translation();
        const auto truth = io::compartment_at(structure, p);
        ASSERT_TRUE(truth.has_value());
        if (std::abs(p.x() - structure.connections[0].centre.x()) > 0.1) {
            EXPECT_EQ(e.compartment, *truth) << "frame " << e.index;
        }
        EXPECT_GE(e.landmarks_matched, 1u);
        EXPECT_LT((e.T_world_body->translation() - truth_at(e.stamp_s).translation()).norm(), 0.05)
            << "frame " << e.index;
        if (previous != -2 && e.compartment != previous) ++compartment_changes;
        previous = e.compartment;
    }
    EXPECT_GE(corrections, 10) << ::testing::PrintToString(gates(r.events));
    EXPECT_EQ(compartment_changes, 1);  // through the manhole, once
    EXPECT_LT(mean_error(r.fused), 0.04);
}

}  // namespace
}  // namespace scantling::localization
