#pragma once
/// @file
/// Absolute localisation in a known, self-similar confined space (SPEC §7): a depth camera's
/// frames registered against the map, gated, and fused with VIO (pose_filter.hpp).
///
/// Per depth frame, in capture order, once the VIO has passed the frame's stamp (so the filter
/// can predict the pose at that instant):
/// - skipped when not due (registration_period_s), with too few returns, or without attitude;
/// - tracking (the filter is running): ICP (point-to-plane, front faces, localisation of the
///   map) or Stein-ICP from the filter's prediction at the capture time, with its covariance,
///   or the frame × longitudinal landmarks seen matched with the map's (art. B,
///   landmark_correction.hpp; a frame without any is skipped, not rejected), or the column's
///   3-DoF registration on its detected wall and downcomer (art. F, column_registration.hpp;
///   a frame without them in view is skipped as "not_registrable");
/// - re-localisation (at the start without a known pose, after max_rejections rejected frames,
///   after a VIO dropout or jump): FPFH of the frame in a gravity-aligned frame (roll and pitch
///   from the IMU), matched against the cached map descriptors of the compartment the robot is
///   in, or of every compartment when that is unknown (a "kidnapped" start), the 4-DoF robust
///   solver (x, y, z, yaw) with hypothesis verification, then ICP. Candidates from different
///   places that explain the frame about equally well are refused as ambiguous: in a tank of
///   identical bays one view often fits several, and a wrong bay is worse than waiting;
/// - gates, in this order: attitude against the IMU, overlap with the map, speed against the
///   previous absolute pose moved by the VIO (the jump, not the vehicle's own motion), and
///   (tracking only) the Mahalanobis distance to the prediction;
/// - a passed registration updates the filter at the capture time (late, by its compute time);
///   a re-localisation restarts it.
/// The compartment the robot is in changes only through a manhole (compartment_tracker.hpp).
/// Every frame yields one FrameEvent; odometry, IMU and frame faults yield warnings.
///
/// Thread-safety: not thread-safe (one per robot); the map is shared read-only. Deterministic
/// for a given input order and config, for any thread count.

#include <Eigen/Geometry>
#include <cstddef>
#include <deque>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <scantling/core/point_cloud.hpp>
#include <scantling/io/recording.hpp>
#include <scantling/localization/attitude_estimator.hpp>
#include <scantling/localization/compartment_tracker.hpp>
#include <scantling/localization/localization_map.hpp>
#include <scantling/localization/localizer_config.hpp>
#include <scantling/localization/pose_filter.hpp>
#include <scantling/localization/velocity_odometry.hpp>

namespace scantling::localization {

enum class FrameOutcome { kRegistered, kRelocalized, kRejected, kSkipped };
std::string_view to_string(FrameOutcome outcome);

enum class LocalizerMode { kNone, kTracking, kRelocalization };
std::string_view to_string(LocalizerMode mode);

/// What happened to one depth frame.
struct FrameEvent {
    std::size_t index = 0;
    double stamp_s = 0.0;  ///< capture time
    FrameOutcome outcome = FrameOutcome::kSkipped;
    LocalizerMode mode = LocalizerMode::kNone;
    /// The gate that rejected it ("attitude", "overlap", "speed", "mahalanobis", "ambiguous",
    /// "registration", "inside_map"), or why it was skipped ("rate", "no_returns", ...).
    std::string gate;
    std::string reason;          ///< with the numbers
    int compartment = -1;        ///< the compartment searched or registered in (-1: all / unknown)
    std::size_t num_points = 0;  ///< after downsampling
    /// The registration's body pose, when one was computed (also for rejected ones).
    std::optional<Eigen::Isometry3d> T_world_body;
    double overlap = 0.0;
    double mahalanobis_squared = 0.0;   ///< tracking only
    std::size_t landmarks_seen = 0;     ///< landmark tracking: frame × longitudinal detections
    std::size_t landmarks_matched = 0;  ///< of those, matched with the map's
    double compute_ms = 0.0;            ///< wall time of the registration (not deterministic)
};

/// A fault in the inputs that the localiser worked around.
struct LocalizerWarning {
    double stamp_s = 0.0;
    std::string source;  ///< "vio", "imu", "depth"
    std::string message;
};

class Localizer {
  public:
    /// Validates the config (ConfigError). `map` must outlive nothing: it is shared.
    Localizer(std::shared_ptr<const LocalizationMap> map, LocalizerConfig config);

    /// A known start: the body pose at its stamp (applied once the VIO reaches it).
    void set_initial_pose(const AbsolutePose& pose);
    void add_imu(const io::ImuRecord& sample);
    /// Adds a VIO sample, then processes the frames it lets through. Returns the fused state at
    /// this sample (nullopt before the first absolute pose). With odometry_input: velocity the
    /// sample's position is ignored: its body velocity is integrated with the IMU's roll and
    /// pitch and its own yaw steps (velocity_odometry.hpp; feed the IMU samples up to its
    /// stamp first).
    std::optional<FusedState> add_vio(const io::VioRecord& sample);
    /// Queues a depth frame (sensor frame, NaN = no return) with the camera's mounting.
    void add_depth_frame(std::size_t index, PointCloud frame_sensor,
                         const Eigen::Isometry3d& T_body_sensor);
    /// Frames that never saw a later VIO sample are skipped ("no_odometry").
    void finish();

    std::vector<FrameEvent> take_events();
    std::vector<LocalizerWarning> take_warnings();
    std::optional<FusedState> state() const { return filter_.state(); }
    bool tracking() const { return filter_.initialized() && !lost_; }
    const LocalizerConfig& config() const { return config_; }

  private:
    struct QueuedFrame {
        std::size_t index = 0;
        PointCloud cloud;
        Eigen::Isometry3d T_body_sensor = Eigen::Isometry3d::Identity();
    };
    struct AcceptedPose {
        double stamp_s = 0.0;
        Eigen::Isometry3d T_world_body = Eigen::Isometry3d::Identity();
        Eigen::Isometry3d T_odom_body = Eigen::Isometry3d::Identity();
    };
    struct Candidate;

    void process(const QueuedFrame& frame);
    FrameEvent track(const PointCloud& scan, const PointCloud& finite, const QueuedFrame& frame,
                     FrameEvent event);
    /// The landmark correction of a frame, or nullopt with the event's gate set (landmarks).
    std::optional<AbsolutePose> landmark_pose(const PointCloud& finite, const QueuedFrame& frame,
                                              const AbsolutePose& predicted, FrameEvent& event);
    /// The column's 3-DoF registration of a frame, or nullopt with the event's gate set
    /// (column; a frame without the structure in view is skipped, not rejected).
    std::optional<AbsolutePose> column_pose(const PointCloud& finite, const QueuedFrame& frame,
                                            const AbsolutePose& predicted,
                                            const Eigen::Matrix3d& R_world_body_imu,
                                            FrameEvent& event);
    /// The gates of a tracking measurement, then the filter update (or the rejection).
    FrameEvent gate_and_fuse(const AbsolutePose& measured, const PointCloud& scan,
                             const QueuedFrame& frame, const Eigen::Matrix3d& R_world_body_imu,
                             FrameEvent event);
    FrameEvent relocalize(const PointCloud& scan, const QueuedFrame& frame, FrameEvent event);
    std::vector<int> regions_to_search();
    std::vector<Candidate> relocalize_in(const PointCloud& scan_gravity,
                                         const PointCloud& scan_sensor,
                                         const Eigen::Isometry3d& T_gravity_sensor,
                                         const Eigen::Isometry3d& T_body_sensor, int compartment,
                                         const std::optional<Aabb>& near) const;
    /// FPFH + robust 4-DoF solver: T_world_gravity, or nullopt.
    std::optional<Eigen::Isometry3d> fpfh_guess(const PointCloud& scan_gravity,
                                                int compartment) const;
    /// Two ICP passes from a guess, with the result's overlap (nullopt: did not converge).
    std::optional<Candidate> verify(const PointCloud& scan_sensor,
                                    const Eigen::Isometry3d& T_world_sensor_guess,
                                    const Eigen::Isometry3d& T_body_sensor, int compartment) const;
    /// The prediction a re-localisation searches near and must agree with (see the .cpp).
    std::optional<AbsolutePose> relocalization_prior(double stamp_s) const;
    /// Every gate of a re-localisation candidate (sets c.gate and c.reason when one fails).
    void gate_candidate(Candidate& c, double stamp_s, const Eigen::Matrix3d& R_world_body_imu,
                        const std::optional<AbsolutePose>& prior) const;
    /// Why `best` is ambiguous among `passed` ("" when it is not).
    std::string ambiguity(const std::vector<Candidate>& passed, const Candidate& best) const;
    /// Attitude, overlap and speed gates; "" when all pass, else the gate's name (reason set).
    std::string common_gates(const Eigen::Isometry3d& T_world_body, double overlap, double stamp_s,
                             const Eigen::Matrix3d& R_world_body_imu, std::string& reason) const;
    void accept(const AbsolutePose& pose, bool restart);
    void reject(FrameEvent& event);
    std::optional<Eigen::Matrix3d> imu_attitude(double stamp_s) const;
    void warn(double stamp_s, std::string source, std::string message);

    std::shared_ptr<const LocalizationMap> map_;
    LocalizerConfig config_;
    PoseFilter filter_;
    AttitudeEstimator attitude_;
    VelocityOdometry velocity_odometry_;  ///< odometry_input: velocity
    std::deque<QueuedFrame> queue_;
    std::vector<FrameEvent> events_;
    std::vector<LocalizerWarning> warnings_;
    std::optional<AcceptedPose> last_accepted_;
    std::optional<double> last_attempt_s_;
    std::optional<double> last_vio_stamp_s_;
    std::optional<double> last_frame_stamp_s_;
    /// The compartment the robot is in, followed through the manholes (relocalisation and
    /// landmark association are restricted to it).
    CompartmentTracker compartments_;
    std::optional<Eigen::Vector3d> last_fused_position_;
    int consecutive_rejections_ = 0;
    int failed_restricted_relocalizations_ = 0;
    double dropout_s_ = 0.0;
    bool lost_ = false;
};

/// Registration covariance usable by the filter: `covariance` when present, otherwise the
/// inverse of `information` with the directions it does not constrain given `free_variance`.
Matrix6d usable_covariance(const std::optional<Matrix6d>& covariance, const Matrix6d& information,
                           double free_variance);

}  // namespace scantling::localization
