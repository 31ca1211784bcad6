#include "scantling/localization/landmark_correction.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <limits>
#include <optional>

#include <scantling/core/voxel_grid.hpp>

#include "detail/config_checks.hpp"

namespace scantling::localization {
namespace {

/// The map's frame normal at a landmark, pointing into the landmark's compartment (the side
/// its face looks at).
Eigen::Vector3d map_frame_normal(const io::StructuralMap& map, const io::Landmark& landmark) {
    Eigen::Vector3d axis = Eigen::Vector3d::UnitX();
    for (const io::FrameLine& f : map.frames) {
        if (f.number == landmark.frame) axis = f.axis;
    }
    const io::Compartment* c = io::find_compartment(map, landmark.compartment);
    if (c != nullptr && axis.dot(c->bounds.center() - landmark.position) < 0.0) axis = -axis;
    return axis;
}

/// The compartment and those its connections open onto (a manhole shows the next bay's
/// frame): the map tree's neighbourhood. Empty = all.
std::vector<int> admissible_compartments(const io::StructuralMap& map, int compartment) {
    if (compartment < 0) return {};
    std::vector<int> out{compartment};
    for (const io::Connection& c : map.connections) {
        if (c.compartment_a == compartment && c.compartment_b >= 0) out.push_back(c.compartment_b);
        if (c.compartment_b == compartment && c.compartment_a >= 0) out.push_back(c.compartment_a);
    }
    return out;
}

bool candidate(const io::Landmark& m, const std::vector<int>& compartments) {
    return m.kind == io::LandmarkKind::FrameLongitudinal &&
           (compartments.empty() || std::find(compartments.begin(), compartments.end(),
                                              m.compartment) != compartments.end());
}

/// Nearest admissible map landmark of every detection, then one detection per map landmark
/// (the nearest wins).
std::vector<LandmarkMatch> associate(const perception::FrameLandmarks& seen,
                                     const io::StructuralMap& map, int compartment, double gate_m) {
    const std::vector<int> compartments = admissible_compartments(map, compartment);
    std::vector<LandmarkMatch> matches;
    for (std::size_t k = 0; k < seen.landmarks.size(); ++k) {
        const perception::DetectedLandmark& d = seen.landmarks[k];
        LandmarkMatch best{-1, static_cast<int>(k), d.position, gate_m};
        for (const io::Landmark& m : map.landmarks) {
            // The face the camera sees must face the landmark's compartment.
            if (!candidate(m, compartments) || d.frame_normal.dot(map_frame_normal(map, m)) <= 0.0)
                continue;
            const double distance = (m.position - d.position).norm();
            if (distance < best.distance_m)
                best = {m.id, static_cast<int>(k), d.position, distance};
        }
        if (best.map_landmark >= 0) matches.push_back(best);
    }
    std::sort(matches.begin(), matches.end(), [](const LandmarkMatch& a, const LandmarkMatch& b) {
        return a.map_landmark != b.map_landmark ? a.map_landmark < b.map_landmark
                                                : a.distance_m < b.distance_m;
    });
    matches.erase(std::unique(matches.begin(), matches.end(),
                              [](const LandmarkMatch& a, const LandmarkMatch& b) {
                                  return a.map_landmark == b.map_landmark;
                              }),
                  matches.end());
    return matches;
}

/// The rotation of the predicted world frame that turns the seen frame normals onto the map's.
Eigen::Matrix3d normal_alignment(const std::vector<LandmarkMatch>& matches,
                                 const perception::FrameLandmarks& seen,
                                 const io::StructuralMap& map) {
    Eigen::Vector3d n_seen = Eigen::Vector3d::Zero(), n_map = Eigen::Vector3d::Zero();
    Eigen::Vector3d reference = Eigen::Vector3d::UnitX();
    for (const LandmarkMatch& m : matches) {
        const io::Landmark& l = map.landmarks[static_cast<std::size_t>(m.map_landmark)];
        const Eigen::Vector3d a = map_frame_normal(map, l);
        const Eigen::Vector3d& b =
            seen.landmarks[static_cast<std::size_t>(m.detection)].frame_normal;
        // Frames facing opposite ways (both ends of a bay in view) must not cancel.
        if (n_map.isZero()) reference = a;
        const double s = a.dot(reference) < 0.0 ? -1.0 : 1.0;
        n_map += s * a;
        n_seen += s * b;
    }
    return Eigen::Quaterniond::FromTwoVectors(n_seen, n_map).toRotationMatrix();
}

Eigen::Vector3d offset_of(const LandmarkMatch& m, const Eigen::Matrix3d& R,
                          const io::StructuralMap& map) {
    return map.landmarks[static_cast<std::size_t>(m.map_landmark)].position - R * m.seen_world;
}

/// The largest set of matches whose offsets (map − rotated seen) agree within `tolerance_m`
/// of one another's mean: a spurious line (a bracket, a weld seam, a plate edge) makes a
/// landmark that no other agrees with. Ties keep the earlier seed (deterministic).
std::vector<LandmarkMatch> consensus(const std::vector<LandmarkMatch>& matches,
                                     const Eigen::Matrix3d& R, const io::StructuralMap& map,
                                     double tolerance_m) {
    std::vector<LandmarkMatch> best;
    for (const LandmarkMatch& seed : matches) {
        const Eigen::Vector3d o = offset_of(seed, R, map);
        std::vector<LandmarkMatch> agree;
        for (const LandmarkMatch& m : matches) {
            if ((offset_of(m, R, map) - o).norm() <= tolerance_m) agree.push_back(m);
        }
        if (agree.size() > best.size()) best = std::move(agree);
    }
    return best;
}

Eigen::Isometry3d correction(const std::vector<LandmarkMatch>& inliers, const Eigen::Matrix3d& R,
                             const io::StructuralMap& map) {
    Eigen::Isometry3d delta = Eigen::Isometry3d::Identity();
    delta.linear() = R;
    Eigen::Vector3d offset = Eigen::Vector3d::Zero();
    for (const LandmarkMatch& m : inliers) offset += offset_of(m, R, map);
    delta.translation() = offset / static_cast<double>(inliers.size());
    return delta;
}

/// (δp, δθ) covariance at the body: landmarks fix position and two rotation axes.
Matrix6d correction_covariance(const Eigen::Vector3d& frame_normal, std::size_t n,
                               const LandmarkCorrectionConfig& c) {
    Matrix6d C = Matrix6d::Zero();
    C.topLeftCorner<3, 3>() = Eigen::Matrix3d::Identity() *
                              (c.position_sigma_m * c.position_sigma_m / static_cast<double>(n));
    const Eigen::Vector3d u = frame_normal.normalized();
    const Eigen::Matrix3d along = u * u.transpose();
    C.bottomRightCorner<3, 3>() =
        along * (c.free_rotation_sigma_rad * c.free_rotation_sigma_rad) +
        (Eigen::Matrix3d::Identity() - along) * (c.normal_sigma_rad * c.normal_sigma_rad);
    return C;
}

}  // namespace

void LandmarkCorrectionConfig::validate(std::string_view prefix) const {
    detector.validate(fmt::format("{}.detector", prefix));
    detail::require_positive(voxel_size_m, prefix, "voxel_size_m");
    detail::require_positive(association_distance_m, prefix, "association_distance_m");
    detail::require_positive(max_residual_m, prefix, "max_residual_m");
    detail::require(min_landmarks >= 1, prefix, "min_landmarks", static_cast<double>(min_landmarks),
                    ">= 1");
    detail::require_positive(position_sigma_m, prefix, "position_sigma_m");
    detail::require_positive(normal_sigma_rad, prefix, "normal_sigma_rad");
    detail::require_positive(free_rotation_sigma_rad, prefix, "free_rotation_sigma_rad");
}

LandmarkCorrection correct_with_landmarks(const PointCloud& frame_sensor,
                                          const AbsolutePose& predicted,
                                          const Eigen::Isometry3d& T_body_sensor,
                                          const io::StructuralMap& map, int compartment,
                                          const LandmarkCorrectionConfig& config) {
    config.validate();
    LandmarkCorrection out;
    out.pose = predicted;
    const Eigen::Isometry3d T_world_sensor = predicted.T_world_body * T_body_sensor;
    const PointCloud seen = transformed(
        frame_sensor.empty() ? frame_sensor : voxel_downsample(frame_sensor, config.voxel_size_m),
        T_world_sensor);
    out.detected =
        perception::detect_frame_landmarks(seen, T_world_sensor.translation(), config.detector);
    if (out.detected.landmarks.empty()) {
        out.failure = "no_landmarks";
        out.reason = fmt::format("{} frames, {} stiffeners seen", out.detected.frame_planes.size(),
                                 out.detected.lines.size());
        return out;
    }
    out.matches = associate(out.detected, map, compartment, config.association_distance_m);
    if (out.matches.size() < config.min_landmarks) {
        out.failure = "no_match";
        out.reason = fmt::format("{} of {} landmarks matched within {} m, fewer than {}",
                                 out.matches.size(), out.detected.landmarks.size(),
                                 config.association_distance_m, config.min_landmarks);
        return out;
    }
    const Eigen::Matrix3d R = normal_alignment(out.matches, out.detected, map);
    std::vector<LandmarkMatch> inliers = consensus(out.matches, R, map, config.max_residual_m);
    if (inliers.size() < config.min_landmarks) {
        out.failure = "residual";
        out.reason = fmt::format(
            "at most {} of {} matched landmarks agree within {} m, fewer than {}", inliers.size(),
            out.matches.size(), config.max_residual_m, config.min_landmarks);
        return out;
    }
    out.outliers = out.matches.size() - inliers.size();
    out.matches = std::move(inliers);
    const Eigen::Isometry3d delta = correction(out.matches, R, map);
    out.pose.T_world_body = delta * predicted.T_world_body;
    const Eigen::Vector3d normal = delta.linear() * out.detected.landmarks.front().frame_normal;
    out.pose.covariance =
        twist_covariance(correction_covariance(normal, out.matches.size(), config),
                         out.pose.T_world_body.translation());
    return out;
}

}  // namespace scantling::localization
