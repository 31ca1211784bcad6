#pragma once
/// @file Pieces shared by the simulator benchmark's files (bench/sim_bench*.cpp).

#include <string_view>

#include <scantling/core/bounds.hpp>
#include <scantling/sim/ray_caster.hpp>
#include <scantling/sim/world.hpp>

namespace scantling::bench {

/// Bounds of the triangles of `world` tagged with surface `surface` (empty box when none).
Aabb surface_bounds(const sim::World& world, std::string_view surface);

/// Registers the simulated-flight benchmarks "hull_flight_60s/ours/<n>thr" (a 60 s OS1-64 +
/// IMU flight along the parametric ship hull in its dry dock, timed as a multiple of real time)
/// and, when `dtc_world` and `dtc_caster` are given (both outliving the run), the same flight
/// along the DTC hull as "dtc_hull_flight_60s/ours/<n>thr".
void register_flight_benchmarks(const sim::World* dtc_world, const sim::RayCaster* dtc_caster);

}  // namespace scantling::bench
