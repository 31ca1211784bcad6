#pragma once
/// @file Simulated scans of the SPEC §7 tanks with known truth, shared by the registration
/// benchmark (registration_bench_tanks.cpp) and the consistency experiment: the ballast-tank
/// mock-up seen by an Intel L515 depth camera (320 × 240, 70° × 55°) and the distillation column
/// by an Ouster OS0-64-like 360° LiDAR (±45°, 64 × 1024), each against its CAD map
/// (`sim::sample_map` at the voxel size: i.i.d. samples over every face, hidden ones included,
/// with the triangle normals, which point to the free side).

#include <Eigen/Geometry>
#include <cstdint>
#include <memory>
#include <string>

#include <scantling/core/point_cloud.hpp>
#include <scantling/core/random.hpp>
#include <scantling/core/se3.hpp>
#include <scantling/sim/depth_camera.hpp>
#include <scantling/sim/ray_caster.hpp>
#include <scantling/sim/spinning_lidar.hpp>
#include <scantling/sim/world.hpp>

namespace scantling::bench {

enum class TankScene {
    kMockup,  ///< depth camera inside compartment 1, looking along +x towards the web frame
    kColumn,  ///< 360° LiDAR below the first tray, level, any heading (SPEC §7 art. F)
};

/// One scan with its truth.
struct TankScan {
    Eigen::Isometry3d T_map_body = Eigen::Isometry3d::Identity();  ///< the true pose
    /// Voxel-downsampled scan in the body frame (x forward, z up, sensor at the origin).
    PointCloud body;
};

/// A world, its CAD map and a sensor. Not copyable (the ray caster refers to the world).
class TankScanner {
  public:
    TankScanner(TankScene scene, double voxel_m, std::uint64_t map_seed);
    TankScanner(const TankScanner&) = delete;
    TankScanner& operator=(const TankScanner&) = delete;

    /// Draws a true pose (see TankScene; mock-up: x ∈ [0.3, 0.9], y ∈ [1.6, 2.4],
    /// z ∈ [0.9, 1.3] m, roll/pitch ±0.1 rad, yaw ±0.3 rad; column: within 0.8 m of the axis,
    /// z ∈ [0.8, 1.4] m, level, yaw uniform) and scans from it; views with fewer than 1000
    /// returns (through a manhole) are redrawn.
    TankScan scan(Rng& rng) const;

    /// A second scan for scan-to-scan pairs, from `T_map_body` moved by up to ±0.3 m in x and y,
    /// ±0.1 m in z and ±30° in yaw (roll and pitch kept); redrawn as scan().
    TankScan scan_near(const Eigen::Isometry3d& T_map_body, Rng& rng) const;

    /// The CAD map, world frame.
    const PointCloud& map() const { return map_; }
    /// The part of the map around the space the robot knows it is in (SPEC §7: compartments
    /// are known), for global registration: the mock-up's compartment 1 (x <= 2.75 m), the
    /// column from the floor to 0.3 m above the first tray. Normals re-estimated as the scans'
    /// (k = 30) and turned towards the centre of the poses scan() draws: the map has both faces
    /// of every plate, whose opposite triangle normals would make its FPFH unlike the scans'.
    PointCloud local_map() const;
    const std::string& name() const { return name_; }
    TankScene scene() const { return scene_; }

  private:
    /// The scan from `T_map_body`; an empty cloud for a blind view.
    PointCloud scan_from(const Eigen::Isometry3d& T_map_body, Rng& rng) const;

    TankScene scene_;
    std::string name_;
    double voxel_m_;
    sim::World world_;
    PointCloud map_;
    std::unique_ptr<sim::RayCaster> caster_;
    std::unique_ptr<sim::DepthCamera> camera_;
    std::unique_ptr<sim::SpinningLidar> lidar_;
};

/// Truth perturbed uniformly by ±`trans_m` / ±`rot_rad` per DoF (only x, y, yaw when `planar`),
/// composed in (x, y, z, roll, pitch, yaw) parameters as Stein-ICP's (stein_icp.hpp).
Eigen::Isometry3d perturbed(const Eigen::Isometry3d& T, double trans_m, double rot_rad, bool planar,
                            Rng& rng);

}  // namespace scantling::bench
