// YAML binding of the next-best-view planner's config (a mission's `stack.nbv:`): every key
// once, defaults from NbvPlannerConfig's initialisers, unknown keys rejected by the schema.
#include <scantling/planning/config_yaml.hpp>

#include <string>
#include <utility>
#include <vector>

namespace scantling::planning {
namespace {

using io::ConfigSchema;
using io::kNonNegative;
using io::kPositive;

ConfigSchema<mapping::ViewFrustum> view_frustum_schema() {
    using V = mapping::ViewFrustum;
    ConfigSchema<V> s;
    s.field("horizontal_fov_rad", &V::horizontal_fov_rad, "full horizontal FOV, rad", kPositive)
        .field("vertical_fov_rad", &V::vertical_fov_rad, "full vertical FOV, rad", kPositive)
        .field("max_depth_m", &V::max_depth_m, "reach of the gain's rays, m", kPositive)
        .field("rays_horizontal", &V::rays_horizontal, "gain rays per row, >= 2")
        .field("rays_vertical", &V::rays_vertical, "gain rays per column, >= 2");
    return s;
}

ConfigSchema<ParallelConfig> parallel_schema() {
    ConfigSchema<ParallelConfig> s;
    s.field("num_threads", &ParallelConfig::num_threads, "0 = all hardware threads", kNonNegative);
    return s;
}

const std::vector<std::pair<std::string, NbvSampling>> kSamplings = {
    {"uniform", NbvSampling::kUniform}, {"frontier", NbvSampling::kFrontier}};

void add_tree_fields(ConfigSchema<NbvPlannerConfig>& s) {
    using C = NbvPlannerConfig;
    s.field("bounds_min_world_m", &C::bounds_min_world_m, "exploration volume's low corner, m")
        .field("bounds_max_world_m", &C::bounds_max_world_m, "exploration volume's high corner, m")
        .field("max_nodes", &C::max_nodes, "N_T: tree nodes, root included")
        .field("samples_per_node", &C::samples_per_node, "sample budget per tree node")
        .field("max_edge_m", &C::max_edge_m, "longest edge, m", kPositive)
        .field("lambda_per_m", &C::lambda_per_m, "gain discount per metre of edge", kNonNegative)
        .field("vehicle_box_m", &C::vehicle_box_m, "vehicle collision box, m", kPositive)
        .field("clearance_m", &C::clearance_m, "margin around the box on edges, m", kNonNegative);
}

void add_gain_fields(ConfigSchema<NbvPlannerConfig>& s) {
    using C = NbvPlannerConfig;
    s.section("camera", &C::camera, view_frustum_schema(), "the gain's camera frustum")
        .field("p_body_camera_m", &C::p_body_camera_m, "camera position in the body, m")
        .field("camera_pitch_rad", &C::camera_pitch_rad, "camera pitch, > 0 looks down, rad")
        .field("min_gain_m3", &C::min_gain_m3, "exhausted below this best gain, m³", kNonNegative)
        .field("defect_aware", &C::defect_aware, "weight views of defects (μ = 1 + Σ 1/d)")
        .enum_field("sampling", &C::sampling, kSamplings, "where samples come from")
        .field("frontier_sample_fraction", &C::frontier_sample_fraction,
               "share of frontier samples", kNonNegative)
        .field("frontier_standoff_m", &C::frontier_standoff_m,
               "steer stops this short of a frontier, m", kNonNegative)
        .field("frontier_cell_m", &C::frontier_cell_m, "frontier cell edge, m", kPositive)
        .field("seed", &C::seed, "random seed")
        .section("parallel", &C::parallel, parallel_schema(), "gain evaluation threads");
}

}  // namespace

const ConfigSchema<NbvPlannerConfig>& nbv_planner_config_schema() {
    static const ConfigSchema<NbvPlannerConfig> schema = [] {
        ConfigSchema<NbvPlannerConfig> s;
        add_tree_fields(s);
        add_gain_fields(s);
        return s;
    }();
    return schema;
}

}  // namespace scantling::planning
