#include "scantling/localization/localizer.hpp"

#include <fmt/format.h>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <chrono>
#include <cmath>

#include <scantling/core/error.hpp>
#include <scantling/core/voxel_grid.hpp>

namespace scantling::localization {

std::string_view to_string(FrameOutcome outcome) {
    switch (outcome) {
        case FrameOutcome::kRegistered:
            return "registered";
        case FrameOutcome::kRelocalized:
            return "relocalized";
        case FrameOutcome::kRejected:
            return "rejected";
        case FrameOutcome::kSkipped:
            return "skipped";
    }
    return "?";
}

std::string_view to_string(LocalizerMode mode) {
    switch (mode) {
        case LocalizerMode::kNone:
            return "none";
        case LocalizerMode::kTracking:
            return "tracking";
        case LocalizerMode::kRelocalization:
            return "relocalization";
    }
    return "?";
}

Matrix6d usable_covariance(const std::optional<Matrix6d>& covariance, const Matrix6d& information,
                           double free_variance) {
    if (covariance && covariance->allFinite()) return *covariance;
    Eigen::SelfAdjointEigenSolver<Matrix6d> eig(0.5 * (information + information.transpose()));
    const double largest = std::max(eig.eigenvalues().maxCoeff(), 0.0);
    Vector6d variances;
    for (int k = 0; k < 6; ++k) {
        const double lambda = eig.eigenvalues()[k];
        // A direction the information barely constrains carries no weight in the filter.
        variances[k] = lambda > 1e-6 * largest && lambda > 0.0
                           ? std::min(1.0 / lambda, free_variance)
                           : free_variance;
    }
    return eig.eigenvectors() * variances.asDiagonal() * eig.eigenvectors().transpose();
}

namespace {

/// The filter's config for the odometry input: the IMU's tilt (velocity input) wanders more
/// than a VIO's (velocity_odometry.hpp).
PoseFilterConfig odometry_filter_config(const LocalizerConfig& c) {
    PoseFilterConfig f = c.filter;
    if (c.odometry_input == OdometryInput::kVelocity) {
        f.tilt_random_walk_rad_per_sqrt_m = std::max(
            f.tilt_random_walk_rad_per_sqrt_m, c.velocity_odometry.tilt_random_walk_rad_per_sqrt_m);
    }
    return f;
}

}  // namespace

Localizer::Localizer(std::shared_ptr<const LocalizationMap> map, LocalizerConfig config)
    : map_(std::move(map)),
      config_(std::move(config)),
      filter_(odometry_filter_config(config_)),
      attitude_(config_.attitude),
      velocity_odometry_(config_.velocity_odometry),
      compartments_(map_ ? map_->structure() : nullptr) {
    if (!map_) throw InputError("localizer: no map");
    config_.validate();
    compartments_.reset(config_.start_compartment);
}

void Localizer::warn(double stamp_s, std::string source, std::string message) {
    warnings_.push_back({stamp_s, std::move(source), std::move(message)});
}

void Localizer::set_initial_pose(const AbsolutePose& pose) {
    const MeasurementStatus s = filter_.initialize(pose);
    if (s == MeasurementStatus::kInvalid || s == MeasurementStatus::kTooOld) {
        throw InputError(fmt::format("initial pose at {} s: {}", pose.stamp_s, to_string(s)));
    }
    last_accepted_.reset();
    lost_ = false;
}

void Localizer::add_imu(const io::ImuRecord& sample) {
    const ImuStatus s = attitude_.add(sample);
    if (s == ImuStatus::kGapRestart) {
        warn(sample.stamp_s, "imu",
             fmt::format("gap of more than {} s before this sample: attitude restarted from the "
                         "accelerometer",
                         config_.attitude.max_gap_s));
    } else if (s == ImuStatus::kOutOfOrder || s == ImuStatus::kInvalid) {
        warn(sample.stamp_s, "imu", fmt::format("sample ignored ({})", to_string(s)));
    }
}

std::optional<FusedState> Localizer::add_vio(const io::VioRecord& vio) {
    const io::VioRecord sample =
        config_.odometry_input == OdometryInput::kVelocity
            ? velocity_odometry_.integrate(vio, attitude_.attitude_at(vio.stamp_s))
            : vio;
    const OdometryStatus s = filter_.add_odometry(sample);
    switch (s) {
        case OdometryStatus::kOutOfOrder:
            warn(sample.stamp_s, "vio", "sample not after the previous one: ignored");
            return filter_.state();
        case OdometryStatus::kJump:
            warn(sample.stamp_s, "vio", "jump: body pose held across it, re-localising");
            lost_ = true;
            break;
        case OdometryStatus::kDropout:
            dropout_s_ += last_vio_stamp_s_ ? sample.stamp_s - *last_vio_stamp_s_ : 0.0;
            if (dropout_s_ >= config_.dropout_relocalization_s && !lost_ && filter_.initialized()) {
                warn(sample.stamp_s, "vio",
                     fmt::format("dropout longer than {} s: re-localising",
                                 config_.dropout_relocalization_s));
                lost_ = true;
            }
            break;
        default:
            dropout_s_ = 0.0;
            break;
    }
    last_vio_stamp_s_ = sample.stamp_s;
    while (!queue_.empty() && queue_.front().cloud.stamp_s <= sample.stamp_s) {
        process(queue_.front());
        queue_.pop_front();
    }
    const std::optional<FusedState> state = filter_.state();
    if (state) {
        const Eigen::Vector3d p = state->T_world_body.translation();
        if (last_fused_position_) compartments_.move(*last_fused_position_, p);
        last_fused_position_ = p;
    }
    return state;
}

void Localizer::add_depth_frame(std::size_t index, PointCloud frame_sensor,
                                const Eigen::Isometry3d& T_body_sensor) {
    if (!std::isfinite(frame_sensor.stamp_s)) {
        warn(0.0, "depth", fmt::format("frame {} has a non-finite stamp: ignored", index));
        return;
    }
    try {
        check_consistent(frame_sensor, "depth frame");
    } catch (const InputError& e) {
        warn(frame_sensor.stamp_s, "depth", fmt::format("frame {} ignored: {}", index, e.what()));
        return;
    }
    if (last_frame_stamp_s_ && frame_sensor.stamp_s <= *last_frame_stamp_s_) {
        warn(frame_sensor.stamp_s, "depth",
             fmt::format("frame {} is not after the previous frame: ignored", index));
        return;
    }
    last_frame_stamp_s_ = frame_sensor.stamp_s;
    queue_.push_back({index, std::move(frame_sensor), T_body_sensor});
}

void Localizer::finish() {
    for (const QueuedFrame& f : queue_) {
        FrameEvent e;
        e.index = f.index;
        e.stamp_s = f.cloud.stamp_s;
        e.gate = "no_odometry";
        e.reason = "no VIO sample after the frame";
        events_.push_back(std::move(e));
    }
    queue_.clear();
}

std::vector<FrameEvent> Localizer::take_events() { return std::exchange(events_, {}); }
std::vector<LocalizerWarning> Localizer::take_warnings() { return std::exchange(warnings_, {}); }

std::optional<Eigen::Matrix3d> Localizer::imu_attitude(double stamp_s) const {
    if (auto R = attitude_.attitude_at(stamp_s)) return R;
    // Without an IMU, the VIO's gravity-aligned attitude (its roll and pitch are absolute).
    if (const auto V = filter_.odometry_at(stamp_s)) return Eigen::Matrix3d(V->linear());
    return std::nullopt;
}

void Localizer::process(const QueuedFrame& frame) {
    FrameEvent event;
    event.index = frame.index;
    event.stamp_s = frame.cloud.stamp_s;
    const double t = frame.cloud.stamp_s;
    if (last_attempt_s_ && config_.registration_period_s > 0.0 &&
        t - *last_attempt_s_ < config_.registration_period_s - 1e-9) {
        event.gate = "rate";
        events_.push_back(std::move(event));
        return;
    }
    const auto start = std::chrono::steady_clock::now();
    PointCloud finite = remove_non_finite(frame.cloud);
    PointCloud scan =
        finite.empty() ? finite
                       : voxel_downsample(finite, {map_->config().voxel_size_m, config_.parallel});
    event.num_points = scan.size();
    if (scan.size() < config_.min_points) {
        event.gate = "no_returns";
        event.reason = fmt::format("{} points after downsampling, fewer than {}", scan.size(),
                                   config_.min_points);
        events_.push_back(std::move(event));
        return;
    }
    last_attempt_s_ = t;
    const bool tracking_now = filter_.initialized() && !lost_ && !config_.global_every_frame;
    event = tracking_now ? track(scan, finite, frame, std::move(event))
                         : relocalize(scan, frame, std::move(event));
    event.compute_ms =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    events_.push_back(std::move(event));
}

std::string Localizer::common_gates(const Eigen::Isometry3d& T_world_body, double overlap,
                                    double stamp_s, const Eigen::Matrix3d& R_world_body_imu,
                                    std::string& reason) const {
    const registration::GateResult attitude = registration::check_attitude(
        T_world_body.linear(), R_world_body_imu, config_.gates.attitude);
    if (!attitude.passed) {
        reason = attitude.reason;
        return "attitude";
    }
    const registration::GateResult o = registration::check_overlap(overlap, config_.gates.overlap);
    if (!o.passed) {
        reason = o.reason;
        return "overlap";
    }
    if (last_accepted_ && stamp_s > last_accepted_->stamp_s) {
        const auto V = filter_.odometry_at(stamp_s);
        if (V) {
            // Where the previous absolute pose says the body is now, moved by the VIO.
            const Eigen::Isometry3d expected =
                last_accepted_->T_world_body * last_accepted_->T_odom_body.inverse() * *V;
            const registration::GateResult speed = registration::check_speed(
                expected, last_accepted_->stamp_s, T_world_body, stamp_s, config_.gates.speed);
            if (!speed.passed) {
                reason = speed.reason;
                return "speed";
            }
        }
    }
    return "";
}

void Localizer::accept(const AbsolutePose& pose, bool restart) {
    const MeasurementStatus s = restart ? filter_.initialize(pose) : filter_.update(pose);
    if (s != MeasurementStatus::kApplied) {
        warn(pose.stamp_s, "filter", fmt::format("absolute pose not applied: {}", to_string(s)));
        return;
    }
    const auto V = filter_.odometry_at(pose.stamp_s);
    last_accepted_ =
        AcceptedPose{pose.stamp_s, pose.T_world_body, V ? *V : Eigen::Isometry3d::Identity()};
    consecutive_rejections_ = 0;
    failed_restricted_relocalizations_ = 0;
    lost_ = false;
    dropout_s_ = 0.0;
    if (restart || compartments_.current() < 0) {
        // A new start: where the pose is; from then on, through the manholes (add_vio).
        compartments_.locate(pose.T_world_body.translation());
        last_fused_position_.reset();
    }
}

void Localizer::reject(FrameEvent& event) {
    event.outcome = FrameOutcome::kRejected;
    ++consecutive_rejections_;
    if (event.mode == LocalizerMode::kTracking &&
        consecutive_rejections_ >= config_.max_rejections) {
        lost_ = true;
        consecutive_rejections_ = 0;
        warn(event.stamp_s, "localizer",
             fmt::format("{} tracking frames rejected in a row: re-localising",
                         config_.max_rejections));
    } else if (event.mode == LocalizerMode::kRelocalization &&
               consecutive_rejections_ >= config_.max_rejections && last_accepted_) {
        // The motion filter must not lock the robot out forever after a wrong absolute pose.
        last_accepted_.reset();
        consecutive_rejections_ = 0;
        warn(event.stamp_s, "localizer", "previous absolute pose forgotten by the speed gate");
    }
}

}  // namespace scantling::localization
