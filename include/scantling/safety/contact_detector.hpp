#pragma once
/// @file
/// Out-of-view contact detection from the IMU (SPEC §5 mitigations; issue 14, item 6): an
/// underwater drone (Blueye X3 class, ~9 kg, ≤ 1 m/s) that bumps into a hull appendage behind
/// or below it, outside its camera and sonar, sees a short spike in its IMU's specific force
/// that its own commands do not explain. The detector reports it once and recommends a back-off
/// so the vehicle can see the obstacle and bypass it.
///
/// Per IMU sample (IMU frame = body frame, R = R_world_body from the estimator):
///
///   a_world  = R f_body + g_world,           g_world = (0, 0, −g)   (world z up)
///   raw      = a_world − a_expected_world     (what the commands do not explain)
///   residual = raw − b,   b = running mean of raw (exponential, time constant τ ≈ 1 s)
///
/// The running mean b absorbs what varies slowly: the accelerometer bias, a tilt error of the
/// estimator (g sin 3° ≈ 0.5 m/s²), an unmodelled part of a gentle manoeuvre. It is frozen
/// while |residual| is above the threshold, so a spike does not leak into it. A contact is a
/// run of `min_samples_above` consecutive samples with |residual| > threshold, after a warm-up
/// of τ and outside the refractory time of the previous contact; it is reported at the sample
/// that completes the run (≈ 15 ms into the spike at 200 Hz), so the back-off starts early.
///
/// Sign of the back-off: the obstacle pushes the vehicle away from itself, so the impulse (the
/// residual's direction) points from the obstacle towards the vehicle. Backing off along the
/// impulse direction moves away from the obstacle: a bump into something at +y pushes the
/// vehicle to −y and the back-off velocity is −y. The velocity is 3D in the world frame (a
/// 4-DoF ROV controls surge, sway, heave and yaw, so all three components are reachable).
///
/// A run that stays above the threshold longer than `max_spike_duration_s` is not an impact
/// (a collision at ≤ 1 m/s lasts tens of ms) but a step in an offset (an attitude estimate
/// that jumped, a thrust the caller did not pass): it may have been reported once, then the
/// running mean restarts from the current value so it does not report again every refractory
/// period.
///
/// Not modelled: the lever-arm accelerations of an IMU away from the centre of mass (ω², ω̇
/// terms; small at the ROV's turn rates), and contacts too soft to exceed the threshold
/// (stopping from v over t_c gives ≈ v / t_c: 3 m/s² catches 0.15 m/s stopped within 50 ms).
///
/// Input contract: non-finite stamp, specific force, angular rate, attitude or expected
/// acceleration, or a zero quaternion: InputError naming the field. A stamp not after the
/// previous one is ignored and counted (`num_out_of_order`). Units: seconds, m/s², m/s.
/// Cost O(1) per sample, no allocation. Not thread-safe (one detector per IMU stream).

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cstddef>
#include <optional>
#include <string_view>

#include <scantling/io/recording.hpp>

namespace scantling::safety {

/// Defaults for a Blueye X3 class ROV: thrust accelerations < 1 m/s², wave and turbulence
/// noise on the accelerometer < 0.5 m/s², an IMU at 100–200 Hz.
struct ContactDetectorConfig {
    /// |residual| above this is a contact, m/s². 3 m/s² is three times the largest thrust
    /// acceleration and six times the wave/turbulence noise, so neither triggers even when
    /// the caller passes no expected acceleration; it still catches 0.15 m/s stopped in 50 ms.
    double threshold_mps2 = 3.0;
    /// Consecutive samples above the threshold before a contact is reported: 3 (15 ms at
    /// 200 Hz) rejects a single corrupted sample; a 50 ms impact has ~10.
    std::size_t min_samples_above = 3;
    /// After a contact, no new one for this long, s: the rebound and the vehicle's thrust
    /// reaction after one impact are the same contact, reported once.
    double refractory_s = 1.0;
    /// τ of the running mean removed from the residual, s: slow terms (bias, tilt error,
    /// unmodelled manoeuvres) go, an impact (tens of ms) stays. Also the warm-up time.
    double baseline_time_constant_s = 1.0;
    /// A run above the threshold longer than this is an offset step, not an impact, s.
    double max_spike_duration_s = 0.5;
    /// g, m/s² (the specific force at rest is +g along world z).
    double gravity_mps2 = 9.81;
    /// Back-off speed, m/s: slow enough to stay controllable near a hull, fast enough to gain
    /// 0.4 m in the back-off time, which brings a nearby appendage into the camera's view.
    double back_off_speed_mps = 0.2;
    /// How long the back-off velocity is recommended after the contact, s.
    double back_off_duration_s = 2.0;

    /// Throws ConfigError naming "<prefix>.<field>", its value and what was expected: all
    /// durations, speeds, g and the threshold finite > 0 (refractory ≥ 0), min samples ≥ 1.
    void validate(std::string_view prefix = "contact_detector") const;
};

/// One contact, as reported once by ContactDetector::add.
struct Contact {
    double stamp_s = 0.0;  ///< stamp of the sample that completed the run
    /// Unit vector, world frame: mean residual direction over the run, i.e. the push the
    /// vehicle received (from the obstacle towards the vehicle).
    Eigen::Vector3d impulse_direction_world = Eigen::Vector3d::UnitX();
    double peak_residual_mps2 = 0.0;  ///< largest |residual| in the run up to the report
    /// back_off_speed · impulse direction, world frame, m/s.
    Eigen::Vector3d back_off_velocity_world_mps = Eigen::Vector3d::Zero();
    double back_off_until_s = 0.0;  ///< stamp_s + back_off_duration_s
};

class ContactDetector {
  public:
    /// Validates `config` (ConfigError).
    explicit ContactDetector(const ContactDetectorConfig& config = {});

    /// One IMU sample with the estimator's attitude at its stamp (q_world_body, normalised
    /// here) and the acceleration the commands should produce (world frame; zero when the
    /// caller has no model). Returns a new contact once; nullopt otherwise.
    std::optional<Contact> add(
        const io::ImuRecord& imu, const Eigen::Quaterniond& q_world_body,
        const Eigen::Vector3d& a_expected_world_mps2 = Eigen::Vector3d::Zero());

    /// True in [contact stamp, contact stamp + back_off_duration) of the last contact.
    bool backing_off(double t_s) const;
    /// The recommended velocity (world, m/s) while backing off; zero otherwise.
    Eigen::Vector3d back_off_velocity(double t_s) const;

    const std::optional<Contact>& last_contact() const { return last_contact_; }
    /// The last accepted sample's residual (after the running mean), world frame, m/s².
    const Eigen::Vector3d& residual_world_mps2() const { return residual_; }
    std::size_t num_contacts() const { return num_contacts_; }
    std::size_t num_out_of_order() const { return num_out_of_order_; }
    /// Runs longer than max_spike_duration_s that restarted the running mean.
    std::size_t num_baseline_restarts() const { return num_baseline_restarts_; }
    const ContactDetectorConfig& config() const { return config_; }

  private:
    void update_baseline(const Eigen::Vector3d& raw, double dt_s);
    std::optional<Contact> on_above(const Eigen::Vector3d& raw, double stamp_s);
    bool may_report(double stamp_s) const;
    Contact make_contact(double stamp_s) const;

    ContactDetectorConfig config_;
    bool started_ = false;
    double start_s_ = 0.0;
    double last_stamp_s_ = 0.0;
    Eigen::Vector3d baseline_ = Eigen::Vector3d::Zero();
    double baseline_samples_ = 0.0;  ///< for the warm-up mean (1/n weights)
    Eigen::Vector3d residual_ = Eigen::Vector3d::Zero();
    std::size_t run_samples_ = 0;
    double run_start_s_ = 0.0;
    Eigen::Vector3d run_sum_ = Eigen::Vector3d::Zero();
    double run_peak_mps2_ = 0.0;
    std::optional<Contact> last_contact_;
    std::size_t num_contacts_ = 0;
    std::size_t num_out_of_order_ = 0;
    std::size_t num_baseline_restarts_ = 0;
};

}  // namespace scantling::safety
