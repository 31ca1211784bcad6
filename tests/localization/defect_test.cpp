// Defects lifted through known poses, merged over views, placed in surveyors' terms.
#include <gtest/gtest.h>

#include <cmath>

#include <scantling/core/error.hpp>
#include <scantling/core/random.hpp>
#include <scantling/localization/defect_lifting.hpp>
#include <scantling/localization/defect_map.hpp>
#include <scantling/localization/fused_track.hpp>
#include <scantling/localization/survey_location.hpp>

namespace scantling::localization {
namespace {

constexpr double kDeg = M_PI / 180.0;

/// A wall x = 3 (normal −x) sampled every 5 mm over y, z ∈ [0, 2], with range noise `sigma_m`
/// along x; the camera at the origin looking along +x (optical z = world x).
struct WallScene {
    PinholeIntrinsics K = PinholeIntrinsics::from_fov(320, 240, 66.0 * kDeg, 49.5 * kDeg);
    Eigen::Isometry3d T_world_camera = [] {
        Eigen::Matrix3d R;  // optical x right (−y world), y down (−z world), z forward (+x)
        R << 0, 0, 1, -1, 0, 0, 0, -1, 0;
        Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
        T.linear() = R;
        T.translation() = Eigen::Vector3d(0.0, 1.0, 1.0);
        return T;
    }();

    PointCloud wall(double sigma_m, std::uint64_t seed) const {
        Rng rng(seed);
        PointCloud cloud;
        for (double y = 0.0; y <= 2.0; y += 0.005) {
            for (double z = 0.0; z <= 2.0; z += 0.005) {
                cloud.points.emplace_back(3.0 + sigma_m * rng.normal(), y, z);
            }
        }
        return cloud;
    }
    io::DefectSighting sighting_of(const Eigen::Vector3d& centre_world, double radius_px) const {
        const auto pixel = K.project(T_world_camera.inverse() * centre_world);
        EXPECT_TRUE(pixel.has_value());
        return {
            .image = 4, .stamp_s = 2.0, .defect_id = 7, .pixel = *pixel, .radius_px = radius_px};
    }
    LiftingView view(const Matrix6d& body_covariance = Matrix6d::Zero()) const {
        return {K, T_world_camera, T_world_camera.translation(), body_covariance};
    }
};

TEST(DefectLifting, LiftsTheCentreOntoTheWallThroughAKnownPose) {
    const WallScene scene;
    const Eigen::Vector3d centre(3.0, 1.3, 0.8);
    const LiftResult r =
        lift_defect(scene.sighting_of(centre, 6.0), scene.view(), scene.wall(0.005, 1));
    ASSERT_TRUE(r.observation) << r.reason;
    const DefectObservation& o = *r.observation;
    EXPECT_LT((o.position_world - centre).norm(), 0.003);
    EXPECT_EQ(o.defect_id, 7);
    EXPECT_EQ(o.image, 4u);
    EXPECT_NEAR(o.normal_world.x(), -1.0, 1e-3);  // towards the camera
    EXPECT_NEAR(o.range_m, (centre - scene.T_world_camera.translation()).norm(), 0.003);
    EXPECT_GT(o.support_points, 50u);
    // The returns within 0.3 m of the centre: a disc of the 5 mm grid (~11 300 points).
    EXPECT_NEAR(static_cast<double>(o.local_cloud_world.size()), M_PI * 0.09 / 25e-6, 400.0);
    EXPECT_TRUE(o.pose_covariance.isZero());
}

TEST(DefectLifting, MeasurementCovarianceMatchesTheScatterOverNoiseDraws) {
    const WallScene scene;
    const Eigen::Vector3d centre(3.0, 0.7, 1.4);
    double nees = 0.0;
    const int draws = 40;
    for (int k = 0; k < draws; ++k) {
        DefectLiftingConfig config;
        config.range_sigma_m = 0.01;
        config.pixel_sigma_px = 1e-6;  // the pixel is exact here: only the range noise counts
        const LiftResult r = lift_defect(scene.sighting_of(centre, 3.0), scene.view(),
                                         scene.wall(0.01, 100 + k), config);
        ASSERT_TRUE(r.observation) << r.reason;
        const Eigen::Vector3d e = r.observation->position_world - centre;
        nees += e.dot(r.observation->measurement_covariance.ldlt().solve(e));
    }
    // The error lies along the ray (rank 1): mean of χ²(1) over 40 draws, 1 ± 0.22.
    EXPECT_GT(nees / draws, 0.4);
    EXPECT_LT(nees / draws, 2.0);
}

TEST(DefectLifting, PoseCovarianceIsCarriedToThePoint) {
    const WallScene scene;
    Matrix6d P = Matrix6d::Zero();
    P(5, 5) = std::pow(1.0 * kDeg, 2);  // 1° of yaw about the body
    const LiftResult r =
        lift_defect(scene.sighting_of({3.0, 1.0, 1.0}, 6.0), scene.view(P), scene.wall(0.0, 1));
    ASSERT_TRUE(r.observation) << r.reason;
    // 3 m ahead, a yaw error of 1° moves the point 5.2 cm sideways (y), nothing along x or z.
    EXPECT_NEAR(std::sqrt(r.observation->pose_covariance(1, 1)), 3.0 * kDeg, 1e-4);
    EXPECT_NEAR(r.observation->pose_covariance(0, 0), 0.0, 1e-9);
    EXPECT_NEAR(r.observation->pose_covariance(2, 2), 0.0, 1e-9);
}

TEST(DefectLifting, RefusesASightingWithoutReturnsOrOnAGrazingPlate) {
    const WallScene scene;
    const io::DefectSighting s = scene.sighting_of({3.0, 1.0, 1.0}, 6.0);
    const LiftResult empty = lift_defect(s, scene.view(), PointCloud{});
    EXPECT_FALSE(empty.observation);
    EXPECT_EQ(empty.reason.rfind("no_depth", 0), 0u) << empty.reason;
    // The floor z = 0.9 seen nearly edge-on from z = 1 at 3 m: ~2° of incidence.
    PointCloud floor;
    for (double x = 2.5; x <= 3.5; x += 0.005) {
        for (double y = 0.8; y <= 1.2; y += 0.005) floor.points.emplace_back(x, y, 0.9);
    }
    const auto pixel = scene.K.project(scene.T_world_camera.inverse() * Eigen::Vector3d(3, 1, 0.9));
    ASSERT_TRUE(pixel);
    io::DefectSighting low = s;
    low.pixel = *pixel;
    const LiftResult grazing = lift_defect(low, scene.view(), floor);
    EXPECT_FALSE(grazing.observation);
    EXPECT_EQ(grazing.reason.rfind("oblique", 0), 0u) << grazing.reason;
    DefectLiftingConfig bad;
    bad.min_support_points = 2;
    EXPECT_THROW(bad.validate(), ConfigError);
}

DefectObservation view_at(const Eigen::Vector3d& p, double sigma_m, double pose_sigma_m,
                          double stamp_s) {
    DefectObservation o;
    o.defect_id = 3;
    o.stamp_s = stamp_s;
    o.position_world = p;
    o.measurement_covariance = Eigen::Matrix3d::Identity() * sigma_m * sigma_m;
    o.pose_covariance = Eigen::Matrix3d::Identity() * pose_sigma_m * pose_sigma_m;
    o.local_cloud_world.points = {p};
    return o;
}

TEST(DefectMap, MergesViewsByInformationAndDropsTheOneThatDisagrees) {
    DefectMap map;
    map.add(view_at({1.00, 2.0, 0.5}, 0.01, 0.01, 1.0));
    map.add(view_at({1.02, 2.0, 0.5}, 0.01, 0.01, 2.0));
    map.add(view_at({1.01, 2.0, 0.5}, 0.005, 0.01, 3.0));  // the best view
    map.add(view_at({1.40, 2.0, 0.5}, 0.01, 0.01, 4.0));   // a stiffener in front
    const std::vector<MappedDefect> defects = map.defects();
    ASSERT_EQ(defects.size(), 1u);
    const MappedDefect& d = defects.front();
    EXPECT_EQ(d.views, 3u);
    EXPECT_EQ(d.outlier_views, 1u);
    // Weights 1 : 1 : 4 → x = (1.00 + 1.02 + 4 · 1.01) / 6 = 1.01.
    EXPECT_NEAR(d.position_world.x(), 1.01, 1e-9);
    // Measurement 1 / (100² + 100² + 200²)... plus the mean pose variance, not shrunk.
    const double merged = 1.0 / (1e4 + 1e4 + 4e4);
    EXPECT_NEAR(d.covariance(0, 0), merged + 1e-4, 1e-12);
    EXPECT_EQ(d.best_view.stamp_s, 3.0);
    EXPECT_EQ(d.best_view.local_cloud_world.size(), 1u);
    EXPECT_EQ(d.first_seen_s, 1.0);
    EXPECT_EQ(d.last_seen_s, 4.0);
    EXPECT_NEAR(d.largest_sigma_m(), std::sqrt(merged + 1e-4), 1e-9);
}

io::StructuralMap two_bays() {
    io::StructuralMap m;
    m.compartments = {{0, "bay_1", Aabb{{0, 0, 0}, {2.65, 2.9, 1.75}}, 0},
                      {1, "bay_2", Aabb{{2.65, 0, 0}, {5.3, 2.9, 1.75}}, 0}};
    m.frames = {{0, {0.0, 1.45, 0.9}, Eigen::Vector3d::UnitX(), "aft_bulkhead"},
                {1, {2.65, 1.45, 0.9}, Eigen::Vector3d::UnitX(), "web_frame"},
                {2, {5.3, 1.45, 0.9}, Eigen::Vector3d::UnitX(), "fore_bulkhead"}};
    m.longitudinals = {{1, {0.0, 1.8, 0.1}, Eigen::Vector3d::UnitX(), "bottom"},
                       {2, {0.0, 2.8, 0.9}, Eigen::Vector3d::UnitX(), "side_shell"}};
    return m;
}

TEST(SurveyLocation, NamesCompartmentFrameLongitudinalAndHeight) {
    const io::StructuralMap m = two_bays();
    const SurveyLocation a = locate_in_structure(m, {2.3, 2.7, 1.0});
    EXPECT_EQ(a.compartment, 0);
    EXPECT_EQ(a.compartment_name, "bay_1");
    EXPECT_EQ(a.frame, 1);
    EXPECT_NEAR(a.from_frame_m, -0.35, 1e-12);
    EXPECT_EQ(a.longitudinal, 2);
    EXPECT_NEAR(a.from_longitudinal_m, std::hypot(0.1, 0.1), 1e-12);
    EXPECT_NEAR(a.height_above_floor_m, 1.0, 1e-12);
    EXPECT_EQ(a.text(), "bay_1, frame 1 -0.35 m, longitudinal 2 (0.14 m), 1.00 m above the floor");
    // On the web frame itself both bays contain it: the one it was seen from wins.
    EXPECT_EQ(locate_in_structure(m, {2.65, 1.0, 0.5}, 1).compartment, 1);
    EXPECT_EQ(locate_in_structure(m, {2.65, 1.0, 0.5}, 0).compartment, 0);
    EXPECT_EQ(locate_in_structure(m, {9.0, 1.0, 0.5}).compartment, -1);
}

FusedState state_at(double stamp_s, double x_m, double yaw_rad) {
    FusedState s;
    s.stamp_s = stamp_s;
    s.T_world_body.translation() = Eigen::Vector3d(x_m, 0, 0);
    s.T_world_body.linear() = Eigen::AngleAxisd(yaw_rad, Eigen::Vector3d::UnitZ()).matrix();
    s.covariance = Matrix6d::Identity() * stamp_s;
    return s;
}

TEST(FusedTrack, InterpolatesBetweenSamplesAndRefusesGapsAndEnds) {
    const std::vector<FusedState> track = {state_at(1.0, 0.0, 0.0), state_at(1.1, 0.1, 0.2),
                                           state_at(2.0, 0.2, 0.2)};
    const auto mid = fused_state_at(track, 1.075, 0.2);
    ASSERT_TRUE(mid);
    EXPECT_NEAR(mid->T_world_body.translation().x(), 0.075, 1e-12);
    EXPECT_NEAR(Eigen::AngleAxisd(mid->T_world_body.linear()).angle(), 0.15, 1e-9);
    EXPECT_EQ(mid->covariance(0, 0), 1.1);  // the nearer sample's
    EXPECT_TRUE(fused_state_at(track, 1.1, 0.2));
    EXPECT_FALSE(fused_state_at(track, 1.5, 0.2));  // 0.9 s between samples: a dropout
    EXPECT_FALSE(fused_state_at(track, 0.5, 0.2));
    EXPECT_FALSE(fused_state_at(track, 2.5, 0.2));
}

}  // namespace
}  // namespace scantling::localization
