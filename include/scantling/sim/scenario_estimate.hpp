#pragma once
/// @file
/// The size of the recording a scenario will write, estimated before anything runs (issue 10:
/// "a run that would write terabytes is refused by validation, with a stated estimate").
///
/// Per sensor: firings in [0, duration) at the sensor's effective rate (the preset's when
/// `rate_hz` is 0) times the bytes of one firing, an upper estimate from the frame size: points
/// × bytes per point for LiDARs (rings × columns; a return per beam), width × height × channels
/// for images, beams × bins for sonar pings, one text row for the other sensors; plus the
/// ground-truth row of every clock tick and, once the world is built, the CAD map (area /
/// spacing² points). Compression and missed returns only make the real recording smaller.
///
/// Scenario::validate refuses a scenario whose estimate exceeds kMaxRecordingBytes (ConfigError
/// stating the estimate and the keys that drive it); callers (the CLI) announce the estimate
/// when it is over kLargeRecordingBytes. The runner can add the CAD map once the world is
/// built: check_recording_estimate(estimate_recording(scenario, surface_area(world.mesh))).

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <scantling/sim/scenario.hpp>

namespace scantling::sim {

/// Largest recording a scenario may write: 64 GiB.
inline constexpr std::uint64_t kMaxRecordingBytes = std::uint64_t{64} << 30;
/// A recording worth announcing before it runs: 1 GiB.
inline constexpr std::uint64_t kLargeRecordingBytes = std::uint64_t{1} << 30;

/// One sensor's share of the recording.
struct SensorOutputEstimate {
    std::string key;            ///< "sensors[0]"
    std::string type;           ///< "spinning_lidar"
    double rate_hz = 0.0;       ///< effective rate
    std::uint64_t firings = 0;  ///< in [0, duration)
    std::uint64_t bytes_per_firing = 0;
    std::uint64_t bytes = 0;  ///< firings × bytes_per_firing (saturating)
    /// What sizes one firing, e.g. "64 rings x columns 1024" (keys as written in YAML).
    std::string frame_size;
};

struct RecordingEstimate {
    double duration_s = 0.0;  ///< simulated (the trajectory's when duration_s is 0)
    std::int64_t ticks = 0;   ///< clock ticks: floor(duration / dt) + 1
    std::uint64_t ground_truth_bytes = 0;
    std::vector<SensorOutputEstimate> sensors;
    std::uint64_t map_bytes = 0;    ///< CAD map; 0 when the world's area is not given
    std::uint64_t total_bytes = 0;  ///< everything above (saturating)

    /// One line: "recording estimate 70.3 GiB over duration_s = 600 s: sensors[0]
    /// (spinning_lidar, rate_hz 20, 64 rings x columns 2048) 12000 x 3.5 MiB = 42 GiB; ...",
    /// largest share first.
    std::string describe() const;
};

/// Simulated duration: `duration_s`, or the trajectory's when it is 0 (ConfigError for a bad
/// trajectory).
double scenario_duration(const Scenario& scenario);

/// Estimate of everything the run writes. `world_area_m2`: the built world's surface area
/// (core surface_area), to include the CAD map when `export.world` is on. ConfigError for a
/// sensor whose config is invalid (the same message the runner would give).
RecordingEstimate estimate_recording(const Scenario& scenario,
                                     std::optional<double> world_area_m2 = std::nullopt);

/// estimate_recording(scenario).total_bytes.
std::uint64_t estimate_recording_bytes(const Scenario& scenario);

/// Throws ConfigError "recording estimate 70.3 GiB is more than the 64 GiB a run may write: ..."
/// (describe()) when the estimate exceeds kMaxRecordingBytes.
void check_recording_estimate(const RecordingEstimate& estimate);

/// "1.5 GiB", "12.0 MiB", "512 bytes".
std::string format_bytes(std::uint64_t bytes);

}  // namespace scantling::sim
