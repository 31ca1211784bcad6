#include <gtest/gtest.h>

#include <unistd.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iterator>
#include <limits>
#include <numbers>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include <scantling/core/error.hpp>
#include <scantling/io/png.hpp>
#include <scantling/perception/texture_map.hpp>

namespace scantling::perception {
namespace {

namespace fs = std::filesystem;

constexpr double kCellM = 0.005;
// Checkerboard square edge: not a multiple of the cell, so the squares' edges pass at every
// distance from the cell centres and the cells next to them are really tested.
constexpr double kSquareM = 0.037;
constexpr double kHeightM = 0.3;  // the camera's height above the ground
// The nearest pixel's ray meets the ground within half a pixel diagonal of the cell centre:
// 0.7 mm looking down from 0.3 m at 1 mm/px, < 2 mm at the far edge of the 30° view (2.6 mm/px).
// Cells farther than this from a square's edge must therefore have the square's colour.
constexpr double kEdgeMarginM = 0.003;
constexpr double kMinColourShare = 0.99;  // of the cells away from edges; measured 1.0 (all
                                          // cells, edges too: 1.0 down, 0.995 tilted)
// Counting cell centres inside the footprint: the error is a fraction of the border cells'
// area (~7 % of the footprint at 5 mm cells), far less in practice; measured 0.0 % straight
// down and −0.8 % tilted (where a footprint edge lies 1.25 mm short of a row of cell centres).
constexpr double kAreaTolerance = 0.02;

const Rgb8 kLight(230, 200, 40);
const Rgb8 kDark(20, 70, 160);
const Rgb8 kSky(120, 180, 255);
const Rgb8 kBlack(0, 0, 0);
const Rgb8 kRed(255, 0, 0);

Rgb8 checker_color(double x_m, double y_m) {
    const auto sum = static_cast<long>(std::floor(x_m / kSquareM) + std::floor(y_m / kSquareM));
    return sum % 2 == 0 ? kLight : kDark;
}

double distance_to_edge_m(double x_m, double y_m) {
    const auto to_line = [](double s) { return std::abs(s - kSquareM * std::round(s / kSquareM)); };
    return std::min(to_line(x_m), to_line(y_m));
}

/// 320 × 240 px, f = 300 px: looking down from 0.3 m it sees 0.32 m × 0.24 m at 1 mm/px.
PinholeIntrinsics test_camera() { return {320, 240, 300.0, 300.0, 159.5, 119.5}; }

/// Camera at `p_map` looking along `forward_map` with its x axis along `right_map`.
Eigen::Isometry3d camera_pose(const Eigen::Vector3d& p_map, const Eigen::Vector3d& forward_map,
                              const Eigen::Vector3d& right_map) {
    Eigen::Isometry3d T_map_camera = Eigen::Isometry3d::Identity();
    const Eigen::Vector3d z = forward_map.normalized();
    const Eigen::Vector3d x = right_map.normalized();
    T_map_camera.linear() << x, z.cross(x), z;
    T_map_camera.translation() = p_map;
    return T_map_camera;
}

Eigen::Isometry3d looking_down(double x_m, double y_m, double height_m) {
    return camera_pose({x_m, y_m, height_m}, -Eigen::Vector3d::UnitZ(), Eigen::Vector3d::UnitX());
}

/// Camera at height kHeightM pitched `tilt_deg` from straight down towards +y.
Eigen::Isometry3d tilted(double x_m, double y_m, double tilt_deg) {
    const double t = tilt_deg * std::numbers::pi / 180.0;
    return camera_pose({x_m, y_m, kHeightM}, {0.0, std::sin(t), -std::cos(t)},
                       Eigen::Vector3d::UnitX());
}

/// Where the ray through `pixel` meets the ground z = 0, or nullopt (it points up).
std::optional<Eigen::Vector3d> ground_hit(const PinholeIntrinsics& intrinsics,
                                          const Eigen::Isometry3d& T_map_camera,
                                          const Eigen::Vector2d& pixel) {
    const Eigen::Vector3d d = T_map_camera.linear() * intrinsics.ray_direction(pixel);
    const Eigen::Vector3d c = T_map_camera.translation();
    if (!(d.z() < 0.0)) return std::nullopt;
    return c + d * (-c.z() / d.z());
}

/// Ray-casts every pixel centre onto the ground, coloured by `ground_color` (sky above).
io::RgbImage render(const PinholeIntrinsics& intrinsics, const Eigen::Isometry3d& T_map_camera,
                    const std::function<Rgb8(double, double)>& ground_color = checker_color) {
    io::RgbImage image{intrinsics.width, intrinsics.height, {}};
    for (int v = 0; v < intrinsics.height; ++v) {
        for (int u = 0; u < intrinsics.width; ++u) {
            const auto hit = ground_hit(intrinsics, T_map_camera, Eigen::Vector2d(u, v));
            image.pixels.push_back(hit ? ground_color(hit->x(), hit->y()) : kSky);
        }
    }
    return image;
}

io::RgbImage uniform(const PinholeIntrinsics& intrinsics, const Rgb8& color) {
    return {
        intrinsics.width, intrinsics.height,
        std::vector<Rgb8>(static_cast<std::size_t>(intrinsics.width * intrinsics.height), color)};
}

/// Area of the image's footprint on the ground: the quadrilateral of its corner rays' hits.
double footprint_area_m2(const PinholeIntrinsics& intrinsics, const Eigen::Isometry3d& T) {
    const double w = intrinsics.width - 0.5;
    const double h = intrinsics.height - 0.5;
    const std::array<Eigen::Vector2d, 4> corners{
        Eigen::Vector2d(-0.5, -0.5), {w, -0.5}, {w, h}, {-0.5, h}};
    double twice_area = 0.0;
    for (std::size_t i = 0; i < 4; ++i) {
        const Eigen::Vector3d a = *ground_hit(intrinsics, T, corners[i]);
        const Eigen::Vector3d b = *ground_hit(intrinsics, T, corners[(i + 1) % 4]);
        twice_area += a.x() * b.y() - b.x() * a.y();
    }
    return 0.5 * std::abs(twice_area);
}

TextureMapConfig small_map() {
    TextureMapConfig config;
    config.cell_size_m = kCellM;
    config.min_x_m = config.min_y_m = -0.5;
    config.max_x_m = config.max_y_m = 0.5;
    return config;
}

struct ProjectionFigures {
    std::size_t observed = 0;
    std::size_t away_from_edges = 0;
    std::size_t right_colour_away = 0;
    std::size_t right_colour_all = 0;
    std::size_t unobserved_not_black = 0;
    double area_m2 = 0.0;
};

ProjectionFigures measure_live(const TextureMap& map) {
    ProjectionFigures f;
    for (std::size_t iy = 0; iy < map.rows(); ++iy) {
        for (std::size_t ix = 0; ix < map.columns(); ++ix) {
            const Eigen::Vector3d p = map.cell_centre_map(ix, iy);
            const Rgb8 color = map.live_color(ix, iy);
            if (!map.live_observed(ix, iy)) {
                f.unobserved_not_black += color != kBlack ? 1 : 0;
                continue;
            }
            ++f.observed;
            const bool right = color == checker_color(p.x(), p.y());
            f.right_colour_all += right ? 1 : 0;
            if (distance_to_edge_m(p.x(), p.y()) > kEdgeMarginM) {
                ++f.away_from_edges;
                f.right_colour_away += right ? 1 : 0;
            }
        }
    }
    f.area_m2 = static_cast<double>(f.observed) * kCellM * kCellM;
    return f;
}

void expect_projection(const ProjectionFigures& f, double expected_area_m2) {
    ASSERT_GT(f.away_from_edges, 1000u);
    const double share =
        static_cast<double>(f.right_colour_away) / static_cast<double>(f.away_from_edges);
    EXPECT_GE(share, kMinColourShare);
    EXPECT_EQ(f.unobserved_not_black, 0u);
    EXPECT_NEAR(f.area_m2 / expected_area_m2, 1.0, kAreaTolerance);
    ::testing::Test::RecordProperty("colour_share_away_from_edges", std::to_string(share));
    ::testing::Test::RecordProperty(
        "colour_share_all", std::to_string(static_cast<double>(f.right_colour_all) / f.observed));
    ::testing::Test::RecordProperty("area_ratio", std::to_string(f.area_m2 / expected_area_m2));
}

TEST(TextureMap, ProjectsACheckerboardSeenFromAboveBackOntoItsColours) {
    TextureMap map(small_map());
    const PinholeIntrinsics camera = test_camera();
    const Eigen::Isometry3d T = looking_down(0.013, -0.021, kHeightM);
    const std::size_t painted = map.add_image(render(camera, T), camera, T);
    const ProjectionFigures f = measure_live(map);
    EXPECT_EQ(painted, f.observed);
    EXPECT_EQ(map.live_stats().observed_cells, f.observed);
    // Straight down: the footprint is (width · h / fx) × (height · h / fy) = 0.32 m × 0.24 m.
    expect_projection(f, (320 * kHeightM / 300.0) * (240 * kHeightM / 300.0));
    EXPECT_EQ(map.clean_stats().observed_cells, 0u);  // only stops paint the clean layer
}

TEST(TextureMap, ProjectsACheckerboardSeenByACameraTiltedThirtyDegrees) {
    TextureMap map(small_map());
    const PinholeIntrinsics camera = test_camera();
    const Eigen::Isometry3d T = tilted(0.007, -0.2, 30.0);
    map.add_image(render(camera, T), camera, T);
    expect_projection(measure_live(map), footprint_area_m2(camera, T));
}

TEST(TextureMap, LeavesGroundBeyondMaxRangeUnobserved) {
    TextureMapConfig config = small_map();
    config.max_range_m = 0.5;
    TextureMap limited(config);
    TextureMap unlimited(small_map());
    const PinholeIntrinsics camera = test_camera();
    const Eigen::Isometry3d T = tilted(0.0, -0.4, 55.0);  // the far edge is ~1.2 m away
    const io::RgbImage image = render(camera, T);
    const std::size_t near = limited.add_image(image, camera, T);
    const std::size_t all = unlimited.add_image(image, camera, T);
    EXPECT_GT(near, 1000u);
    EXPECT_LT(near, all);
    for (std::size_t iy = 0; iy < limited.rows(); ++iy) {
        for (std::size_t ix = 0; ix < limited.columns(); ++ix) {
            const double range_m = (limited.cell_centre_map(ix, iy) - T.translation()).norm();
            if (limited.live_observed(ix, iy)) {
                EXPECT_LE(range_m, config.max_range_m);
            }
            if (unlimited.live_observed(ix, iy) && range_m < config.max_range_m) {
                EXPECT_TRUE(limited.live_observed(ix, iy));
            }
        }
    }
}

TEST(TextureMap, SeesNothingFromBelowTheGroundOrLookingUp) {
    TextureMap map(small_map());
    const PinholeIntrinsics camera = test_camera();
    const io::RgbImage image = uniform(camera, kLight);
    EXPECT_EQ(map.add_image(image, camera, looking_down(0.0, 0.0, -0.3)), 0u);
    const Eigen::Isometry3d up =
        camera_pose({0.0, 0.0, kHeightM}, Eigen::Vector3d::UnitZ(), Eigen::Vector3d::UnitX());
    EXPECT_EQ(map.add_image(image, camera, up), 0u);
    EXPECT_EQ(map.live_stats().observed_cells, 0u);
    EXPECT_EQ(map.num_images(), 2u);
}

/// A 10 × 10 grid of 2 cm cells centred on the body, all free but the listed ones.
SurfaceGrid obstacle_grid() {
    SurfaceGrid grid;
    grid.cell_size_m = 0.02;
    grid.cells_per_side = 10;
    grid.origin_xy_m = Eigen::Vector2d(-0.1, -0.1);
    grid.cells.assign(100, SurfaceLabel::kFree);
    grid.cells[5 * 10 + 7] = SurfaceLabel::kPositive;
    grid.cells[2 * 10 + 2] = SurfaceLabel::kNegative;
    grid.cells[8 * 10 + 4] = SurfaceLabel::kUncertain;
    return grid;
}

Eigen::Isometry3d stop_pose() {
    Eigen::Isometry3d T_map_body = Eigen::Isometry3d::Identity();
    T_map_body.linear() =
        Eigen::AngleAxisd(std::numbers::pi / 2, Eigen::Vector3d::UnitZ()).matrix();
    T_map_body.translation() = Eigen::Vector3d(0.011, 0.023, 0.0);
    return T_map_body;
}

/// Runs one stop with a checkerboard image from above (x_m, y_m) and `grid` at `T_map_body`.
std::size_t stop(TextureMap& map, double x_m, double y_m, const SurfaceGrid& grid,
                 const Eigen::Isometry3d& T_map_body) {
    const PinholeIntrinsics camera = test_camera();
    const Eigen::Isometry3d T = looking_down(x_m, y_m, kHeightM);
    map.begin_stop();
    const std::size_t seen = map.add_stop_image(render(camera, T), camera, T);
    map.end_stop(grid, T_map_body);
    return seen;
}

TEST(TextureMap, PaintsObstacleCellsRedOnTheCleanLayerAtTheStopPose) {
    for (const bool uncertain_is_obstacle : {false, true}) {
        TextureMapConfig config = small_map();
        config.uncertain_is_obstacle = uncertain_is_obstacle;
        TextureMap map(config);
        const SurfaceGrid grid = obstacle_grid();
        const Eigen::Isometry3d T_body_map = stop_pose().inverse();
        stop(map, 0.0, 0.0, grid, stop_pose());
        std::size_t expected_obstacles = 0;
        for (std::size_t iy = 0; iy < map.rows(); ++iy) {
            for (std::size_t ix = 0; ix < map.columns(); ++ix) {
                const Eigen::Vector3d p = map.cell_centre_map(ix, iy);
                const SurfaceLabel label = grid.label_at((T_body_map * p).head<2>());
                const bool obstacle = label == SurfaceLabel::kPositive ||
                                      label == SurfaceLabel::kNegative ||
                                      (uncertain_is_obstacle && label == SurfaceLabel::kUncertain);
                expected_obstacles += obstacle ? 1 : 0;
                if (obstacle) {
                    EXPECT_EQ(map.clean_color(ix, iy), kRed) << ix << ", " << iy;
                } else if (map.clean_observed(ix, iy)) {
                    EXPECT_EQ(map.clean_color(ix, iy), checker_color(p.x(), p.y()));
                }
            }
        }
        // Each 2 cm obstacle cell holds 4 × 4 map cells (the stop pose is off the 5 mm grid,
        // so the count may differ by a row or column).
        EXPECT_NEAR(static_cast<double>(expected_obstacles), uncertain_is_obstacle ? 48 : 32, 8);
        EXPECT_EQ(map.clean_stats().obstacle_cells, expected_obstacles);
        EXPECT_EQ(map.live_stats().observed_cells, 0u);  // stop images stay off the live layer
    }
}

TEST(TextureMap, RewritesTheCleanLayerAtTheNextStop) {
    TextureMap map(small_map());
    const std::size_t first_seen = stop(map, 0.0, 0.0, obstacle_grid(), stop_pose());
    ASSERT_GT(map.clean_stats().obstacle_cells, 0u);
    ASSERT_EQ(map.clean_stats().observed_cells, first_seen);
    const TextureLayerStats before = map.clean_stats();

    // Mid-stop, the clean layer still shows the previous stop in full.
    const PinholeIntrinsics camera = test_camera();
    const Eigen::Isometry3d T = looking_down(0.3, 0.3, kHeightM);
    map.begin_stop();
    const std::size_t second_seen = map.add_stop_image(render(camera, T), camera, T);
    EXPECT_EQ(map.clean_stats().observed_cells, before.observed_cells);
    EXPECT_EQ(map.clean_stats().obstacle_cells, before.obstacle_cells);
    map.end_stop(SurfaceGrid{}, Eigen::Isometry3d::Identity());  // no surface found: no labels

    EXPECT_EQ(map.num_stops(), 2u);
    EXPECT_EQ(map.clean_stats().obstacle_cells, 0u);
    EXPECT_EQ(map.clean_stats().observed_cells, second_seen);
    std::size_t stale = 0;
    for (std::size_t iy = 0; iy < map.rows(); ++iy) {
        for (std::size_t ix = 0; ix < map.columns(); ++ix) {
            const Eigen::Vector3d p = map.cell_centre_map(ix, iy);
            const bool in_second = camera.project(T.inverse(Eigen::Isometry) * p).has_value();
            if (!in_second) stale += map.clean_color(ix, iy) != kBlack ? 1 : 0;
        }
    }
    EXPECT_EQ(stale, 0u);
}

TEST(TextureMap, KeepsTheNearestViewOfAStopWhateverTheOrder) {
    const PinholeIntrinsics camera = test_camera();
    const Eigen::Isometry3d near = looking_down(0.0, 0.0, kHeightM);
    const Eigen::Isometry3d far = looking_down(0.0, 0.0, 2.0 * kHeightM);
    for (const bool near_first : {true, false}) {
        TextureMap map(small_map());
        map.begin_stop();
        if (near_first) map.add_stop_image(uniform(camera, kLight), camera, near);
        map.add_stop_image(uniform(camera, kDark), camera, far);
        if (!near_first) map.add_stop_image(uniform(camera, kLight), camera, near);
        map.end_stop(SurfaceGrid{}, Eigen::Isometry3d::Identity());
        const std::size_t centre = map.columns() / 2;
        EXPECT_EQ(map.clean_color(centre, centre), kLight);      // seen by both: the near one wins
        EXPECT_EQ(map.clean_color(centre, centre + 40), kDark);  // y = 0.2 m: only the far one
        EXPECT_TRUE(map.clean_observed(centre, centre + 40));
    }
}

class TempDir {
  public:
    TempDir() {
        const auto* test = ::testing::UnitTest::GetInstance()->current_test_info();
        path_ = fs::temp_directory_path() / (std::string("scantling_texture_map_") + test->name() +
                                             "_" + std::to_string(getpid()));
        fs::remove_all(path_);
        fs::create_directories(path_);
    }
    ~TempDir() { fs::remove_all(path_); }
    const fs::path& path() const { return path_; }

  private:
    fs::path path_;
};

std::string read_text(const fs::path& path) {
    std::ifstream in(path);
    std::stringstream text;
    text << in.rdbuf();
    return text.str();
}

TEST(TextureMap, WritesBothLayersAsPngsThatReadBackAndItsMetadata) {
    TempDir tmp;
    TextureMapConfig config = small_map();
    config.max_y_m = 0.3;  // not square, so a swapped width and height shows
    TextureMap map(config);
    const PinholeIntrinsics camera = test_camera();
    const Eigen::Isometry3d T = looking_down(0.05, 0.0, kHeightM);
    map.add_image(render(camera, T), camera, T);
    stop(map, 0.0, 0.0, obstacle_grid(), stop_pose());
    const std::string dir = (tmp.path() / "map").string();
    map.write(dir);

    const io::RgbImage live = io::read_png(dir + "/live.png");
    const io::RgbImage clean = io::read_png(dir + "/clean.png");
    ASSERT_EQ(map.columns(), 200u);
    ASSERT_EQ(map.rows(), 160u);
    for (const io::RgbImage* image : {&live, &clean}) {
        EXPECT_EQ(image->width, 200);
        EXPECT_EQ(image->height, 160);
    }
    EXPECT_EQ(live.pixels, map.live_image().pixels);
    EXPECT_EQ(clean.pixels, map.clean_image().pixels);
    // North-up: pixel (u, v) is cell (u, rows − 1 − v).
    const Eigen::Vector2d obstacle_map = (stop_pose() * Eigen::Vector3d(0.05, 0.01, 0.0)).head<2>();
    const auto ix = static_cast<std::size_t>((obstacle_map.x() - config.min_x_m) / kCellM);
    const auto iy = static_cast<std::size_t>((obstacle_map.y() - config.min_y_m) / kCellM);
    EXPECT_EQ(map.clean_color(ix, iy), kRed);
    EXPECT_EQ(clean.pixels[(map.rows() - 1 - iy) * map.columns() + ix], kRed);

    const std::string json = read_text(fs::path(dir) / "metadata.json");
    EXPECT_NE(json.find("\"cell_size_m\": 0.005"), std::string::npos) << json;
    EXPECT_NE(json.find("\"columns\": 200"), std::string::npos) << json;
    EXPECT_NE(json.find("\"max_y_m\": 0.3,"), std::string::npos) << json;
    EXPECT_NE(json.find("\"stops\": 1"), std::string::npos) << json;
    EXPECT_NE(json.find("\"obstacle_cells\": " + std::to_string(map.clean_stats().obstacle_cells)),
              std::string::npos)
        << json;
    EXPECT_NE(json.find("\"T_world_map\": [[1, 0, 0, 0], [0, 1, 0, 0]"), std::string::npos) << json;
}

TEST(TextureMap, WritesNothingWhenTheFolderCannotBeMade) {
    TempDir tmp;
    std::ofstream(tmp.path() / "blocker") << "a file";
    TextureMap map(small_map());
    EXPECT_THROW(map.write((tmp.path() / "blocker" / "map").string()), FileError);
    EXPECT_EQ(std::distance(fs::directory_iterator(tmp.path()), fs::directory_iterator{}), 1);
}

void expect_config_error(const TextureMapConfig& config, const std::string& field) {
    try {
        TextureMap map(config);
        ADD_FAILURE() << "accepted a bad " << field;
    } catch (const ConfigError& e) {
        EXPECT_NE(std::string(e.what()).find(field), std::string::npos) << e.what();
    }
}

TEST(TextureMap, RefusesABadConfigNamingTheField) {
    const auto with = [](const std::function<void(TextureMapConfig&)>& change) {
        TextureMapConfig config = small_map();
        change(config);
        return config;
    };
    const double nan = std::numeric_limits<double>::quiet_NaN();
    expect_config_error(with([](auto& c) { c.cell_size_m = 0.0; }), "texture_map.cell_size_m");
    expect_config_error(with([](auto& c) { c.max_x_m = c.min_x_m; }), "texture_map.max_x_m");
    expect_config_error(with([&](auto& c) { c.min_y_m = nan; }), "texture_map.min_y_m");
    expect_config_error(with([](auto& c) { c.max_range_m = -1.0; }), "texture_map.max_range_m");
    expect_config_error(with([&](auto& c) { c.T_world_map.translation().x() = nan; }),
                        "texture_map.T_world_map");
    expect_config_error(with([](auto& c) { c.T_world_map.linear() *= 2.0; }),
                        "texture_map.T_world_map");
    // 1 mm over 10 km × 1 m: 1e10 cells, refused before anything is allocated.
    expect_config_error(with([](auto& c) {
                            c.cell_size_m = 0.001;
                            c.max_x_m = 1e4;
                        }),
                        "texture_map.cell_size_m");
    EXPECT_NO_THROW(TextureMap{TextureMapConfig{}});
}

TEST(TextureMap, RefusesBadInputsAndLeavesTheMapUnchanged) {
    TextureMap map(small_map());
    const PinholeIntrinsics camera = test_camera();
    const Eigen::Isometry3d T = looking_down(0.0, 0.0, kHeightM);
    io::RgbImage small = uniform(camera, kLight);
    small.width = 160;
    EXPECT_THROW(map.add_image(small, camera, T), InputError);
    Eigen::Isometry3d not_finite = T;
    not_finite.translation().z() = std::numeric_limits<double>::infinity();
    EXPECT_THROW(map.add_image(uniform(camera, kLight), camera, not_finite), InputError);
    PinholeIntrinsics bad_camera = camera;
    bad_camera.fx = 0.0;
    try {
        map.add_image(uniform(camera, kLight), bad_camera, T);
        ADD_FAILURE() << "accepted fx = 0";
    } catch (const ConfigError& e) {
        EXPECT_NE(std::string(e.what()).find("texture_map.intrinsics.fx"), std::string::npos);
    }
    EXPECT_EQ(map.num_images(), 0u);
    EXPECT_EQ(map.live_stats().observed_cells, 0u);

    EXPECT_THROW(map.add_stop_image(uniform(camera, kLight), camera, T), InputError);
    EXPECT_THROW(map.end_stop(SurfaceGrid{}, T), InputError);
    map.begin_stop();
    SurfaceGrid broken = obstacle_grid();
    broken.cells.pop_back();
    EXPECT_THROW(map.end_stop(broken, Eigen::Isometry3d::Identity()), InputError);
    Eigen::Isometry3d sheared = Eigen::Isometry3d::Identity();
    sheared.linear()(0, 1) = 0.5;
    EXPECT_THROW(map.end_stop(obstacle_grid(), sheared), InputError);
    EXPECT_TRUE(map.in_stop());
    EXPECT_EQ(map.num_stops(), 0u);
}

}  // namespace
}  // namespace scantling::perception
