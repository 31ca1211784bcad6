#pragma once
/// @file
/// Upper bounds of the scenario keys that size a run (issue 10): a scenario is hostile input,
/// and one absurd number (`duration_s: 1e12`, `width: 100000000`, a 1e9 m tank) must be
/// refused by validation naming the key, not discovered as `std::bad_alloc` or a full disk.
/// Each bound sits far above any real sensor, vehicle or structure and low enough that no
/// single accepted value exhausts memory; the recording's total size is bounded separately
/// (scenario_estimate.hpp). The schema (scenario_schema.hpp) applies these as key ranges, so
/// `scenario_schema().describe()` prints them.

#include <cstddef>
#include <cstdint>

namespace scantling::sim::limits {

// Clock and duration.
inline constexpr double kMaxDuration_s = 86'400.0;  ///< one day of simulated time
inline constexpr double kMinDt_s = 1e-5;            ///< a 100 kHz clock
inline constexpr double kMaxDt_s = 1.0;
/// Clock ticks of a run (duration / dt + 1), e.g. 2.7 h at dt_s 0.005: the vehicle state
/// (~0.2 kB) and ground-truth pose (~0.15 kB) of every tick, and the text rows of the sensors
/// sampled at most once per tick (~0.15 kB each), are held in memory until the run ends:
/// below 3 GB at this bound even with every row sensor at the clock rate.
inline constexpr std::int64_t kMaxTicks = 2'000'000;

/// parallel.num_threads (0 = all hardware threads).
inline constexpr int kMaxThreads = 1'024;

// Sensors.
inline constexpr double kMaxRate_hz = 1.0 / kMinDt_s;  ///< and at most 1 / dt_s (one per tick)
inline constexpr double kMinRate_hz = 1e-3;            ///< when set (0 = the preset's rate)
inline constexpr int kMaxLidarColumns = 16'384;        ///< Ouster and Velodyne: <= 2'083
inline constexpr int kMaxImageSide_px = 8'192;         ///< camera, depth and stereo width/height
/// Pixels of one image (width x height, the height from the preset's aspect when unset): a
/// camera holds a ray (24 bytes) and a colour per pixel, ~0.5 GB at this bound.
inline constexpr std::int64_t kMaxImagePixels = 16'777'216;
/// Points of one frame (LiDAR rings x columns, rosette point_rate / rate_hz, depth pixels):
/// a frame in memory takes ~40 bytes per point, ~170 MB at this bound.
inline constexpr std::int64_t kMaxPointsPerFrame = 4'194'304;
inline constexpr int kMaxSonarBeams = 4'096;  ///< MultibeamSonarConfig's own bound
inline constexpr int kMaxSonarBins = 8'192;   ///< MultibeamSonarConfig's own bound
inline constexpr double kMaxSensorRange_m = 10'000.0;
inline constexpr std::size_t kMaxUwbAnchors = 1'024;

// Worlds and trajectories.
/// Any world length, width, height, diameter or radius: the largest ships are ~400 m long
/// (an urban world is sized by its number of blocks).
inline constexpr double kMaxWorldExtent_m = 500.0;
/// Any coordinate (waypoints, trajectory centres, poses): 100 km from the world origin.
inline constexpr double kMaxCoordinate_m = 100'000.0;
/// Smallest spacing of repeated structure (stiffeners, longitudinals, frames, courses): with
/// kMaxWorldExtent_m it bounds their count per run of structure to 5000.
inline constexpr double kMinStructureSpacing_m = 0.1;
inline constexpr int kMaxSegments = 1'024;      ///< facets around a cylinder, tank, column or strip
inline constexpr int kMaxStructureCount = 128;  ///< trays, nozzles, compartments, seams, beams
/// Products of repeated structure (courses x segments, windows of all facades, ...): see
/// detail/scenario_checks.hpp. Worlds at this bound take < 0.5 GB (the slowest, a storage
/// tank, about a minute to build).
inline constexpr std::int64_t kMaxWorldElements = 100'000;
inline constexpr int kMaxUrbanBlocks = 32;  ///< urban blocks_x and blocks_y
inline constexpr int kMaxDefects = 10'000;  ///< defects.count
inline constexpr std::size_t kMaxWaypoints = 10'000;
/// Moving obstacles: each is tested against every ray of every sensor (no acceleration structure).
inline constexpr std::size_t kMaxMovingObstacles = 256;
/// Surface obstacles of a world (`world.obstacles` plus `world.plate.holes`): each is a few
/// dozen to a few hundred triangles, and plate holes are checked pairwise for overlap.
inline constexpr std::size_t kMaxSurfaceObstacles = 1'024;
/// Any size of a surface obstacle (bolt diameter, bracket side, bead width and height): a
/// larger one is structure, not an obstacle on it.
inline constexpr double kMaxSurfaceObstacleSize_m = 10.0;
inline constexpr double kMaxTurns = 10'000.0;      ///< helix rotations, orbit turns
inline constexpr double kMaxMeshScale = 10'000.0;  ///< mesh file units to metres
/// CAD-map spacing: the map has area / spacing² points (core caps it at 1e9 points).
inline constexpr double kMinMapSpacing_m = 0.005;

}  // namespace scantling::sim::limits
