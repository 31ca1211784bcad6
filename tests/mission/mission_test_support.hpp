#pragma once
// Shared by the closed-loop tests: a short go-to flight beside the hull in the dry dock.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <string>

namespace scantling::mission::test {

/// 12 s in the dry dock beside the hull: hover at the start, fly 2 m along the hull and 0.5 m
/// up to the recorded point A, with the default scenario's sensors (UWB anchors included).
inline const std::string kGoTo = R"(
simulation:
  world: {type: ship_hull, ship_hull: {surroundings: {environment: dry_dock}}}
  vehicle: {type: mav}
  sensors:
    - {type: spinning_lidar, columns: 512, T_body_sensor: {xyz: [0.0, 0.0, 0.1]}}
    - {type: imu, rate_hz: 200}
    - {type: range_finder, rate_hz: 20, T_body_sensor: {xyz: [0.0, 0.0, -0.05], rpy_deg: [0.0, 90.0, 0.0]}}
    - {type: barometer, rate_hz: 20}
    - type: uwb
      anchors:
        - {id: 1, position_world: [2.0, 14.0, 0.5]}
        - {id: 2, position_world: [28.0, 14.0, 0.5]}
        - {id: 3, position_world: [28.0, 14.0, 8.0]}
        - {id: 4, position_world: [2.0, 14.0, 8.0]}
  duration_s: 12
  seed: 3
  export: {world: false}
start: {xyz: [20.0, 10.6, 2.0], rpy_deg: [0.0, 0.0, -90.0]}
floor_height_m: -1.5
recorded_points: [{name: A, position_m: [18.0, 10.6, 2.5]}]
mission: {type: goto, point: A}
operator: [{time_s: 11.0, command: abort}]
linger_s: 20.0  # keep flying to the end: the abort comes after the arrival
)";

inline std::filesystem::path temp_dir(const std::string& name) {
    const std::filesystem::path dir =
        std::filesystem::path(::testing::TempDir()) /
        ("scantling_mission_" + name + "_" + std::to_string(::getpid()));
    std::filesystem::remove_all(dir);
    return dir;
}

}  // namespace scantling::mission::test
