#include <fmt/format.h>
#include <algorithm>
#include <scantling/core/error.hpp>
#include <scantling/io/config_node.hpp>
#include <scantling/io/config_schema.hpp>
#include <scantling/odometry/liodom.hpp>
#include <string>

namespace scantling::odometry {
namespace detail {
std::string_view preset_yaml(std::string_view name);  // liodom_presets.cpp (generated)
}  // namespace detail

namespace {

using io::ConfigSchema;
using io::kNonNegative;
using io::kPositive;
using io::kUnitInterval;

ConfigSchema<ParallelConfig> parallel_schema() {
    ConfigSchema<ParallelConfig> s;
    s.field("num_threads", &ParallelConfig::num_threads, "0 = all hardware threads", kNonNegative);
    return s;
}

ConfigSchema<RingOrganizerConfig> rings_schema() {
    ConfigSchema<RingOrganizerConfig> s;
    s.field("num_rings", &RingOrganizerConfig::num_rings,
            "0 = the ring field when present, else detected", kNonNegative)
        .enum_field("source", &RingOrganizerConfig::source,
                    {{"auto", RingSource::kAuto},
                     {"ring_field", RingSource::kRingField},
                     {"scan_order", RingSource::kScanOrder},
                     {"elevation", RingSource::kElevation}},
                    "where the ring of a point comes from")
        .field("min_ring_gap_rad", &RingOrganizerConfig::min_ring_gap_rad,
               "empty elevation band separating two rings, rad", kPositive)
        .field("min_ring_points", &RingOrganizerConfig::min_ring_points,
               "smaller rings are dropped", kPositive)
        .field("scan_start_azimuth_rad", &RingOrganizerConfig::scan_start_azimuth_rad,
               "azimuth where each ring of a scan-ordered sweep starts (nan = the first "
               "return's; KITTI: 0)");
    return s;
}

ConfigSchema<EdgeExtractionConfig> features_schema() {
    using C = EdgeExtractionConfig;
    ConfigSchema<C> s;
    s.field("min_range_m", &C::min_range_m, "r_min: closer points are dropped, m", kNonNegative)
        .field("max_range_m", &C::max_range_m, "r_max: farther points are dropped, m", kPositive)
        .field("curvature_half_window", &C::curvature_half_window,
               "neighbours each side in the LOAM curvature", kPositive)
        .field("num_sectors", &C::num_sectors, "sectors per ring", kPositive)
        .field("max_edges_per_sector", &C::max_edges_per_sector, "N: edges kept per sector",
               kPositive)
        .field("min_edge_curvature", &C::min_edge_curvature, "LOAM curvature threshold",
               kNonNegative)
        .field("max_azimuth_gap_factor", &C::max_azimuth_gap_factor,
               "azimuth gap (x median step) that breaks a ring's neighbourhood", kPositive)
        .field("range_jump_ratio", &C::range_jump_ratio,
               "relative range jump that marks an occlusion boundary", kPositive)
        .field("reject_unreliable", &C::reject_unreliable,
               "drop occluded and beam-parallel points (LOAM)")
        .field("max_incidence_rad", &C::max_incidence_rad,
               "beam-to-normal angle above which a point is beam-parallel, rad", kPositive)
        .field("max_planes_per_sector", &C::max_planes_per_sector,
               "planar points kept per sector beside the edges (0 = edges only)", kNonNegative)
        .field("max_plane_curvature", &C::max_plane_curvature,
               "largest LOAM curvature of a planar point", kNonNegative)
        .section("rings", &C::rings, rings_schema(), "ring organisation")
        .section("parallel", &C::parallel, parallel_schema(), "threads over rings");
    return s;
}

ConfigSchema<EdgeRegistrationConfig> registration_schema() {
    using C = EdgeRegistrationConfig;
    ConfigSchema<C> s;
    s.field("num_neighbors", &C::num_neighbors, "k of the line fit", kPositive)
        .field("max_neighbor_distance_m", &C::max_neighbor_distance_m,
               "farthest accepted neighbour, m", kPositive)
        .field("line_eigen_ratio", &C::line_eigen_ratio, "lambda1 >= ratio * lambda2 is a line",
               kPositive)
        .field("plane_eigen_ratio", &C::plane_eigen_ratio,
               "planar points: lambda2 >= ratio * lambda3 is a plane", kPositive)
        .field("huber_delta_m", &C::huber_delta_m, "Huber threshold on the weighted distance, m",
               kPositive)
        .field("max_iterations", &C::max_iterations, "outer iterations", kPositive)
        .field("inner_iterations", &C::inner_iterations, "Gauss-Newton steps per outer iteration",
               kPositive)
        .field("refit_distance_m", &C::refit_distance_m,
               "refit a point's line or plane once it moved this far since its fit (0 = always), m",
               kNonNegative)
        .field("min_correspondences", &C::min_correspondences,
               "fewer: the sweep is carried by the motion model", kPositive)
        .field("convergence_translation_m", &C::convergence_translation_m,
               "update below which it has converged, m", kNonNegative)
        .field("convergence_rotation_rad", &C::convergence_rotation_rad,
               "update below which it has converged, rad", kNonNegative)
        .field("degeneracy_ratio", &C::degeneracy_ratio,
               "eigenvalue ratio below which a direction is degenerate (0 = never)", kUnitInterval)
        .field("converge_on_observed", &C::converge_on_observed,
               "converged when the update along the non-degenerate directions is small")
        .field("range_weighting", &C::range_weighting, "weight 1 - (r - r_min)/(r_max - r_min)")
        .section("parallel", &C::parallel, parallel_schema(),
                 "threads of the correspondence search");
    return s;
}

ConfigSchema<mapping::CellMapConfig> map_schema() {
    using C = mapping::CellMapConfig;
    ConfigSchema<C> s;
    s.field("cell_size_xy_m", &C::cell_size_xy_m, "s_xy, m", kPositive)
        .field("cell_size_z_m", &C::cell_size_z_m, "s_z, m", kPositive)
        .field("max_points_per_cell", &C::max_points_per_cell,
               "budget; modified cells above it are voxel-thinned", kPositive)
        .field("thinning_voxel_m", &C::thinning_voxel_m, "voxel edge of the thinning, m", kPositive)
        .enum_field("hash", &C::hash,
                    {{"mixed", mapping::CellHashKind::kMixed},
                     {"source_xor", mapping::CellHashKind::kSourceXor}},
                    "hash of the cell table");
    return s;
}

ConfigSchema<LocalMapConfig> local_map_schema() {
    using C = LocalMapConfig;
    ConfigSchema<C> s;
    s.field("radius_m", &C::radius_m, "cells within this distance of the sensor, m", kPositive)
        .field("num_recent_sweeps", &C::num_recent_sweeps, "latest sweeps added", kNonNegative)
        .field("rebuild_distance_m", &C::rebuild_distance_m,
               "re-gather the cells after moving this far, m", kNonNegative);
    return s;
}

ConfigSchema<LiodomConfig> liodom_schema() {
    using C = LiodomConfig;
    ConfigSchema<C> s;
    s.section("features", &C::features, features_schema(), "edge extraction")
        .section("registration", &C::registration, registration_schema(), "pose estimation")
        .section("map", &C::map, map_schema(), "hashed cell map")
        .section("local_map", &C::local_map, local_map_schema(), "adaptive local map")
        .field("max_time_gap_s", &C::max_time_gap_s, "larger gaps between sweeps are reported, s",
               kPositive)
        .field("max_speed_mps", &C::max_speed_mps, "faster predictions reset the velocity, m/s",
               kPositive)
        .field("bootstrap_voxel_m", &C::bootstrap_voxel_m,
               "voxel of the dense GICP that starts the second sweep, m (0 = off)", kNonNegative)
        .field("plane_recent_sweeps", &C::plane_recent_sweeps,
               "latest sweeps whose planar points join the planes' local map", kNonNegative)
        .section("parallel", &C::parallel, parallel_schema(), "threads of the pipeline");
    return s;
}

FileLocation line_of(const io::ConfigNode& node) {
    FileLocation location;
    location.line = node.line;
    return location;
}

/// Applies `node` over `base`, or over the preset it names (`preset: NAME`).
LiodomConfig config_from(const io::ConfigNode& node, LiodomConfig base) {
    io::ConfigNode body = node;
    if (body.is_map()) {
        const auto it = std::find_if(body.map.begin(), body.map.end(),
                                     [](const auto& e) { return e.first == "preset"; });
        if (it != body.map.end()) {
            if (!it->second.is_scalar()) {
                throw ParseError(node.file, line_of(it->second),
                                 "key 'preset': expected a name (" +
                                     fmt::format("{}", fmt::join(liodom_preset_names(), ", ")) +
                                     ")");
            }
            const std::string preset = it->second.scalar;
            if (detail::preset_yaml(preset).empty()) {
                throw ParseError(node.file, line_of(it->second),
                                 fmt::format("key 'preset': '{}' is not a preset (expected one "
                                             "of: {})",
                                             preset, fmt::join(liodom_preset_names(), ", ")));
            }
            base = liodom_preset(preset);
            body.map.erase(it);
        }
    }
    liodom_schema().apply(body, base);
    return base;
}

}  // namespace

std::vector<std::string> liodom_preset_names() { return {"kitti", "os1_drone", "confined"}; }

LiodomConfig liodom_preset(std::string_view name) {
    const std::string_view yaml = detail::preset_yaml(name);
    if (yaml.empty()) {
        throw ConfigError(fmt::format("preset = '{}', expected one of: {}", name,
                                      fmt::join(liodom_preset_names(), ", ")));
    }
    LiodomConfig config;
    liodom_schema().apply(
        io::parse_yaml_string(std::string(yaml), "config/odometry/" + std::string(name) + ".yaml"),
        config);
    return config;
}

LiodomConfig load_liodom_config(const std::string& path) {
    return config_from(io::parse_yaml_file(path), liodom_preset("kitti"));
}

LiodomConfig liodom_config_from_node(const io::ConfigNode& node, const LiodomConfig& base) {
    return config_from(node, base);
}

std::string describe_liodom_config(const LiodomConfig& config) {
    return liodom_schema().describe(config);
}

}  // namespace scantling::odometry
