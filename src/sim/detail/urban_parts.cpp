#include "urban_parts.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

namespace scantling::sim::detail {
namespace {

const Eigen::Vector3d kUp = Eigen::Vector3d::UnitZ();
// The facade skin reaches this far behind the glazing, so no slit shows at its foot.
constexpr double kEmbed_m = 0.02;
constexpr double kPierWidth_m = 0.5;
// Window opening of a storey: from the sill above its floor to the lintel below the next.
constexpr double kSill_m = 0.9;
constexpr double kLintel_m = 0.4;
constexpr double kBalconyDepth_m = 1.0;
constexpr double kBalconySlab_m = 0.18;
constexpr double kRailingHeight_m = 1.0;
constexpr double kRailingThickness_m = 0.08;
// Street furniture: distances from the kerb onto the sidewalk (or the road, for cars).
constexpr double kPoleFromKerb_m = 0.5;
constexpr double kPoleRadius_m = 0.08;
constexpr double kPoleHeight_m = 7.0;
constexpr int kPoleSegments = 8;
constexpr double kTreeFromKerb_m = 1.5;
constexpr double kTrunkRadius_m = 0.15;
constexpr int kTrunkSegments = 6;
constexpr double kCarFromKerb_m = 0.3;
constexpr double kCarHalfWidth_m = 0.9;

// Quad a-b-c-d wound so that it faces `outward`.
void add_facing(MeshBuilder& builder, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                const Eigen::Vector3d& c, const Eigen::Vector3d& d, const Eigen::Vector3d& outward,
                int tag) {
    if ((c - a).cross(d - b).dot(outward) >= 0.0) {
        builder.add_quad(a, b, c, d, tag);
    } else {
        builder.add_quad(a, d, c, b, tag);
    }
}

// Local frame of a building: u along the street, d from the building line into the block,
// z up from the sidewalk.
struct Frame {
    Eigen::Vector3d origin, u, d;
    Eigen::Vector3d at(double u_m, double d_m, double z_m) const {
        return origin + u_m * u + d_m * d + z_m * kUp;
    }
    void box(MeshBuilder& builder, const Eigen::Vector3d& lo, const Eigen::Vector3d& hi,
             int tag) const {
        builder.add_box(box_between(origin, u, d, kUp, lo, hi), tag);
    }
};

// The glazing sits facade_recess_m behind the building line on the front and on the corner
// sides; plain walls elsewhere.
void add_body(MeshBuilder& builder, const UrbanConfig& config, const UrbanTags& tags,
              const Frame& f, const BuildingSpec& b) {
    const double r = config.facade_recess_m, D = b.depth_m, H = b.height_m;
    const double u0 = b.corner_start ? r : 0.0;
    const double u1 = b.frontage_m - (b.corner_end ? r : 0.0);
    add_facing(builder, f.at(u0, r, 0), f.at(u1, r, 0), f.at(u1, r, H), f.at(u0, r, H), -f.d,
               tags.window);
    add_facing(builder, f.at(u0, D, 0), f.at(u1, D, 0), f.at(u1, D, H), f.at(u0, D, H), f.d,
               tags.building_wall);
    add_facing(builder, f.at(u0, r, 0), f.at(u0, D, 0), f.at(u0, D, H), f.at(u0, r, H), -f.u,
               b.corner_start ? tags.window : tags.building_wall);
    add_facing(builder, f.at(u1, r, 0), f.at(u1, D, 0), f.at(u1, D, H), f.at(u1, r, H), f.u,
               b.corner_end ? tags.window : tags.building_wall);
    add_facing(builder, f.at(u0, r, H), f.at(u1, r, H), f.at(u1, D, H), f.at(u0, D, H), kUp,
               tags.roof);
}

int storey_count(const UrbanConfig& config, double height_m) {
    return std::max(1, static_cast<int>(std::floor(height_m / config.storey_height_m + 1e-9)));
}

// Piers at every bay boundary, bands between the storeys, the attic above the last windows
// and the sill band of the ground floor (except at the door).
void add_facade(MeshBuilder& builder, const UrbanConfig& config, const UrbanTags& tags,
                const Frame& f, const BuildingSpec& b) {
    const double skin = config.facade_recess_m + kEmbed_m, S = config.storey_height_m;
    const double H = b.height_m, W = b.frontage_m;
    const int bays = bay_count(config, W), storeys = storey_count(config, H);
    const double bay = W / bays;
    for (int k = 0; k <= bays; ++k) {
        const double u0 = std::max(0.0, k * bay - 0.5 * kPierWidth_m);
        const double u1 = std::min(W, k * bay + 0.5 * kPierWidth_m);
        f.box(builder, {u0, 0.0, 0.0}, {u1, skin, H}, tags.facade);
    }
    for (int s = 1; s < storeys; ++s) {
        f.box(builder, {0.0, 0.0, s * S - kLintel_m}, {W, skin, s * S + kSill_m}, tags.facade);
    }
    f.box(builder, {0.0, 0.0, storeys * S - kLintel_m}, {W, skin, H}, tags.facade);
    for (int k = 0; k < bays; ++k) {
        if (k == b.door_bay) continue;
        f.box(builder, {k * bay, 0.0, 0.0}, {(k + 1) * bay, skin, kSill_m}, tags.facade);
    }
    if (!b.balconies) return;
    for (int s = 1; s < storeys; ++s) {
        for (int k = 1; k < bays; k += 2) {
            const double u0 = k * bay + 0.5 * kPierWidth_m, u1 = (k + 1) * bay - 0.5 * kPierWidth_m;
            f.box(builder, {u0, -kBalconyDepth_m, s * S - kBalconySlab_m}, {u1, kEmbed_m, s * S},
                  tags.balcony);
            f.box(builder, {u0, -kBalconyDepth_m, s * S},
                  {u1, -kBalconyDepth_m + kRailingThickness_m, s * S + kRailingHeight_m},
                  tags.balcony);
        }
    }
}

// Unit icosphere (one subdivision of the icosahedron): 80 triangles.
std::vector<std::array<Eigen::Vector3d, 3>> unit_icosphere() {
    const double p = (1.0 + std::sqrt(5.0)) / 2.0;
    const std::array<Eigen::Vector3d, 12> v{{{-1, p, 0},
                                             {1, p, 0},
                                             {-1, -p, 0},
                                             {1, -p, 0},
                                             {0, -1, p},
                                             {0, 1, p},
                                             {0, -1, -p},
                                             {0, 1, -p},
                                             {p, 0, -1},
                                             {p, 0, 1},
                                             {-p, 0, -1},
                                             {-p, 0, 1}}};
    constexpr std::array<std::array<int, 3>, 20> kFaces{
        {{0, 11, 5},  {0, 5, 1},  {0, 1, 7},  {0, 7, 10}, {0, 10, 11}, {1, 5, 9}, {5, 11, 4},
         {11, 10, 2}, {10, 7, 6}, {7, 1, 8},  {3, 9, 4},  {3, 4, 2},   {3, 2, 6}, {3, 6, 8},
         {3, 8, 9},   {4, 9, 5},  {2, 4, 11}, {6, 2, 10}, {8, 6, 7},   {9, 8, 1}}};
    std::vector<std::array<Eigen::Vector3d, 3>> out;
    for (const auto& face : kFaces) {
        const Eigen::Vector3d a = v[face[0]].normalized(), b = v[face[1]].normalized(),
                              c = v[face[2]].normalized();
        // (x + y) is symmetric in IEEE arithmetic, so shared edges get identical midpoints.
        const Eigen::Vector3d ab = (a + b).normalized(), bc = (b + c).normalized(),
                              ca = (c + a).normalized();
        out.push_back({a, ab, ca});
        out.push_back({ab, b, bc});
        out.push_back({ca, bc, c});
        out.push_back({ab, bc, ca});
    }
    return out;
}

}  // namespace

UrbanTags add_urban_surfaces(MeshBuilder& builder) {
    UrbanTags t{};
    t.road = builder.surface("road", true, 0.12);
    t.sidewalk = builder.surface("sidewalk", true, 0.3);
    t.kerb = builder.surface("kerb", true, 0.4);
    t.building_wall = builder.surface("building_wall", true, 0.45);
    t.window = builder.surface("window", false, 0.08);
    t.facade = builder.surface("facade", true, 0.55);
    t.roof = builder.surface("roof", true, 0.2);
    t.balcony = builder.surface("balcony", true, 0.5);
    t.pole = builder.surface("pole", false, 0.35);
    t.tree_trunk = builder.surface("tree_trunk", true, 0.2);
    t.tree_crown = builder.surface("tree_crown", true, 0.5);
    t.parked_car = builder.surface("parked_car", false, 0.4);
    return t;
}

int bay_count(const UrbanConfig& config, double frontage_m) {
    return std::max(1, static_cast<int>(std::lround(frontage_m / config.bay_width_m)));
}

void add_building(MeshBuilder& builder, const UrbanConfig& config, const UrbanTags& tags,
                  const StreetSide& side, const BuildingSpec& building) {
    const Eigen::Vector3d origin = side.kerb_start + building.start_m * side.along +
                                   config.sidewalk_width_m * side.inward +
                                   config.kerb_height_m * kUp;
    const Frame front{origin, side.along, side.inward};
    add_body(builder, config, tags, front, building);
    add_facade(builder, config, tags, front, building);
    // A corner side's facade runs from the front building line to the back wall.
    const BuildingSpec corner{
        .frontage_m = building.depth_m, .height_m = building.height_m, .door_bay = -1};
    if (building.corner_start) {
        add_facade(builder, config, tags, Frame{origin, side.inward, side.along}, corner);
    }
    if (building.corner_end) {
        const Eigen::Vector3d end = origin + building.frontage_m * side.along;
        add_facade(builder, config, tags, Frame{end, side.inward, -side.along}, corner);
    }
}

void add_block_platform(MeshBuilder& builder, const UrbanConfig& config, const UrbanTags& tags,
                        const Eigen::Vector2d& min_xy, const Eigen::Vector2d& max_xy) {
    const std::array<Eigen::Vector3d, 4> ground{
        Eigen::Vector3d(min_xy.x(), min_xy.y(), 0.0), Eigen::Vector3d(max_xy.x(), min_xy.y(), 0.0),
        Eigen::Vector3d(max_xy.x(), max_xy.y(), 0.0), Eigen::Vector3d(min_xy.x(), max_xy.y(), 0.0)};
    const Eigen::Vector3d lift = config.kerb_height_m * kUp;
    add_facing(builder, ground[0] + lift, ground[1] + lift, ground[2] + lift, ground[3] + lift, kUp,
               tags.sidewalk);
    for (std::size_t k = 0; k < 4; ++k) {
        const Eigen::Vector3d& a = ground[k];
        const Eigen::Vector3d& b = ground[(k + 1) % 4];
        const Eigen::Vector3d outward = (b - a).cross(kUp);  // the loop is counter-clockwise
        add_facing(builder, a, b, b + lift, a + lift, outward, tags.kerb);
    }
}

void add_lamp_post(MeshBuilder& builder, const UrbanConfig& config, const UrbanTags& tags,
                   const StreetSide& side, double at_m) {
    const Eigen::Vector3d base = side.kerb_start + at_m * side.along +
                                 kPoleFromKerb_m * side.inward + config.kerb_height_m * kUp;
    builder.add_cylinder(base, kUp, side.along, kPoleRadius_m, kPoleHeight_m, kPoleSegments, true,
                         true, tags.pole);
    const Eigen::Vector3d top = base + kPoleHeight_m * kUp;
    const Eigen::Vector3d to_street = -side.inward;
    builder.add_box(
        box_between(top, to_street, side.along, kUp, {0.0, -0.05, -0.15}, {1.6, 0.05, -0.05}),
        tags.pole);
    builder.add_box(
        box_between(top, to_street, side.along, kUp, {1.2, -0.2, -0.32}, {1.8, 0.2, -0.15}),
        tags.pole);
}

void add_tree(MeshBuilder& builder, const UrbanConfig& config, const UrbanTags& tags,
              const StreetSide& side, double at_m, double trunk_height_m, double crown_radius_m) {
    const Eigen::Vector3d base = side.kerb_start + at_m * side.along +
                                 kTreeFromKerb_m * side.inward + config.kerb_height_m * kUp;
    // The trunk reaches into the crown, so no gap shows between them.
    builder.add_cylinder(base, kUp, side.along, kTrunkRadius_m,
                         trunk_height_m + 0.5 * crown_radius_m, kTrunkSegments, true, false,
                         tags.tree_trunk);
    const Eigen::Vector3d centre = base + (trunk_height_m + 0.6 * crown_radius_m) * kUp;
    for (const auto& t : unit_icosphere()) {
        const Eigen::Vector3d a = centre + crown_radius_m * t[0];
        const Eigen::Vector3d b = centre + crown_radius_m * t[1];
        const Eigen::Vector3d c = centre + crown_radius_m * t[2];
        if ((b - a).cross(c - a).dot(a + b + c - 3.0 * centre) >= 0.0) {
            builder.add_triangle(a, b, c, tags.tree_crown);
        } else {
            builder.add_triangle(a, c, b, tags.tree_crown);
        }
    }
}

void add_parked_car(MeshBuilder& builder, const UrbanTags& tags, const StreetSide& side,
                    double at_m, double cabin_shift_m) {
    const Eigen::Vector3d centre =
        side.kerb_start + at_m * side.along - (kCarFromKerb_m + kCarHalfWidth_m) * side.inward;
    const auto box = [&](const Eigen::Vector3d& lo, const Eigen::Vector3d& hi) {
        builder.add_box(box_between(centre, side.along, side.inward, kUp, lo, hi), tags.parked_car);
    };
    box({-2.2, -kCarHalfWidth_m, 0.3}, {2.2, kCarHalfWidth_m, 1.0});
    box({-1.2 + cabin_shift_m, -0.8, 1.0}, {1.2 + cabin_shift_m, 0.8, 1.45});
    for (const double u : {-1.4, 1.4}) {
        for (const double v : {-0.72, 0.72})
            box({u - 0.32, v - 0.12, 0.0}, {u + 0.32, v + 0.12, 0.64});
    }
}

}  // namespace scantling::sim::detail
