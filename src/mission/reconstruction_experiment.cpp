#include <scantling/mission/reconstruction_experiment.hpp>

#include <algorithm>
#include <cmath>

#include <scantling/core/config_checks.hpp>
#include <scantling/core/random.hpp>
#include <scantling/sim/helix_trajectory.hpp>
#include <scantling/sim/pinhole_camera.hpp>
#include <scantling/sim/ray_caster.hpp>
#include <scantling/sim/sensor_mount.hpp>

namespace scantling::mission {
namespace {

constexpr double kTwoPi = 2.0 * std::numbers::pi;
constexpr std::uint64_t kSunlightStream = 0x5u;

/// The simulated world and sensor, and the running map of one experiment.
struct Flight {
    Flight(const ReconstructionExperimentConfig& c)
        : config(c),
          world(sim::build_cylinder(c.cylinder)),
          caster(world.mesh, world.surface_tags),
          scene{caster, world.metadata},
          stereo(c.stereo),
          map(map_config(c)),
          rng(c.seed),
          sun_rng(rng.split(kSunlightStream)) {}

    static perception::FeatureMapConfig map_config(const ReconstructionExperimentConfig& c) {
        perception::FeatureMapConfig m = c.feature_map;
        m.intrinsics = c.stereo.intrinsics;
        m.min_depth_m = c.stereo.min_depth_m;
        m.max_depth_m = c.stereo.max_depth_m;
        return m;
    }

    /// The sunlight model (file comment of the header): keep with p = a + (1 − a) max(0, n·s).
    bool lit(const Eigen::Vector3d& p_world) {
        if (!config.sunlight) return true;
        const Eigen::Vector3d sun(std::cos(config.sun_azimuth_rad),
                                  std::sin(config.sun_azimuth_rad), 0.0);
        const Eigen::Vector2d radial = p_world.head<2>();
        // Points well inside the rim lie on the end caps (normal ±z, horizontal sun: n·s = 0).
        const bool on_side = radial.norm() > 0.9 * config.cylinder.radius_m;
        const double ns = on_side ? radial.normalized().dot(sun.head<2>()) : 0.0;
        const double p = config.shadow_ambient + (1.0 - config.shadow_ambient) * std::max(0.0, ns);
        return sun_rng.uniform() < p;
    }

    void frame(const Eigen::Isometry3d& T_world_body) {
        const PointCloud cloud = stereo.scan(scene, T_world_body, rng, clock_s, config.parallel);
        const Eigen::Isometry3d T_world_camera = T_world_body * config.stereo.T_body_sensor;
        std::vector<Eigen::Vector3d> kept;
        kept.reserve(cloud.points.size());
        for (const Eigen::Vector3d& p : cloud.points) {
            if (lit(T_world_camera * p)) kept.push_back(p);
        }
        raw_points += kept.size();
        map.insert(kept, T_world_camera);
        ++frames;
    }

    /// Flies `trajectory`, one frame every 1 / frame_rate_hz from its start (end excluded).
    void fly(const sim::Trajectory& trajectory) {
        const double dt = 1.0 / config.frame_rate_hz;
        const auto n = static_cast<std::size_t>(std::ceil(trajectory.duration_s() / dt - 1e-9));
        for (std::size_t k = 0; k < n; ++k) {
            frame(trajectory.at(static_cast<double>(k) * dt).T_world_body);
            clock_s += dt;
        }
        clock_s += trajectory.duration_s() - static_cast<double>(n) * dt;
    }

    std::vector<Eigen::Vector3d> points() const { return map.confirmed_cloud().points; }

    const ReconstructionExperimentConfig& config;
    sim::World world;
    sim::RayCaster caster;
    sim::SceneView scene;
    sim::StereoPoints stereo;
    perception::FeatureMap map;
    Rng rng;
    Rng sun_rng;
    double clock_s = 0.0;
    std::size_t frames = 0;
    std::size_t raw_points = 0;
};

/// A flat arc of the circle about the origin facing the centre, from `from_rad` by `arc_rad`.
sim::OrbitTrajectory arc(const ReconstructionExperimentConfig& config, double radius_m,
                         double height_m, double from_rad, double arc_rad) {
    sim::OrbitTrajectoryConfig orbit;
    orbit.centre_m = Eigen::Vector3d(0.0, 0.0, height_m);
    orbit.radius_m = radius_m;
    orbit.angular_rate_radps = arc_rad >= 0.0 ? config.omega_radps : -config.omega_radps;
    orbit.start_angle_rad = from_rad;
    orbit.turns = std::max(std::abs(arc_rad), 1e-9) / kTwoPi;
    orbit.heading = sim::OrbitHeading::kFaceCentre;
    return sim::OrbitTrajectory(orbit);
}

/// Vertical take-off at azimuth `angle_rad` facing the centre, from z 0 to `height_m`.
sim::OrbitTrajectory takeoff(const ReconstructionExperimentConfig& config, double radius_m,
                             double height_m, double angle_rad) {
    // An orbit with a negligible angular rate is a vertical climb facing the centre.
    sim::OrbitTrajectoryConfig climb;
    climb.radius_m = radius_m;
    climb.start_angle_rad = angle_rad;
    climb.climb_rate_mps = config.takeoff_climb_mps;
    const double duration_s = height_m / config.takeoff_climb_mps;
    climb.angular_rate_radps = 1e-12;
    climb.turns = duration_s * climb.angular_rate_radps / kTwoPi;
    return sim::OrbitTrajectory(climb);
}

planning::SectorCounts sectors(const std::vector<Eigen::Vector3d>& points, double start_rad) {
    return planning::count_sectors(points, Eigen::Vector2d::Zero(), start_rad);
}

}  // namespace

sim::StereoPointsConfig uav3d_stereo_points() {
    sim::StereoPointsConfig stereo;
    stereo.intrinsics = sim::uav3d_camera().intrinsics;
    stereo.rate_hz = 30.0;
    stereo.baseline_m = 0.12;
    stereo.feature_spacing_px = 20.0;
    Eigen::Matrix3d R_body_optical;
    R_body_optical.col(0) = -Eigen::Vector3d::UnitY();  // optical x: right = −body y
    R_body_optical.col(1) = -Eigen::Vector3d::UnitZ();  // optical y: down = −body z
    R_body_optical.col(2) = Eigen::Vector3d::UnitX();   // optical z: forward = body x
    stereo.T_body_sensor = Eigen::Isometry3d::Identity();
    stereo.T_body_sensor.linear() = R_body_optical;
    return stereo;
}

void ReconstructionExperimentConfig::validate(std::string_view prefix) const {
    using namespace config_checks;
    cylinder.validate("cylinder");
    stereo.validate("stereo_points");
    feature_map.validate("feature_map");
    require_positive(omega_radps, prefix, "omega_radps");
    require_positive(frame_rate_hz, prefix, "frame_rate_hz");
    require(std::isfinite(sun_azimuth_rad), prefix, "sun_azimuth_rad", sun_azimuth_rad, "finite");
    require(shadow_ambient >= 0.0 && shadow_ambient <= 1.0, prefix, "shadow_ambient",
            shadow_ambient, "in [0, 1]");
    require_positive(takeoff_climb_mps, prefix, "takeoff_climb_mps");
    parallel.validate("parallel");
}

HelixRun run_helix(const ReconstructionExperimentConfig& config, double radius_m,
                   double rotations) {
    config.validate();
    config_checks::require_positive(radius_m, "reconstruction", "helix radius_m");
    config_checks::require_positive(rotations, "reconstruction", "helix rotations");
    HelixRun run;
    run.radius_m = radius_m;
    run.rotations = rotations;
    run.duration_s = kTwoPi * rotations / config.omega_radps;
    run.v_z_mps = config.cylinder.height_m / run.duration_s;  // covers the height once
    sim::HelixTrajectoryConfig helix;
    helix.radius_m = radius_m;
    helix.omega_radps = config.omega_radps;
    helix.v_z_mps = run.v_z_mps;
    helix.rotations = rotations;
    Flight flight(config);
    flight.fly(sim::HelixTrajectory(helix));
    run.path_length_m = run.duration_s * std::hypot(radius_m * config.omega_radps, run.v_z_mps);
    run.frames = flight.frames;
    run.raw_points = flight.raw_points;
    const std::vector<Eigen::Vector3d> points = flight.points();
    run.confirmed_points = points.size();
    run.sectors = sectors(points, 0.0);
    return run;
}

namespace {

PlannerStepRow row(const Flight& flight, std::size_t step, double start_rad) {
    const std::vector<Eigen::Vector3d> points = flight.points();
    PlannerStepRow r;
    r.step = step;
    r.total = points.size();
    r.sectors = sectors(points, start_rad);
    return r;
}

}  // namespace

PlannerRun run_planner(const ReconstructionExperimentConfig& config,
                       const planning::PointDensityPlannerConfig& planner_config) {
    config.validate();
    planning::PointDensityPlanner planner(planner_config);
    Flight flight(config);
    const planning::ObjectEstimate fixed = planning::locate_object({}, planner_config);
    PlannerRun run;
    run.flight_radius_m = fixed.flight_radius_m;
    run.flight_height_m = planner_config.flight_height_m.value_or(config.cylinder.height_m / 2);
    const double r = run.flight_radius_m;
    const double z = run.flight_height_m;
    double angle = planner_config.start_angle_rad;
    flight.fly(takeoff(config, r, z, angle));
    flight.fly(arc(config, r, z, angle, kTwoPi));  // step 0: one turn, positive direction
    PlannerStepRow step0 = row(flight, 0, planner_config.start_angle_rad);
    step0.arc_rad = kTwoPi;
    step0.turns = 1.0;
    step0.path_length_m = z + kTwoPi * r;
    step0.time_s = flight.clock_s;
    run.steps.push_back(step0);
    {
        planning::PointDensityPlannerConfig unfixed = planner_config;
        unfixed.fixed_centre_xy_m.reset();
        unfixed.fixed_flight_radius_m = 0.0;
        run.voxel_estimate = planning::locate_object(flight.points(), unfixed);
    }
    for (;;) {
        const std::vector<Eigen::Vector3d> points = flight.points();
        const planning::ObjectEstimate object = planning::locate_object(points, planner_config);
        const planning::DensityStep step = planner.next(points, object, angle);
        if (step.status != planning::PlannerStatus::kTarget) {
            run.stop = step.status;
            break;
        }
        flight.fly(arc(config, r, z, angle, step.arc_rad));
        angle += step.arc_rad;
        PlannerStepRow next = row(flight, step.step, planner_config.start_angle_rad);
        next.target_sector = step.sector;
        next.arc_rad = step.arc_rad;
        next.turns = run.steps.back().turns + std::abs(step.arc_rad) / kTwoPi;
        next.path_length_m = run.steps.back().path_length_m + r * std::abs(step.arc_rad);
        next.time_s = flight.clock_s;
        run.steps.push_back(next);
    }
    run.frames = flight.frames;
    return run;
}

}  // namespace scantling::mission
