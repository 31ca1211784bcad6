#include "registration_tank_scans.hpp"

#include <cmath>
#include <numbers>
#include <vector>

#include <scantling/core/normals.hpp>
#include <scantling/core/voxel_grid.hpp>
#include <scantling/registration/stein_icp.hpp>
#include <scantling/sim/sensor_mount.hpp>
#include <scantling/sim/world_builders.hpp>
#include <scantling/sim/world_export.hpp>

namespace scantling::bench {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr std::size_t kMinReturns = 1000;
// The column's first tray is at z = 2 m (DistillationColumnConfig::tray_spacing_m); the mock-up's
// web frame at x = 2.65 m (BallastTankMockupConfig::length_m / 2).
constexpr double kColumnLocalTopM = 2.3;
constexpr double kMockupLocalEndM = 2.75;

/// The optical frame (x right, y down, z forward) in a body frame (x forward, z up).
Eigen::Isometry3d T_body_optical() {
    return make_isometry((Eigen::Matrix3d() << 0, 0, 1, -1, 0, 0, 0, -1, 0).finished(),
                         Eigen::Vector3d::Zero());
}

Vector6d draw_truth(TankScene scene, Rng& rng) {
    Vector6d p;
    if (scene == TankScene::kColumn) {
        const double r = 0.8 * std::sqrt(rng.uniform()), phi = rng.uniform(-kPi, kPi);
        p << r * std::cos(phi), r * std::sin(phi), rng.uniform(0.8, 1.4), 0, 0,
            rng.uniform(-kPi, kPi);
    } else {
        p << rng.uniform(0.3, 0.9), rng.uniform(1.6, 2.4), rng.uniform(0.9, 1.3),
            rng.uniform(-0.1, 0.1), rng.uniform(-0.1, 0.1), rng.uniform(-0.3, 0.3);
    }
    return p;
}

}  // namespace

TankScanner::TankScanner(TankScene scene, double voxel_m, std::uint64_t map_seed)
    : scene_(scene),
      name_(scene == TankScene::kColumn ? "column" : "mockup"),
      voxel_m_(voxel_m),
      world_(scene == TankScene::kColumn ? sim::build_distillation_column()
                                         : sim::build_ballast_tank_mockup()),
      map_(sim::sample_map(world_, voxel_m, map_seed)),
      caster_(std::make_unique<sim::RayCaster>(world_.mesh, world_.surface_tags)) {
    if (scene == TankScene::kColumn) {
        lidar_ = std::make_unique<sim::SpinningLidar>(sim::ouster_os0_64(1024, 10.0));
    } else {
        camera_ = std::make_unique<sim::DepthCamera>(sim::intel_l515(320));
    }
}

PointCloud TankScanner::scan_from(const Eigen::Isometry3d& T_map_body, Rng& rng) const {
    const sim::SceneView view{*caster_, world_.metadata};
    PointCloud raw;
    if (lidar_) {
        raw = lidar_->scan(view, T_map_body, rng);
    } else {
        raw =
            transformed(remove_non_finite(camera_->scan(view, T_map_body * T_body_optical(), rng)),
                        T_body_optical());
    }
    if (raw.size() < kMinReturns) return {};
    return voxel_downsample(raw, voxel_m_);
}

TankScan TankScanner::scan(Rng& rng) const {
    for (;;) {
        TankScan s;
        s.T_map_body = registration::isometry_from_pose_params(draw_truth(scene_, rng));
        s.body = scan_from(s.T_map_body, rng);
        if (!s.body.empty()) return s;
    }
}

TankScan TankScanner::scan_near(const Eigen::Isometry3d& T_map_body, Rng& rng) const {
    const Vector6d p = registration::pose_params_from_isometry(T_map_body);
    for (;;) {
        Vector6d q = p;
        q[0] += rng.uniform(-0.3, 0.3);
        q[1] += rng.uniform(-0.3, 0.3);
        q[2] += rng.uniform(-0.1, 0.1);
        q[5] = std::remainder(q[5] + rng.uniform(-kPi / 6, kPi / 6), 2.0 * kPi);
        TankScan s;
        s.T_map_body = registration::isometry_from_pose_params(q);
        s.body = scan_from(s.T_map_body, rng);
        if (!s.body.empty()) return s;
    }
}

PointCloud TankScanner::local_map() const {
    const bool column = scene_ == TankScene::kColumn;
    std::vector<std::size_t> keep;
    for (std::size_t i = 0; i < map_.size(); ++i) {
        const Eigen::Vector3d& p = map_.points[i];
        if (column ? p.z() <= kColumnLocalTopM : p.x() <= kMockupLocalEndM) keep.push_back(i);
    }
    PointCloud local = select(map_, keep);
    local.normals.clear();
    NormalEstimationConfig normals;
    normals.num_neighbors = 30;
    normals.viewpoint = column ? Eigen::Vector3d(0.0, 0.0, 1.1) : Eigen::Vector3d(0.6, 2.0, 1.1);
    estimate_normals(local, normals);
    return local;
}

Eigen::Isometry3d perturbed(const Eigen::Isometry3d& T, double trans_m, double rot_rad, bool planar,
                            Rng& rng) {
    Vector6d p = registration::pose_params_from_isometry(T);
    for (int i = 0; i < 6; ++i) {
        if (planar && i != 0 && i != 1 && i != 5) continue;
        const double w = i < 3 ? trans_m : rot_rad;
        p[i] += rng.uniform(-w, w);
    }
    p[5] = std::remainder(p[5], 2.0 * kPi);
    return registration::isometry_from_pose_params(p);
}

}  // namespace scantling::bench
