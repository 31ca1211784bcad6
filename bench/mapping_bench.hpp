#pragma once
/// @file Inputs of the hashed-cell-map benchmark (bench/mapping_bench*.cpp): maps built from
/// real sweeps and from simulated worlds, each inserted batch by batch as the odometry would
/// insert one sweep's edges at a time.

#include <Eigen/Core>
#include <cstdint>
#include <string>
#include <vector>

#include <scantling/mapping/cell_map.hpp>

namespace scantling::bench {

using Batches = std::vector<std::vector<Eigen::Vector3d>>;

struct MapInput {
    std::string name;
    mapping::CellMapConfig config;  ///< the hash kind is set per run
    Batches batches;                ///< one insert call each
    double gather_radius_m = 50.0;  ///< local-map radius used for gather_near
    bool timed = true;              ///< false: hash statistics only, no timed benchmarks
};

/// Streets of a 1 km x 1 km town centred on the origin: roads every 100 m in x and y, building
/// facades of random height (5-30 m) 12 m either side of each road, the road surface and poles.
/// One batch per 100 m road segment (~10k points, ~2.3M in all).
Batches road_network_map(std::uint64_t seed);

/// A 12 m x 8 m x 4 m ballast-tank bay centred on the origin: shell plates, transverse web
/// frames every 0.8 m with a manhole each, longitudinal stiffeners. Batches of 20k points.
Batches ballast_tank_map(std::uint64_t seed);

}  // namespace scantling::bench
