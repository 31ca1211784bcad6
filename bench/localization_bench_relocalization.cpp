// Our re-localisation of one frame for the localisation benchmark. Its pieces are private to
// the Localizer; they are reproduced here from the public API exactly as
// localizer_relocalization.cpp chains them for a start without a prior (correlative search over
// the compartment, two ICP passes per candidate, the attitude, overlap and degeneracy gates, the
// ambiguity rule), so that its speed and its success can be set against the baseline frame by
// frame. Not reproduced: the inside-the-map check (a candidate's body outside every compartment).
#include <algorithm>
#include <cmath>

#include <scantling/core/se3.hpp>
#include <scantling/core/voxel_grid.hpp>
#include <scantling/registration/icp.hpp>
#include <scantling/registration/quality.hpp>

#include "localization_bench.hpp"

namespace scantling::bench {
namespace {

namespace loc = scantling::localization;
/// One candidate after ICP: the body pose, its overlap with the map, and whether the view
/// leaves a direction free.
struct Verified {
    Eigen::Isometry3d T_world_body = Eigen::Isometry3d::Identity();
    double overlap = 0.0;
    bool degenerate = false;
};

/// Localizer::verify: a coarse ICP pass on the scan at refine_voxel_m, the overlap gate on it,
/// then the polish at the tracking's tight gate, which must converge.
std::optional<Verified> verify(const PointCloud& scan, const Eigen::Isometry3d& guess,
                               const LocalizationData& d, const loc::LocalizerConfig& c) {
    const loc::RelocalizationConfig& rc = c.relocalization;
    registration::IcpConfig icp = rc.refine;
    const loc::MapRegion& map = d.map->whole();
    const double voxel = c.gates.overlap.voxel_size_m;
    const PointCloud thin = voxel_downsample(scan, {rc.refine_voxel_m, c.parallel});
    const auto coarse = registration::align(thin, map.cloud, *map.tree, guess, icp);
    if (registration::overlap_ratio(transformed(thin, coarse.T_target_source), *map.tree, voxel,
                                    c.parallel) < c.gates.overlap.min_overlap) {
        return std::nullopt;
    }
    icp.max_correspondence_distance_m = rc.polish_correspondence_distance_m;
    const auto r = registration::align(scan, map.cloud, *map.tree, coarse.T_target_source, icp);
    if (!r.converged) return std::nullopt;
    return Verified{r.T_target_source * d.T_body_sensor.inverse(),
                    registration::overlap_ratio(transformed(scan, r.T_target_source), *map.tree,
                                                voxel, c.parallel),
                    r.degeneracy.degenerate || !r.covariance};
}

/// The gates a candidate of a start without a prior meets in Localizer::gate_candidate:
/// attitude against the IMU, overlap, a view that fixes every direction (no speed or
/// Mahalanobis gate without a previous pose; the inside-the-map check is left out).
bool passes_gates(const Verified& v, const LocFrame& f, const loc::GateConfig& gates) {
    return registration::check_attitude(v.T_world_body.linear(), f.R_world_body_imu, gates.attitude)
               .passed &&
           v.overlap >= gates.overlap.min_overlap && !v.degenerate;
}

double yaw_of(const Eigen::Matrix3d& R) { return std::atan2(R(1, 0), R(0, 0)); }

/// Localizer::ambiguity: another place (or heading) that explains the frame about as well.
bool ambiguous(const std::vector<Verified>& passed, const Verified& best,
               const loc::RelocalizationConfig& rc) {
    for (const Verified& other : passed) {
        const double distance =
            (other.T_world_body.translation() - best.T_world_body.translation()).norm();
        const double yaw = std::abs(std::remainder(
            yaw_of(other.T_world_body.linear()) - yaw_of(best.T_world_body.linear()), 2 * M_PI));
        const bool elsewhere = distance > rc.ambiguity_distance_m || yaw > rc.ambiguity_yaw_rad;
        if (elsewhere && other.overlap >= best.overlap - rc.ambiguity_overlap_margin) return true;
    }
    return false;
}

/// The frame's scan in the gravity-aligned body frame (roll and pitch from the IMU, yaw 0):
/// T_gravity_sensor, the frame the 4-DoF search works in.
Eigen::Isometry3d gravity_from_sensor(const LocFrame& f, const Eigen::Isometry3d& T_body_sensor) {
    const Eigen::Vector3d rpy = euler_zyx_from_rotation(f.R_world_body_imu);
    Eigen::Isometry3d T_gravity_body = Eigen::Isometry3d::Identity();
    T_gravity_body.linear() = rotation_from_euler_zyx(rpy.x(), rpy.y(), 0.0);
    return T_gravity_body * T_body_sensor;
}

}  // namespace

/// Correlative search over the frame's compartment, every candidate verified and gated, the
/// best by overlap unless ambiguous: T_world_body, or nullopt (no answer).
std::optional<Eigen::Isometry3d> relocalize(const LocFrame& f, const LocalizationData& d,
                                            const localization::LocalizerConfig& c,
                                            RelocTimes& times) {
    const auto t0 = Clock::now();
    const Eigen::Isometry3d T_gravity_sensor = gravity_from_sensor(f, d.T_body_sensor);
    const io::Compartment* box = io::find_compartment(*d.map->structure(), f.compartment);
    const auto candidates = loc::correlative_search(
        d.map->likelihood(), transformed(f.scan, T_gravity_sensor),
        box ? box->bounds : compute_bounds(d.map->whole().cloud), c.relocalization.correlative);
    const auto t1 = Clock::now();
    times.search_ms += ms_since(t0);
    std::vector<Verified> passed;
    for (const loc::SearchCandidate& s : candidates) {
        auto v = verify(f.scan, s.T_world_gravity * T_gravity_sensor, d, c);
        if (v && passes_gates(*v, f, c.gates)) passed.push_back(*v);
    }
    times.verify_ms += ms_since(t1);
    if (passed.empty()) return std::nullopt;
    const Verified& best =
        *std::max_element(passed.begin(), passed.end(),
                          [](const auto& a, const auto& b) { return a.overlap < b.overlap; });
    if (ambiguous(passed, best, c.relocalization)) return std::nullopt;
    return best.T_world_body;
}

}  // namespace scantling::bench
