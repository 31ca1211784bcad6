// The exploration's occupancy octree (SPEC §8, issue 16 item 1) against analytic ground truth:
// a wall seen by a pinhole depth camera (free frustum, occupied wall, unknown behind), missing
// returns, a closed box room explored from many views, unknown volume of boxes, two
// resolutions, bad input, and the .bt file read back by OctoMap's own reader.
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <filesystem>
#include <limits>
#include <numbers>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <octomap/OcTree.h>

#include <scantling/core/error.hpp>
#include <scantling/core/random.hpp>
#include <scantling/mapping/occupancy_octree.hpp>

#include "../planning/expect_error.hpp"

namespace scantling::mapping {
namespace {

using Eigen::Vector3d;

constexpr double kDeg = std::numbers::pi / 180.0;
constexpr double kWallM = 3.0;  // the wall's depth in front of the sensor
const double kNaN = std::numeric_limits<double>::quiet_NaN();
// The box room of the exploration tests: 6 × 4 × 3 m, walls at an odd multiple of 0.025 m, so
// mid-voxel at 0.05 m and a quarter voxel deep at 0.1 m (no point on a voxel face).
const Eigen::AlignedBox3d kRoom(Vector3d(-2.975, -1.975, -1.475), Vector3d(3.025, 2.025, 1.525));

/// Optical frame (x right, y down, z forward) in a body frame (x forward, z up).
Eigen::Matrix3d rotation_body_optical() {
    return (Eigen::Matrix3d() << 0, 0, 1, -1, 0, 0, 0, -1, 0).finished();
}

/// A camera at `p_world` looking along yaw / pitch (pitch > 0 looks down).
Eigen::Isometry3d camera_pose(const Vector3d& p_world, double yaw_rad, double pitch_rad) {
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    T.linear() = (Eigen::AngleAxisd(yaw_rad, Vector3d::UnitZ()) *
                  Eigen::AngleAxisd(pitch_rad, Vector3d::UnitY()))
                     .toRotationMatrix() *
                 rotation_body_optical();
    T.translation() = p_world;
    return T;
}

/// Unit pixel rays of a pinhole camera (optical frame), `width` × `height` over the FOV.
std::vector<Vector3d> pixel_rays(int width, int height, double hfov_rad, double vfov_rad) {
    std::vector<Vector3d> rays;
    const double tx = std::tan(hfov_rad / 2.0), ty = std::tan(vfov_rad / 2.0);
    for (int v = 0; v < height; ++v) {
        for (int u = 0; u < width; ++u) {
            rays.push_back(Vector3d(tx * (2.0 * (u + 0.5) / width - 1.0),
                                    ty * (2.0 * (v + 0.5) / height - 1.0), 1.0)
                               .normalized());
        }
    }
    return rays;
}

/// A wall frame: every pixel of a 320 × 240, 60° × 45° camera hits the plane z = depth_m.
PointCloud wall_frame(double depth_m) {
    PointCloud cloud;
    for (const Vector3d& ray : pixel_rays(320, 240, 60.0 * kDeg, 45.0 * kDeg))
        cloud.points.push_back(ray * (depth_m / ray.z()));
    return cloud;
}

/// Distance along unit `d_world` from `o_world` (inside) to the room's walls.
double room_range(const Vector3d& o_world, const Vector3d& d_world) {
    double t = std::numeric_limits<double>::infinity();
    for (int i = 0; i < 3; ++i) {
        if (d_world[i] > 0.0) t = std::min(t, (kRoom.max()[i] - o_world[i]) / d_world[i]);
        if (d_world[i] < 0.0) t = std::min(t, (kRoom.min()[i] - o_world[i]) / d_world[i]);
    }
    return t;
}

/// A 160 × 120, 70° × 55° depth frame of the room (the L515's FOV), sensor frame.
PointCloud room_frame(const Eigen::Isometry3d& T_world_sensor) {
    PointCloud cloud;
    for (const Vector3d& ray : pixel_rays(160, 120, 70.0 * kDeg, 55.0 * kDeg))
        cloud.points.push_back(
            ray * room_range(T_world_sensor.translation(), T_world_sensor.linear() * ray));
    return cloud;
}

/// Two positions, each: 8 headings level and pitched ±50°, then straight up and down.
std::vector<Eigen::Isometry3d> room_views() {
    std::vector<Eigen::Isometry3d> views;
    for (const Vector3d& p : {Vector3d(-1.0, 0.0, 0.0), Vector3d(1.2, 0.3, 0.2)}) {
        for (double pitch_deg : {0.0, 50.0, -50.0})
            for (int k = 0; k < 8; ++k)
                views.push_back(camera_pose(p, k * 45.0 * kDeg, pitch_deg * kDeg));
        views.push_back(camera_pose(p, 0.0, 90.0 * kDeg));
        views.push_back(camera_pose(p, 0.0, -90.0 * kDeg));
    }
    return views;
}

OccupancyOctree explored_room(double resolution_m) {
    OccupancyOctreeConfig config;
    config.resolution_m = resolution_m;
    OccupancyOctree map(config);
    for (const auto& T : room_views()) map.insert_depth_frame(room_frame(T), T);
    return map;
}

/// The wall scene: the camera at a non-trivial pose, looking along world +x at the wall
/// x = 3.05 (mid-voxel at 0.1 m).
const Eigen::Isometry3d kWallPose = camera_pose(Vector3d(0.05, 0.02, 1.03), 0.0, 0.0);

Vector3d wall_scene_point(double x_right_m, double y_down_m, double depth_m) {
    return kWallPose * Vector3d(x_right_m, y_down_m, depth_m);
}

TEST(OccupancyOctree, WallFrameMarksFrustumFreeWallOccupiedAndBehindUnknown) {
    OccupancyOctree map;
    const DepthInsertStats stats = map.insert_depth_frame(wall_frame(kWallM), kWallPose);
    EXPECT_EQ(stats.points, 320u * 240u);
    EXPECT_EQ(stats.misses, 0u);
    for (const Vector3d& p :
         {Vector3d(0, 0, kWallM), Vector3d(1.2, 0.8, kWallM), Vector3d(-1.3, -0.9, kWallM)})
        EXPECT_EQ(map.query(wall_scene_point(p.x(), p.y(), p.z())), Occupancy::kOccupied)
            << p.transpose();
    for (const Vector3d& p : {Vector3d(0, 0, 1.5), Vector3d(0.5, 0.3, 2.0),
                              Vector3d(-0.2, 0.1, 0.6), Vector3d(1.0, -0.7, 2.7)})
        EXPECT_EQ(map.query(wall_scene_point(p.x(), p.y(), p.z())), Occupancy::kFree)
            << p.transpose();
    for (const Vector3d& p : {Vector3d(0, 0, 3.4), Vector3d(0.5, 0.5, 4.5), Vector3d(2.5, 0, 1.0)})
        EXPECT_EQ(map.query(wall_scene_point(p.x(), p.y(), p.z())), Occupancy::kUnknown)
            << p.transpose();

    // Ground truth: the pyramid up to the wall has volume base · height / 3, base = the wall.
    const double wall_area_m2 =
        (2.0 * kWallM * std::tan(30.0 * kDeg)) * (2.0 * kWallM * std::tan(22.5 * kDeg));
    const double pyramid_m3 = wall_area_m2 * kWallM / 3.0;
    // Free voxels overhang the pyramid's ~20 m² of faces by about half a voxel: +12 % expected
    // at 0.1 m (+13 % measured); an unswept or uncut frustum is off by far more.
    constexpr double kFreeTolerance = 0.15;
    constexpr double kOccupiedTolerance = 0.30;  // one voxel layer ± the wall's edge voxels
    EXPECT_NEAR(map.free_volume_m3(), pyramid_m3, kFreeTolerance * pyramid_m3);
    EXPECT_NEAR(map.occupied_volume_m3(), wall_area_m2 * 0.1,
                kOccupiedTolerance * wall_area_m2 * 0.1);
    EXPECT_NEAR(map.explored_volume_m3(), map.free_volume_m3() + map.occupied_volume_m3(), 1e-9);
}

TEST(OccupancyOctree, MissingReturnsClearFreeSpaceToMaxRangeOnly) {
    OccupancyOctree map;                 // max_range_m = 5
    PointCloud frame = wall_frame(8.0);  // every return beyond reach
    const std::size_t num_far = frame.size();
    for (int i = 0; i < 100; ++i) frame.points.push_back(Vector3d(kNaN, 0.0, 1.0));
    frame.points.push_back(Vector3d(0.0, std::numeric_limits<double>::infinity(), 1.0));
    const DepthInsertStats stats = map.insert_depth_frame(frame, kWallPose);
    EXPECT_EQ(stats.points, num_far);
    EXPECT_EQ(stats.misses, num_far);
    EXPECT_EQ(stats.dropped_non_finite, 101u);
    EXPECT_EQ(map.occupied_volume_m3(), 0.0);
    EXPECT_GT(map.free_volume_m3(), 0.0);
    EXPECT_EQ(map.query(wall_scene_point(0, 0, 4.7)), Occupancy::kFree);
    EXPECT_EQ(map.query(wall_scene_point(0, 0, 5.3)), Occupancy::kUnknown);
    EXPECT_EQ(map.query(wall_scene_point(0, 0, 8.0)), Occupancy::kUnknown);
}

TEST(OccupancyOctree, ExploredVolumeGrowsMonotonicallyToTheRoomVolume) {
    OccupancyOctree map;
    double previous_m3 = 0.0;
    for (const auto& T : room_views()) {
        map.insert_depth_frame(room_frame(T), T);
        const double explored_m3 = map.explored_volume_m3();
        EXPECT_GE(explored_m3, previous_m3 - 1e-9);
        previous_m3 = explored_m3;
    }
    const double room_m3 = kRoom.volume();  // 72 m³
    // Issue 16: "within 10 % of the room's volume". The wall voxels overhang the 108 m² of
    // walls by 0.025 or 0.075 m: +7.5 % expected (+7.7 % measured).
    constexpr double kRoomTolerance = 0.10;
    EXPECT_NEAR(map.explored_volume_m3(), room_m3, kRoomTolerance * room_m3);
}

TEST(OccupancyOctree, UnknownVolumeOfBoxesBehindAndBeforeTheWall) {
    OccupancyOctree map;
    constexpr double kRes = 0.1;
    const Eigen::AlignedBox3d empty(Vector3d(1, 1, 1), Vector3d(0, 0, 0));
    EXPECT_EQ(map.unknown_volume_in_m3(empty), 0.0);
    // Before any frame, a 1 × 0.5 × 0.6 m box is all unknown.
    const Eigen::AlignedBox3d box(Vector3d(3.5, -0.25, 0.7), Vector3d(4.5, 0.25, 1.3));
    const double layer_m3 = 2.0 * (1.0 * 0.5 + 1.0 * 0.6 + 0.5 * 0.6) * kRes;  // one voxel skin
    EXPECT_NEAR(map.unknown_volume_in_m3(box), box.volume(), layer_m3);
    map.insert_depth_frame(wall_frame(kWallM), kWallPose);
    EXPECT_NEAR(map.unknown_volume_in_m3(box), box.volume(), layer_m3);  // behind the wall
    // 1.0-2.0 m in front of the camera (world x), well inside the frustum: all free.
    const Eigen::AlignedBox3d seen(Vector3d(1.0, -0.3, 0.8), Vector3d(2.0, 0.3, 1.2));
    EXPECT_LE(map.unknown_volume_in_m3(seen), 2.0 * kRes * kRes * kRes);
}

TEST(OccupancyOctree, HalfAndTenthMetreResolutionsClassifyTheRoomAlike) {
    const OccupancyOctree coarse = explored_room(0.1), fine = explored_room(0.05);
    EXPECT_DOUBLE_EQ(fine.resolution_m(), 0.05);
    struct Probe {
        Vector3d p_world;
        Occupancy truth;
    };
    const std::vector<Probe> probes = {
        {{0.0, 0.0, 0.0}, Occupancy::kFree},       {{-2.0, 1.0, 0.8}, Occupancy::kFree},
        {{2.0, -1.0, -0.7}, Occupancy::kFree},     {{1.0, 1.5, 1.0}, Occupancy::kFree},
        {{3.025, 0.3, 0.2}, Occupancy::kOccupied}, {{-2.975, 0.0, 0.0}, Occupancy::kOccupied},
        {{0.0, 2.025, 0.1}, Occupancy::kOccupied}, {{0.5, -1.975, 0.0}, Occupancy::kOccupied},
        {{0.2, 0.1, 1.525}, Occupancy::kOccupied}, {{-0.9, 0.1, -1.475}, Occupancy::kOccupied},
        {{3.6, 0.0, 0.0}, Occupancy::kUnknown},    {{0.0, 2.6, 0.0}, Occupancy::kUnknown},
        {{0.0, 0.0, -2.1}, Occupancy::kUnknown},   {{-3.5, 1.0, 1.0}, Occupancy::kUnknown},
    };
    for (const Probe& probe : probes) {
        EXPECT_EQ(coarse.query(probe.p_world), probe.truth) << probe.p_world.transpose();
        EXPECT_EQ(fine.query(probe.p_world), probe.truth) << probe.p_world.transpose();
    }
}

TEST(OccupancyOctree, BadConfigPoseAndPathAreClearErrors) {
    const auto with = [](auto edit) {
        OccupancyOctreeConfig config;
        edit(config);
        return config;
    };
    SCANTLING_EXPECT_ERROR(OccupancyOctree(with([](auto& c) { c.resolution_m = 0.0; })),
                           ConfigError, "occupancy_octree.resolution_m");
    SCANTLING_EXPECT_ERROR(OccupancyOctree(with([](auto& c) { c.resolution_m = -0.1; })),
                           ConfigError, "occupancy_octree.resolution_m");
    SCANTLING_EXPECT_ERROR(OccupancyOctree(with([](auto& c) { c.resolution_m = kNaN; })),
                           ConfigError, "occupancy_octree.resolution_m");
    SCANTLING_EXPECT_ERROR(OccupancyOctree(with([](auto& c) { c.max_range_m = 0.0; })), ConfigError,
                           "occupancy_octree.max_range_m");
    SCANTLING_EXPECT_ERROR(OccupancyOctree(with([](auto& c) { c.prob_hit = 0.4; })), ConfigError,
                           "occupancy_octree.prob_hit");
    SCANTLING_EXPECT_ERROR(OccupancyOctree(with([](auto& c) { c.prob_miss = 0.6; })), ConfigError,
                           "occupancy_octree.prob_miss");
    SCANTLING_EXPECT_ERROR(OccupancyOctree(with([](auto& c) { c.clamp_min = 0.6; })), ConfigError,
                           "occupancy_octree.clamp_min");
    SCANTLING_EXPECT_ERROR(OccupancyOctree(with([](auto& c) { c.clamp_max = 0.45; })), ConfigError,
                           "occupancy_octree.clamp_max");
    SCANTLING_EXPECT_ERROR(OccupancyOctree(with([](auto& c) { c.occupied_threshold = 1.0; })),
                           ConfigError, "occupancy_octree.occupied_threshold");

    OccupancyOctree map;
    Eigen::Isometry3d bad_pose = kWallPose;
    bad_pose.translation().x() = kNaN;
    SCANTLING_EXPECT_ERROR(map.insert_depth_frame(wall_frame(kWallM), bad_pose), InputError,
                           "T_world_sensor");
    EXPECT_THROW(map.query(Vector3d(kNaN, 0, 0)), InputError);

    const std::filesystem::path missing =
        std::filesystem::temp_directory_path() / "scantling_no_such_dir_octree" / "map.bt";
    EXPECT_THROW(map.write_binary(missing.string()), FileError);
    EXPECT_FALSE(std::filesystem::exists(missing.parent_path()));
}

/// The body-convention pose (x forward, z up) of a camera_pose: its optical rotation undone.
Eigen::Isometry3d body_pose(const Eigen::Isometry3d& T_world_optical) {
    Eigen::Isometry3d T = T_world_optical;
    T.linear() = T_world_optical.linear() * rotation_body_optical().transpose();
    return T;
}

/// A narrow view well inside the wall frame's 60° × 45°, reaching `max_depth_m`.
ViewFrustum narrow_view(double max_depth_m) {
    ViewFrustum view;
    view.horizontal_fov_rad = 0.2;
    view.vertical_fov_rad = 0.2;
    view.max_depth_m = max_depth_m;
    view.rays_horizontal = 8;
    view.rays_vertical = 8;
    return view;
}

/// Voxel counts bracketing what the rays of `view` from the identity pose can reach in an empty
/// map (brute force over the voxels). Rays stay in the pinhole pyramid P and within max_depth_m
/// of the apex, so: every voxel they cross meets P, hence its centre is within half a voxel
/// diagonal of each of P's 5 face planes (`upper`); and where the rays are denser than the
/// voxels, every voxel wholly inside P ∩ the ball of radius max_depth_m is crossed (`lower`).
struct FrustumVoxelBounds {
    std::size_t lower = 0, upper = 0;
};

FrustumVoxelBounds frustum_voxel_bounds(const ViewFrustum& view, double res_m) {
    const double d = view.max_depth_m, th = std::tan(view.horizontal_fov_rad / 2.0),
                 tv = std::tan(view.vertical_fov_rad / 2.0);
    const auto max_plane_distance = [&](const Vector3d& p) {  // > 0 outside P
        return std::max({(std::abs(p.y()) - p.x() * th) / std::hypot(1.0, th),
                         (std::abs(p.z()) - p.x() * tv) / std::hypot(1.0, tv), p.x() - d});
    };
    const double margin_m = 0.5 * std::sqrt(3.0) * res_m + 1e-6;  // + float ray rounding
    const int n = static_cast<int>(std::ceil(d / res_m)) + 2;
    FrustumVoxelBounds bounds;
    for (int i = -2; i <= n; ++i) {
        for (int j = -n; j <= n; ++j) {
            for (int k = -n; k <= n; ++k) {
                const Vector3d corner = Vector3d(i, j, k) * res_m;
                bounds.upper +=
                    max_plane_distance(corner + Vector3d::Constant(0.5 * res_m)) <= margin_m;
                bool inside = true;
                for (int c = 0; c < 8; ++c) {
                    const Vector3d p = corner + Vector3d(c & 1, (c >> 1) & 1, c >> 2) * res_m;
                    inside = inside && max_plane_distance(p) <= 0.0 && p.norm() <= d;
                }
                bounds.lower += inside;
            }
        }
    }
    return bounds;
}

TEST(OccupancyOctree, VisibleUnknownVolumeOfAnEmptyMapFillsTheFrustum) {
    const OccupancyOctree map;  // 0.1 m
    constexpr double kVoxelM3 = 0.001;
    // Rays 0.2 / 7 rad apart: denser than the voxels everywhere within the 2 m reach.
    const ViewFrustum dense = narrow_view(2.0);
    const VisibleVolume seen = map.visible_unknown_volume(Eigen::Isometry3d::Identity(), dense);
    EXPECT_EQ(seen.rays, 64u);
    EXPECT_EQ(seen.rays_blocked, 0u);
    EXPECT_DOUBLE_EQ(seen.unknown_m3, static_cast<double>(seen.unknown_voxels) * kVoxelM3);
    const FrustumVoxelBounds bounds = frustum_voxel_bounds(dense, 0.1);
    EXPECT_GT(bounds.lower, 0u);
    EXPECT_GE(seen.unknown_voxels, bounds.lower);
    EXPECT_LE(seen.unknown_voxels, bounds.upper);

    // Rays 1.0 / 7 rad apart, ~ 0.29 m at 2 m, sparser than the voxels: a sampled lower bound
    // of the pyramid, base (2 d tan(h/2)) × (2 d tan(v/2)), height d.
    ViewFrustum sparse = dense;
    sparse.horizontal_fov_rad = sparse.vertical_fov_rad = 1.0;
    const double d = sparse.max_depth_m;
    const double pyramid_m3 = (2.0 * d * std::tan(0.5)) * (2.0 * d * std::tan(0.5)) * d / 3.0;
    const VisibleVolume sampled = map.visible_unknown_volume(Eigen::Isometry3d::Identity(), sparse);
    EXPECT_GT(sampled.unknown_m3, 0.0);
    EXPECT_LE(sampled.unknown_m3, pyramid_m3);
}

TEST(OccupancyOctree, VisibleUnknownVolumeVanishesWhereAFrameSawAndStaysBehindIt) {
    const Eigen::Isometry3d T_world_camera = body_pose(kWallPose);
    Eigen::Isometry3d T_world_back = T_world_camera;
    T_world_back.linear() =
        T_world_camera.linear() *
        Eigen::AngleAxisd(std::numbers::pi, Vector3d::UnitZ()).toRotationMatrix();
    const ViewFrustum view = narrow_view(4.0);  // beyond the wall at 3 m
    OccupancyOctree map;
    const VisibleVolume empty_ahead = map.visible_unknown_volume(T_world_camera, view);
    const VisibleVolume empty_back = map.visible_unknown_volume(T_world_back, view);
    map.insert_depth_frame(wall_frame(kWallM), kWallPose);
    const VisibleVolume ahead = map.visible_unknown_volume(T_world_camera, view);
    const VisibleVolume back = map.visible_unknown_volume(T_world_back, view);
    EXPECT_LT(ahead.unknown_m3, 0.02 * empty_ahead.unknown_m3);
    EXPECT_GT(ahead.rays_blocked, 0.9 * ahead.rays);
    // The frame saw nothing behind the camera: only the camera's own voxel, where its rays
    // start, is now known (free).
    EXPECT_EQ(map.query(T_world_camera.translation()), Occupancy::kFree);
    EXPECT_EQ(back.unknown_voxels + 1, empty_back.unknown_voxels);
    EXPECT_EQ(back.rays_blocked, 0u);
}

TEST(OccupancyOctree, VisibleUnknownVolumeRejectsBadViewsAndPoses) {
    const OccupancyOctree map;
    const auto seen_with = [&](auto edit) {
        ViewFrustum view;
        edit(view);
        return map.visible_unknown_volume(Eigen::Isometry3d::Identity(), view);
    };
    SCANTLING_EXPECT_ERROR(seen_with([](auto& v) { v.horizontal_fov_rad = std::numbers::pi; }),
                           ConfigError, "view_frustum.horizontal_fov_rad");
    SCANTLING_EXPECT_ERROR(seen_with([](auto& v) { v.horizontal_fov_rad = 0.0; }), ConfigError,
                           "view_frustum.horizontal_fov_rad");
    SCANTLING_EXPECT_ERROR(seen_with([](auto& v) { v.vertical_fov_rad = 4.0; }), ConfigError,
                           "view_frustum.vertical_fov_rad");
    SCANTLING_EXPECT_ERROR(seen_with([](auto& v) { v.vertical_fov_rad = kNaN; }), ConfigError,
                           "view_frustum.vertical_fov_rad");
    SCANTLING_EXPECT_ERROR(seen_with([](auto& v) { v.max_depth_m = 0.0; }), ConfigError,
                           "view_frustum.max_depth_m");
    SCANTLING_EXPECT_ERROR(seen_with([](auto& v) { v.rays_horizontal = 1; }), ConfigError,
                           "view_frustum.rays_horizontal");
    SCANTLING_EXPECT_ERROR(seen_with([](auto& v) { v.rays_vertical = 0; }), ConfigError,
                           "view_frustum.rays_vertical");
    Eigen::Isometry3d bad_pose = Eigen::Isometry3d::Identity();
    bad_pose.translation().z() = kNaN;
    SCANTLING_EXPECT_ERROR(map.visible_unknown_volume(bad_pose), InputError, "T_world_camera");
    bad_pose.translation().z() = 1e4;  // beyond the ±3.3 km map at 0.1 m
    SCANTLING_EXPECT_ERROR(map.visible_unknown_volume(bad_pose), InputError, "outside the map");
}

/// Ground truth for box_is_free: every voxel the closed box touches, queried at its centre.
bool box_free_by_queries(const OccupancyOctree& map, const Eigen::AlignedBox3d& box) {
    const double res = map.resolution_m();
    const Eigen::Vector3d lo = (box.min() / res).array().floor();
    const Eigen::Vector3d hi = (box.max() / res).array().floor();
    for (double i = lo.x(); i <= hi.x(); ++i)
        for (double j = lo.y(); j <= hi.y(); ++j)
            for (double k = lo.z(); k <= hi.z(); ++k)
                if (map.query((Vector3d(i, j, k) + Vector3d::Constant(0.5)) * res) !=
                    Occupancy::kFree)
                    return false;
    return true;
}

TEST(OccupancyOctree, BoxIsFreeAgreesWithVoxelQueriesOnAnExploredRoom) {
    const OccupancyOctree map = explored_room(0.1);
    Rng rng(16);
    int free_boxes = 0;
    constexpr int kBoxes = 300;
    for (int n = 0; n < kBoxes; ++n) {
        const Vector3d centre(rng.uniform(-3.2, 3.2), rng.uniform(-2.2, 2.2),
                              rng.uniform(-1.7, 1.7));
        const Vector3d half(rng.uniform(0.02, 0.8), rng.uniform(0.02, 0.8), rng.uniform(0.02, 0.5));
        const Eigen::AlignedBox3d box(centre - half, centre + half);
        const bool truth = box_free_by_queries(map, box);
        EXPECT_EQ(map.box_is_free(box), truth) << centre.transpose() << " ± " << half.transpose();
        free_boxes += truth;
    }
    // Both outcomes are exercised (~ half the boxes touch a wall or leave the room).
    EXPECT_GT(free_boxes, kBoxes / 5);
    EXPECT_LT(free_boxes, kBoxes * 4 / 5);
    // Edge cases: an empty box is free, an unknown map is not, the map's edge is not.
    EXPECT_TRUE(map.box_is_free(Eigen::AlignedBox3d(Vector3d(1, 1, 1), Vector3d(0, 0, 0))));
    EXPECT_FALSE(
        OccupancyOctree().box_is_free(Eigen::AlignedBox3d(Vector3d::Zero(), Vector3d::Ones())));
    EXPECT_FALSE(map.box_is_free(Eigen::AlignedBox3d(Vector3d::Zero(), Vector3d::Constant(1e4))));
    SCANTLING_EXPECT_ERROR(
        map.box_is_free(Eigen::AlignedBox3d(Vector3d::Constant(kNaN), Vector3d::Zero())),
        InputError, "box_is_free");
}

TEST(OccupancyOctree, LineOfSightIsBlockedByOccupiedVoxelsOnly) {
    OccupancyOctree map;
    map.insert_depth_frame(wall_frame(kWallM), kWallPose);
    const Vector3d camera = kWallPose.translation();
    EXPECT_TRUE(map.line_of_sight(camera, wall_scene_point(0.2, 0.1, 2.0)));      // free space
    EXPECT_TRUE(map.line_of_sight(camera, wall_scene_point(0.3, -0.2, kWallM)));  // on the wall
    EXPECT_FALSE(map.line_of_sight(camera, wall_scene_point(0.3, -0.2, kWallM + 0.5)));  // behind
    // Through unknown space (backwards, never seen): not blocked.
    EXPECT_TRUE(map.line_of_sight(camera, wall_scene_point(0.0, 0.0, -3.0)));
    SCANTLING_EXPECT_ERROR(map.line_of_sight(camera, Vector3d(kNaN, 0, 0)), InputError,
                           "line_of_sight");
}

TEST(OccupancyOctree, FrontierPointsAreFreeAndBorderUnknownSpace) {
    OccupancyOctree map;
    map.insert_depth_frame(wall_frame(kWallM), kWallPose);
    const Eigen::AlignedBox3d bounds(Vector3d(-6, -6, -6), Vector3d(6, 6, 6));
    for (const int levels : {0, 1, 2}) {
        const std::vector<Vector3d> points = map.frontier_points(bounds, levels);
        ASSERT_FALSE(points.empty()) << levels;
        const double cell_m = 0.1 * (1 << levels);
        for (const Vector3d& p : points) {
            // In a free voxel; with coarse cells in a free cell, which may hold unknown holes.
            if (levels == 0) {
                ASSERT_EQ(map.query(p), Occupancy::kFree) << p.transpose();
            }
            ASSERT_NE(map.query(p), Occupancy::kOccupied) << p.transpose();
            ASSERT_TRUE(bounds.contains(p));
            // The frustum's side faces border unknown space: some voxel within a cell and a
            // half (the points stand for faces of merged leaves, so allow a few cells) is
            // unknown.
            bool unknown_near = false;
            for (int a = 0; a < 3 && !unknown_near; ++a)
                for (const double s : {-1.0, 1.0})
                    for (double r = 0.1; r <= 8.0 * cell_m && !unknown_near; r += 0.1)
                        unknown_near =
                            map.query(p + s * r * Vector3d::Unit(a)) == Occupancy::kUnknown;
            EXPECT_TRUE(unknown_near) << p.transpose();
        }
    }
    // Coarser cells: fewer points. Bounds without free space: none. Bad input: errors.
    EXPECT_LT(map.frontier_points(bounds, 2).size(), map.frontier_points(bounds, 0).size());
    EXPECT_TRUE(map.frontier_points(Eigen::AlignedBox3d(Vector3d(-6, -6, -6), Vector3d(-5, -5, -5)))
                    .empty());
    SCANTLING_EXPECT_ERROR(map.frontier_points(bounds, 9), InputError, "coarse_levels");
}

TEST(OccupancyOctree, FrontierPointsOfAFullyExploredRoomAreNone) {
    const OccupancyOctree map = explored_room(0.1);
    // The room's inside (no voxel across a wall): every free cell borders free or occupied.
    const Eigen::AlignedBox3d inside(kRoom.min() + Vector3d::Constant(0.1),
                                     kRoom.max() - Vector3d::Constant(0.1));
    EXPECT_TRUE(map.frontier_points(inside, 1).empty()) << map.frontier_points(inside, 1).size();
}

TEST(OccupancyOctree, BoundedVisibleUnknownVolumeCountsOnlyInsideTheBounds) {
    const OccupancyOctree map;                                  // all unknown
    const Eigen::Isometry3d T = Eigen::Isometry3d::Identity();  // looking along +x
    const ViewFrustum view = narrow_view(2.0);
    const VisibleVolume all = map.visible_unknown_volume(T, view);
    const Eigen::AlignedBox3d near_half(Vector3d(-1, -5, -5), Vector3d(1.0, 5, 5));
    const VisibleVolume near = map.visible_unknown_volume(T, view, near_half);
    EXPECT_GT(near.unknown_m3, 0.0);
    EXPECT_LT(near.unknown_m3, 0.5 * all.unknown_m3);  // the pyramid's first half holds 1/8
    const Eigen::AlignedBox3d elsewhere(Vector3d(3, 3, 3), Vector3d(4, 4, 4));
    EXPECT_EQ(map.visible_unknown_volume(T, view, elsewhere).unknown_m3, 0.0);
    const Eigen::AlignedBox3d huge(Vector3d::Constant(-100), Vector3d::Constant(100));
    EXPECT_EQ(map.visible_unknown_volume(T, view, huge).unknown_voxels, all.unknown_voxels);
}

TEST(OccupancyOctree, BinaryFileReadsBackWithOctoMapsOwnReader) {
    OccupancyOctree map;
    map.insert_depth_frame(wall_frame(kWallM), kWallPose);
    const std::filesystem::path path =
        std::filesystem::temp_directory_path() / "scantling_occupancy_octree_test.bt";
    map.write_binary(path.string());
    octomap::OcTree tree(0.1);
    ASSERT_TRUE(tree.readBinary(path.string()));
    EXPECT_EQ(tree.getNumLeafNodes(), map.num_leaves());
    EXPECT_DOUBLE_EQ(tree.getResolution(), map.resolution_m());
    for (const Vector3d& p : {wall_scene_point(0, 0, kWallM), wall_scene_point(0, 0, 1.5)}) {
        const octomap::OcTreeNode* node = tree.search(p.x(), p.y(), p.z());
        ASSERT_NE(node, nullptr);
        EXPECT_EQ(tree.isNodeOccupied(node), map.query(p) == Occupancy::kOccupied);
    }
    std::filesystem::remove(path);
}

}  // namespace
}  // namespace scantling::mapping
