// Global re-localisation: correlative 4-DoF search (or FPFH + the robust solver) in one
// compartment or all, each candidate verified by ICP and the gates (localizer.hpp).
// of one compartment or of all (localizer.hpp).
#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include <scantling/core/normals.hpp>
#include <scantling/core/se3.hpp>
#include <scantling/core/voxel_grid.hpp>
#include <scantling/localization/localizer.hpp>
#include <scantling/registration/feature_matching.hpp>
#include <scantling/registration/quality.hpp>
#include <scantling/registration/robust_registration.hpp>

namespace scantling::localization {

struct Localizer::Candidate {
    int compartment = -1;
    Eigen::Isometry3d T_world_body = Eigen::Isometry3d::Identity();
    Matrix6d covariance = Matrix6d::Identity();
    double overlap = 0.0;
    bool degenerate = false;  ///< the view leaves a direction of the pose free
    std::string gate;         ///< "" when it passed the gates
    std::string reason;
};

namespace {

/// The body's roll and pitch from the IMU, yaw zero: the frame the 4-DoF solver works in.
Eigen::Matrix3d tilt_only(const Eigen::Matrix3d& R_world_body) {
    const Eigen::Vector3d rpy = euler_zyx_from_rotation(R_world_body);
    return rotation_from_euler_zyx(rpy.x(), rpy.y(), 0.0);
}

double yaw_difference_rad(const Eigen::Matrix3d& a, const Eigen::Matrix3d& b) {
    const Eigen::Vector3d x = a * Eigen::Vector3d::UnitX();
    const Eigen::Vector3d y = b * Eigen::Vector3d::UnitX();
    return std::abs(std::remainder(std::atan2(x.y(), x.x()) - std::atan2(y.y(), y.x()), 2 * M_PI));
}

/// The search box around a prediction: its position ± prior_sigmas σ, at least the minimum.
Aabb box_around(const AbsolutePose& prior, const RelocalizationConfig& rc) {
    const Eigen::Vector3d p = prior.T_world_body.translation();
    const double r = std::max(rc.prior_sigmas * largest_position_sigma_m(prior.covariance, p),
                              rc.min_prior_radius_m);
    return Aabb{p - Eigen::Vector3d::Constant(r), p + Eigen::Vector3d::Constant(r)};
}

bool inside_structure(const io::StructuralMap* structure, const Eigen::Vector3d& p) {
    return structure == nullptr || structure->compartments.empty() ||
           io::compartment_at(*structure, p).has_value();
}

}  // namespace

std::vector<int> Localizer::regions_to_search() {
    const io::StructuralMap* structure = map_->structure();
    if (structure == nullptr || structure->compartments.empty()) return {-1};
    const bool restricted =
        compartments_.current() >= 0 &&
        failed_restricted_relocalizations_ < config_.relocalization.failures_before_global;
    if (restricted) return {compartments_.current()};
    std::vector<int> all;
    for (const io::Compartment& c : structure->compartments) all.push_back(c.id);
    return all;
}

std::optional<Localizer::Candidate> Localizer::verify(const PointCloud& scan_sensor,
                                                      const Eigen::Isometry3d& T_world_sensor_guess,
                                                      const Eigen::Isometry3d& T_body_sensor,
                                                      int compartment) const {
    const RelocalizationConfig& rc = config_.relocalization;
    registration::IcpConfig icp = rc.refine;
    icp.parallel = config_.parallel;
    const MapRegion& map = map_->whole();
    // The coarse pass on a thinner scan: it only has to bring the guess into the tight gate.
    const PointCloud thin = voxel_downsample(scan_sensor, {rc.refine_voxel_m, config_.parallel});
    const registration::RegistrationResult coarse =
        registration::align(thin, map.cloud, *map.tree, T_world_sensor_guess, icp);
    // It need not converge (few iterations): the polish that follows must. A candidate whose
    // thin scan already misses the overlap gate costs no second pass (in a tank almost every
    // point lies within the wide gate of some wall, so the pass's own fitness does not tell).
    const double thin_overlap =
        registration::overlap_ratio(transformed(thin, coarse.T_target_source), *map.tree,
                                    config_.gates.overlap.voxel_size_m, config_.parallel);
    if (thin_overlap < config_.gates.overlap.min_overlap) return std::nullopt;
    icp.max_correspondence_distance_m = rc.polish_correspondence_distance_m;
    const registration::RegistrationResult r =
        registration::align(scan_sensor, map.cloud, *map.tree, coarse.T_target_source, icp);
    if (!r.converged) return std::nullopt;
    Candidate c;
    c.compartment = compartment;
    c.T_world_body = r.T_target_source * T_body_sensor.inverse();
    c.covariance = usable_covariance(r.covariance, r.information, 100.0);
    c.degenerate = r.degeneracy.degenerate || !r.covariance;
    c.overlap = registration::overlap_ratio(transformed(scan_sensor, r.T_target_source), *map.tree,
                                            config_.gates.overlap.voxel_size_m, config_.parallel);
    return c;
}

std::vector<Localizer::Candidate> Localizer::relocalize_in(
    const PointCloud& scan_gravity, const PointCloud& scan_sensor,
    const Eigen::Isometry3d& T_gravity_sensor, const Eigen::Isometry3d& T_body_sensor,
    int compartment, const std::optional<Aabb>& near) const {
    std::vector<Eigen::Isometry3d> guesses;  // T_world_gravity
    const RelocalizationConfig& rc = config_.relocalization;
    if (rc.method == RelocalizationMethod::kCorrelative) {
        const io::StructuralMap* structure = map_->structure();
        const io::Compartment* c =
            structure ? io::find_compartment(*structure, compartment) : nullptr;
        Aabb box = c ? c->bounds : compute_bounds(map_->whole().cloud);
        if (near) {  // around the prediction
            box.min = box.min.cwiseMax(near->min);
            box.max = box.max.cwiseMin(near->max);
        }
        CorrelativeSearchConfig search = rc.correlative;
        search.parallel = config_.parallel;
        for (const SearchCandidate& s :
             correlative_search(map_->likelihood(), scan_gravity, box, search)) {
            guesses.push_back(s.T_world_gravity);
        }
    } else if (auto g = fpfh_guess(scan_gravity, compartment)) {
        guesses.push_back(*g);
    }
    std::vector<Candidate> out;
    for (const Eigen::Isometry3d& T_world_gravity : guesses) {
        if (auto c = verify(scan_sensor, T_world_gravity * T_gravity_sensor, T_body_sensor,
                            compartment)) {
            out.push_back(*c);
        }
    }
    return out;
}

std::optional<Eigen::Isometry3d> Localizer::fpfh_guess(const PointCloud& scan_gravity,
                                                       int compartment) const {
    PointCloud with_normals = scan_gravity;
    NormalEstimationConfig normals;
    normals.num_neighbors = config_.relocalization.normal_neighbors;
    normals.viewpoint = Eigen::Vector3d::Zero();  // near the sensor, in the body-origin frame
    normals.parallel = config_.parallel;
    estimate_normals(with_normals, normals);
    registration::FpfhConfig fpfh = map_->config().fpfh;
    fpfh.parallel = config_.parallel;
    const registration::FeatureMatrix descriptors = registration::compute_fpfh(with_normals, fpfh);
    const MapRegion& region = map_->region(compartment);
    registration::MatchConfig match = config_.relocalization.match;
    match.parallel = config_.parallel;
    const std::vector<registration::Correspondence> matches =
        registration::match_features(descriptors, region.descriptors, match);
    registration::RobustRegistrationConfig robust = config_.relocalization.robust;
    robust.parallel = config_.parallel;
    const registration::RobustRegistrationResult global =
        registration::robust_register(with_normals, region.cloud, matches, robust);
    if (!global.registration.converged) return std::nullopt;
    return global.registration.T_target_source;
}

std::optional<AbsolutePose> Localizer::relocalization_prior(double stamp_s) const {
    // While the filter still has an estimate (lost after rejections, a dropout or a jump), the
    // search stays near its prediction and a candidate must agree with it; after
    // failures_before_global failures the prior is dropped too (it may be the wrong one). The
    // sources' pipeline (global_every_frame) registers without a prior.
    if (config_.global_every_frame || !filter_.initialized() ||
        failed_restricted_relocalizations_ >= config_.relocalization.failures_before_global) {
        return std::nullopt;
    }
    return filter_.predict(stamp_s);
}

void Localizer::gate_candidate(Candidate& c, double stamp_s,
                               const Eigen::Matrix3d& R_world_body_imu,
                               const std::optional<AbsolutePose>& prior) const {
    c.gate = common_gates(c.T_world_body, c.overlap, stamp_s, R_world_body_imu, c.reason);
    if (!c.gate.empty()) return;
    if (c.degenerate && !prior) {  // nothing would fill the free direction
        c.gate = "degenerate";
        c.reason = "the view leaves a direction of the pose free (a single wall)";
    } else if (prior) {
        const auto in = filter_.innovation({stamp_s, c.T_world_body, c.covariance});
        if (in && in->mahalanobis_squared > config_.gates.mahalanobis_threshold) {
            c.gate = "mahalanobis";
            c.reason = fmt::format("d² = {:.1f} against the prediction > {:.1f}",
                                   in->mahalanobis_squared, config_.gates.mahalanobis_threshold);
        }
    }
    if (c.gate.empty() && !inside_structure(map_->structure(), c.T_world_body.translation())) {
        c.gate = "inside_map";
        c.reason = "the body would be outside every compartment";
    }
}

std::string Localizer::ambiguity(const std::vector<Candidate>& passed,
                                 const Candidate& best) const {
    const RelocalizationConfig& rc = config_.relocalization;
    for (const Candidate& other : passed) {
        const Eigen::Vector3d a = best.T_world_body.translation();
        const Eigen::Vector3d b = other.T_world_body.translation();
        const bool elsewhere =
            (b - a).norm() > rc.ambiguity_distance_m ||
            yaw_difference_rad(other.T_world_body.linear(), best.T_world_body.linear()) >
                rc.ambiguity_yaw_rad;
        if (elsewhere && other.overlap >= best.overlap - rc.ambiguity_overlap_margin) {
            return fmt::format(
                "({:.2f}, {:.2f}, {:.2f}) and ({:.2f}, {:.2f}, {:.2f}) explain the frame alike "
                "(overlap {:.3f} vs {:.3f})",
                a.x(), a.y(), a.z(), b.x(), b.y(), b.z(), best.overlap, other.overlap);
        }
    }
    return "";
}

FrameEvent Localizer::relocalize(const PointCloud& scan, const QueuedFrame& frame,
                                 FrameEvent event) {
    event.mode = LocalizerMode::kRelocalization;
    const double t = frame.cloud.stamp_s;
    const std::optional<Eigen::Matrix3d> R_imu = imu_attitude(t);
    if (!R_imu) {
        event.gate = "no_attitude";
        event.reason = "neither IMU nor VIO attitude at the capture time";
        return event;
    }
    Eigen::Isometry3d T_gravity_body = Eigen::Isometry3d::Identity();
    T_gravity_body.linear() = tilt_only(*R_imu);
    const Eigen::Isometry3d T_gravity_sensor = T_gravity_body * frame.T_body_sensor;
    const PointCloud scan_gravity = transformed(scan, T_gravity_sensor);
    const std::optional<AbsolutePose> prior = relocalization_prior(t);
    const std::optional<Aabb> near =
        prior ? std::optional(box_around(*prior, config_.relocalization)) : std::nullopt;
    const std::vector<int> regions = regions_to_search();
    const bool restricted =
        regions.size() == 1 && regions.front() >= 0 && map_->structure()->compartments.size() > 1;
    event.compartment = regions.size() == 1 ? regions.front() : -1;
    std::vector<Candidate> passed;
    std::optional<Candidate> first_failed;
    for (const int compartment : regions) {
        for (Candidate& c : relocalize_in(scan_gravity, scan, T_gravity_sensor, frame.T_body_sensor,
                                          compartment, near)) {
            gate_candidate(c, t, *R_imu, prior);
            if (c.gate.empty()) {
                passed.push_back(c);
            } else if (!first_failed || c.overlap > first_failed->overlap) {
                first_failed = c;
            }
        }
    }
    if (passed.empty()) {
        event.gate = first_failed ? first_failed->gate : "registration";
        event.reason = first_failed ? first_failed->reason : "no candidate pose converged";
        if (first_failed) {
            event.T_world_body = first_failed->T_world_body;
            event.overlap = first_failed->overlap;
        }
        if (restricted || prior) ++failed_restricted_relocalizations_;
        reject(event);
        return event;
    }
    const Candidate& best =
        *std::max_element(passed.begin(), passed.end(),
                          [](const auto& a, const auto& b) { return a.overlap < b.overlap; });
    event.T_world_body = best.T_world_body;
    event.overlap = best.overlap;
    event.compartment = best.compartment;
    event.reason = ambiguity(passed, best);
    if (!event.reason.empty()) {
        event.gate = "ambiguous";
        reject(event);
        return event;
    }
    // With a prior the result is fused with it (its free directions keep the prediction's); the
    // sources' pipeline fuses every global registration as an update once running; otherwise
    // the filter starts again from it.
    const bool restart = !prior && !(config_.global_every_frame && filter_.initialized() && !lost_);
    accept(AbsolutePose{t, best.T_world_body, best.covariance}, restart);
    event.outcome = restart ? FrameOutcome::kRelocalized : FrameOutcome::kRegistered;
    return event;
}

}  // namespace scantling::localization
