#pragma once
/// @file
/// LiODOM, LiDAR-only odometry with a hashed cell map (SPEC §2, [D4.2 §II.2]).
///
/// Per sweep: edge extraction (edge_features.hpp) → pose estimation against the adaptive local
/// map from a constant-velocity prediction (edge_registration.hpp) → map update with the
/// optimised pose (mapping/cell_map.hpp) → local map for the next sweep (local_map.hpp).
/// run_odometry() runs extraction of sweep i+1 on one thread while sweep i is registered and
/// mapped on another (a two-stage in-order pipeline), so its results are identical to running
/// the stages one after the other.
///
/// Robustness (issue 4, item 7): an empty sweep, a sweep without edges, a failed
/// registration or an unreadable file does not stop the run; the frame is reported with its
/// status and its pose is carried on by the motion model (it is not added to the map). A gap
/// between stamps larger than `max_time_gap_s` is reported and the velocity is rescaled to it.
#include <Eigen/Geometry>
#include <cstddef>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <scantling/core/parallel.hpp>
#include <scantling/core/point_cloud.hpp>
#include <scantling/mapping/cell_map.hpp>
#include <scantling/odometry/edge_features.hpp>
#include <scantling/odometry/edge_registration.hpp>
#include <scantling/odometry/local_map.hpp>

namespace scantling::io {
struct ConfigNode;
}  // namespace scantling::io

namespace scantling::odometry {

struct LiodomConfig {
    EdgeExtractionConfig features{};
    EdgeRegistrationConfig registration{};
    mapping::CellMapConfig map{};
    LocalMapConfig local_map{};
    /// A gap between consecutive stamps above this is reported (seconds, > 0).
    double max_time_gap_s = 0.5;
    /// Predictions faster than this are clamped (the velocity is reset), m/s (> 0).
    double max_speed_mps = 40.0;
    /// The second sweep has no velocity to predict from: align it to the first with dense GICP
    /// (voxel of this size, metres; 0 = off, predict no motion). Without it a start in motion
    /// (a recording cut mid-drive, a pair of scans 0.5 m apart) begins from a wrong guess that
    /// sparse edges cannot always recover from.
    double bootstrap_voxel_m = 0.2;
    /// Sweeps whose planar points join the planes' local map besides its cells (the edges'
    /// count is local_map.num_recent_sweeps), >= 0. Planar points are dense: each recent sweep
    /// makes the per-sweep rebuild of that k-d tree larger.
    int plane_recent_sweeps = 1;
    /// Threads of the whole run: 1 runs the stages one after the other on the calling thread;
    /// 2 or more pipelines extraction against registration (0 = all hardware threads).
    ParallelConfig parallel{};
    void validate(std::string_view prefix = "odometry") const;
    /// One thread count for the run, the extraction and the registration (what `--threads`
    /// means): 1 makes the whole odometry serial.
    void set_num_threads(int threads) {
        parallel.num_threads = threads;
        features.parallel.num_threads = threads;
        registration.parallel.num_threads = threads;
    }
};

enum class FrameStatus {
    kOk,             ///< registered and added to the map
    kDegenerate,     ///< registered, some directions weakly observed (see num_degenerate)
    kFirst,          ///< the first usable sweep: it starts the map at the initial pose
    kNoEdges,        ///< too few edges (empty, NaN-only or featureless sweep): motion model
    kNotRegistered,  ///< too few correspondences: motion model
    kUnreadable,     ///< the sweep could not be read: motion model
};

/// "ok", "degenerate", "first", "no_edges", "not_registered", "unreadable".
const char* to_string(FrameStatus status);

struct FrameReport {
    std::size_t index = 0;
    double stamp_s = 0.0;
    /// The estimate, T_odom_sensor (odom = the initial pose's frame).
    Eigen::Isometry3d T_odom_sensor = Eigen::Isometry3d::Identity();
    FrameStatus status = FrameStatus::kOk;
    bool time_gap = false;  ///< the gap to the previous sweep exceeded max_time_gap_s
    std::string message;    ///< why the frame is not kOk (empty when it is)
    std::size_t num_points = 0;
    std::size_t num_edges = 0;
    std::size_t num_correspondences = 0;
    int iterations = 0;
    double rmse_m = 0.0;
    int num_degenerate = 0;
    double min_eigen_ratio = 0.0;  ///< of the registration's scaled information (degeneracy)
    /// JᵀWJ of the registration at T_odom_sensor: the information of a left perturbation
    /// exp(δ) · T_odom_sensor, δ = (ρ, ω) in the odom frame, for unit point-to-line noise
    /// (divide by σ² for metres). Zero when the frame was not registered.
    Matrix6d information = Matrix6d::Zero();
    std::size_t local_map_points = 0;
    double extract_ms = 0.0;  ///< wall time of the stages (not deterministic)
    double register_ms = 0.0;
    double map_ms = 0.0;
};

/// Relative sensor motion T_s(t0)_s(t1) between two stamps from another source (VIO, IMU,
/// wheel odometry), or nullopt when it has none for that interval. LiODOM starts each
/// registration from it instead of the constant-velocity model ("IMU and height may improve
/// [the initial guess]", [D4.2]), and degenerate directions keep its value, so a smooth hull
/// side does not stall the estimate.
using MotionPrior = std::function<std::optional<Eigen::Isometry3d>(double t0_s, double t1_s)>;

/// The sequential core: one sweep at a time (not thread-safe; extract() is const and may run
/// concurrently with register_and_map()).
class LidarOdometry {
  public:
    explicit LidarOdometry(const LiodomConfig& config = {},
                           const Eigen::Isometry3d& T_odom_initial = Eigen::Isometry3d::Identity());

    /// Use `prior` for the predictions from now on (empty: constant velocity).
    void set_motion_prior(MotionPrior prior) { prior_ = std::move(prior); }

    /// Stage 1: the sweep's edges (any thread).
    EdgeFeatures extract(const PointCloud& sweep) const;
    /// Stage 2: registers the edges of the next sweep, updates the map, returns the report
    /// (extract_ms is left to the caller). `stamp_s` is the sweep's start stamp.
    /// `motion_hint` (T_prev_this, optional) replaces the constant-velocity prediction while
    /// no velocity is known yet (the bootstrap of the second sweep).
    FrameReport register_and_map(const EdgeFeatures& edges, double stamp_s, std::size_t num_points,
                                 const std::optional<Eigen::Isometry3d>& motion_hint = {});
    /// Stage 2 for a sweep that could not be read: the motion model carries the pose.
    FrameReport skip_unreadable(double stamp_s, const std::string& message);
    /// Both stages.
    FrameReport process(const PointCloud& sweep);

    const LiodomConfig& config() const { return config_; }
    const mapping::CellMap& map() const { return map_; }
    const LocalMap& local_map() const { return local_map_; }
    const LocalMap& plane_local_map() const { return plane_local_map_; }
    std::size_t num_frames() const { return num_frames_; }
    /// Map, local map and motion-model state, bytes (estimate).
    std::size_t memory_bytes() const;

  private:
    Eigen::Isometry3d predict(double stamp_s, bool& time_gap,
                              const std::optional<Eigen::Isometry3d>& motion_hint = {}) const;
    void accept(const Eigen::Isometry3d& T, double stamp_s);
    /// Inserts the registered sweep's edges and planar points (at T) into their maps.
    void update_maps(const EdgeFeatures& edges, const Eigen::Isometry3d& T);

    LiodomConfig config_;
    mapping::CellMap map_;
    LocalMap local_map_;
    /// The planar points' map (empty unless features.max_planes_per_sector > 0).
    mapping::CellMap plane_map_;
    LocalMap plane_local_map_;
    Eigen::Isometry3d T_initial_;
    Eigen::Isometry3d T_last_ = Eigen::Isometry3d::Identity();
    /// Velocity as the twist per second of T_prev⁻¹ T_last (body frame).
    Vector6d velocity_per_s_ = Vector6d::Zero();
    double last_stamp_s_ = 0.0;
    MotionPrior prior_;
    bool has_pose_ = false;
    bool has_velocity_ = false;
    bool map_started_ = false;
    std::size_t num_frames_ = 0;
};

/// Reads sweep i (may throw scantling::Error: the frame is then reported as kUnreadable).
using SweepReader = std::function<PointCloud(std::size_t index)>;
/// Called once per frame, in order, from the registering thread.
using FrameCallback = std::function<void(const FrameReport& report)>;

/// Runs the odometry over `num_sweeps` sweeps (pipelined when config.parallel allows two
/// threads) and returns one report per sweep, in order. Deterministic: the same sweeps and
/// config give the same poses for any thread count.
std::vector<FrameReport> run_odometry(
    std::size_t num_sweeps, const SweepReader& read_sweep, const LiodomConfig& config,
    const FrameCallback& on_frame = {},
    const Eigen::Isometry3d& T_odom_initial = Eigen::Isometry3d::Identity(),
    const MotionPrior& prior = {});

/// Named presets: "kitti" (64-beam automotive LiDAR), "os1_drone" (Ouster OS1-64 on a MAV near
/// a hull or tank), "confined" (tanks a few metres wide). Throws ConfigError for another name.
LiodomConfig liodom_preset(std::string_view name);
/// The preset names, in the order above.
std::vector<std::string> liodom_preset_names();
/// Loads a YAML config: `preset: NAME` (optional, default kitti) then overrides of any field
/// ("features.max_range_m: 30"). Errors name the file, line and key.
LiodomConfig load_liodom_config(const std::string& path);
/// The same for a parsed YAML node (a section of a larger file, e.g. a mission scenario's
/// `stack.odometry`) applied over `base`, or over the preset the node names.
LiodomConfig liodom_config_from_node(const io::ConfigNode& node, const LiodomConfig& base);
/// Every field with its value and documentation, as YAML (for --print-config and the docs).
std::string describe_liodom_config(const LiodomConfig& config);

}  // namespace scantling::odometry
