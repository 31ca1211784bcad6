#include <scantling/core/config_checks.hpp>
#include <scantling/core/error.hpp>
#include <scantling/io/output_transaction.hpp>
#include <scantling/perception/texture_map.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <optional>
#include <utility>

#include <fmt/format.h>

namespace scantling::perception {
namespace {

// Rotations come from normalised quaternions or products of them (errors ~1e-15); 1e-6 still
// catches a scaled or sheared matrix.
constexpr double kRotationTolerance = 1e-6;
// A side that is a whole number of cells up to rounding (2.0 / 0.005 = 400.00000000000006)
// must not get an extra sliver column.
constexpr double kWholeCellsTolerance = 1e-9;
// Body z this close to parallel to the ground: the obstacle grid's shadow on the ground is
// unbounded, so every map cell is tested.
constexpr double kGrazingNormal = 1e-6;

/// Empty when T is finite and rigid, else why not.
std::optional<std::string> rigid_problem(const Eigen::Isometry3d& T) {
    if (!T.matrix().allFinite()) return "is not finite";
    const Eigen::Matrix3d R = T.linear();
    const double error = (R.transpose() * R - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff();
    if (error > kRotationTolerance || R.determinant() < 0.0) {
        return fmt::format("has a rotation that is not orthonormal (|RᵀR − I| = {}, det = {})",
                           error, R.determinant());
    }
    return std::nullopt;
}

void require_rigid_input(const Eigen::Isometry3d& T, std::string_view caller,
                         std::string_view name) {
    if (const auto problem = rigid_problem(T)) {
        throw InputError(fmt::format("texture_map.{}: {} {}", caller, name, *problem));
    }
}

double cells_along(double length_m, double cell_m) {
    return std::max(1.0, std::ceil(length_m / cell_m - kWholeCellsTolerance));
}

void require_extent(double min_m, double max_m, std::string_view prefix, std::string_view axis) {
    const std::string min_field = fmt::format("min_{}_m", axis);
    const std::string max_field = fmt::format("max_{}_m", axis);
    config_checks::require(std::isfinite(min_m), prefix, min_field, min_m, "finite");
    config_checks::require(std::isfinite(max_m) && max_m > min_m, prefix, max_field, max_m,
                           fmt::format("finite > {}.{} = {}", prefix, min_field, min_m));
}

void require_grid(const SurfaceGrid& grid) {
    const auto n = static_cast<std::size_t>(std::max(grid.cells_per_side, 0));
    const bool geometry_ok = n == 0 || (std::isfinite(grid.cell_size_m) && grid.cell_size_m > 0.0 &&
                                        grid.origin_xy_m.allFinite());
    if (grid.cells_per_side < 0 || grid.cells.size() != n * n || !geometry_ok) {
        throw InputError(fmt::format(
            "texture_map.end_stop: obstacles has {} cells, cells_per_side = {}, cell_size_m = {}, "
            "origin ({}, {}); expected cells_per_side² cells, a finite cell size > 0 and origin",
            grid.cells.size(), grid.cells_per_side, grid.cell_size_m, grid.origin_xy_m.x(),
            grid.origin_xy_m.y()));
    }
}

std::string json_matrix(const Eigen::Matrix4d& M) {
    std::string rows;
    for (int r = 0; r < 4; ++r) {
        rows += fmt::format("{}[{}, {}, {}, {}]", r == 0 ? "" : ", ", M(r, 0), M(r, 1), M(r, 2),
                            M(r, 3));
    }
    return "[" + rows + "]";
}

std::string json_rgb(const Rgb8& c) { return fmt::format("[{}, {}, {}]", c[0], c[1], c[2]); }

}  // namespace

void TextureMapConfig::validate(std::string_view prefix) const {
    config_checks::require_positive(cell_size_m, prefix, "cell_size_m");
    require_extent(min_x_m, max_x_m, prefix, "x");
    require_extent(min_y_m, max_y_m, prefix, "y");
    config_checks::require_positive(max_range_m, prefix, "max_range_m");
    if (const auto problem = rigid_problem(T_world_map)) {
        throw ConfigError(
            fmt::format("{}.T_world_map {}, expected a rigid transform", prefix, *problem));
    }
    const double cells =
        cells_along(max_x_m - min_x_m, cell_size_m) * cells_along(max_y_m - min_y_m, cell_size_m);
    if (!(cells <= kMaxTextureMapCells)) {
        throw ConfigError(fmt::format(
            "{}.cell_size_m = {} over {} × {} m gives {} cells, expected <= {} (a larger cell "
            "or a smaller extent)",
            prefix, cell_size_m, max_x_m - min_x_m, max_y_m - min_y_m, cells, kMaxTextureMapCells));
    }
}

struct TextureMap::View {
    const io::RgbImage* image = nullptr;
    PinholeIntrinsics intrinsics;
    Eigen::Isometry3d T_map_camera;
    Eigen::Isometry3d T_camera_map;
};

TextureMap::TextureMap(const TextureMapConfig& config) : config_(config) {
    config_.validate();
    columns_ = static_cast<std::size_t>(
        cells_along(config_.max_x_m - config_.min_x_m, config_.cell_size_m));
    rows_ = static_cast<std::size_t>(
        cells_along(config_.max_y_m - config_.min_y_m, config_.cell_size_m));
    live_ = empty_layer();
    clean_ = empty_layer();
}

TextureMap::Layer TextureMap::empty_layer() const {
    return {std::vector<Rgb8>(columns_ * rows_, config_.unobserved_color),
            std::vector<std::uint8_t>(columns_ * rows_, kUnseen)};
}

TextureMap::View TextureMap::make_view(const io::RgbImage& image,
                                       const PinholeIntrinsics& intrinsics,
                                       const Eigen::Isometry3d& T_map_camera,
                                       std::string_view caller) const {
    intrinsics.validate("texture_map.intrinsics");
    const auto pixels =
        static_cast<std::size_t>(intrinsics.width) * static_cast<std::size_t>(intrinsics.height);
    if (image.width != intrinsics.width || image.height != intrinsics.height ||
        image.pixels.size() != pixels) {
        throw InputError(fmt::format(
            "texture_map.{}: image of {} × {} px with {} pixels, expected the intrinsics' {} × {}",
            caller, image.width, image.height, image.pixels.size(), intrinsics.width,
            intrinsics.height));
    }
    require_rigid_input(T_map_camera, caller, "T_map_camera");
    return {&image, intrinsics, T_map_camera, T_map_camera.inverse(Eigen::Isometry)};
}

TextureMap::CellBox TextureMap::clip(double x0, double y0, double x1, double y1) const {
    // Cells whose centres lie in [x0, x1] × [y0, y1]; the clamps in double keep infinite or
    // huge bounds from overflowing the conversion.
    const auto first = [&](double lo_m, double min_m, std::size_t count) {
        const double i = std::ceil((lo_m - min_m) / config_.cell_size_m - 0.5);
        return static_cast<std::size_t>(std::clamp(i, 0.0, static_cast<double>(count)));
    };
    const auto end = [&](double hi_m, double min_m, std::size_t count) {
        const double i = std::floor((hi_m - min_m) / config_.cell_size_m - 0.5) + 1.0;
        return static_cast<std::size_t>(std::clamp(i, 0.0, static_cast<double>(count)));
    };
    CellBox box{first(x0, config_.min_x_m, columns_), first(y0, config_.min_y_m, rows_),
                end(x1, config_.min_x_m, columns_), end(y1, config_.min_y_m, rows_)};
    box.ix1 = std::max(box.ix1, box.ix0);
    box.iy1 = std::max(box.iy1, box.iy0);
    return box;
}

TextureMap::CellBox TextureMap::cells_to_test(const View& view) const {
    const Eigen::Vector3d c = view.T_map_camera.translation();
    // Below the ground (or in it), or too high to see any ground within range: nothing.
    if (!(c.z() > 0.0) || c.z() > config_.max_range_m) return {};
    const double r = std::sqrt(config_.max_range_m * config_.max_range_m - c.z() * c.z());
    Eigen::Vector2d lo(c.x() - r, c.y() - r);
    Eigen::Vector2d hi(c.x() + r, c.y() + r);
    // When every image corner sees the ground, the image's footprint is the convex quadrilateral
    // of their hits (a projective map keeps convexity in front of the camera).
    const double w = view.intrinsics.width - 0.5;
    const double h = view.intrinsics.height - 0.5;
    const std::array<Eigen::Vector2d, 4> corners{
        Eigen::Vector2d(-0.5, -0.5), {w, -0.5}, {w, h}, {-0.5, h}};
    Eigen::Vector2d foot_lo = Eigen::Vector2d::Constant(std::numeric_limits<double>::infinity());
    Eigen::Vector2d foot_hi = -foot_lo;
    for (const auto& corner : corners) {
        const Eigen::Vector3d d =
            view.T_map_camera.linear() * view.intrinsics.ray_direction(corner);
        if (!(d.z() < 0.0)) return clip(lo.x(), lo.y(), hi.x(), hi.y());
        const Eigen::Vector2d hit = (c + d * (-c.z() / d.z())).head<2>();
        foot_lo = foot_lo.cwiseMin(hit);
        foot_hi = foot_hi.cwiseMax(hit);
    }
    lo = lo.cwiseMax(foot_lo);
    hi = hi.cwiseMin(foot_hi);
    return clip(lo.x(), lo.y(), hi.x(), hi.y());
}

std::size_t TextureMap::paint(const View& view, Layer& layer, std::vector<float>* ranges_m) const {
    const CellBox box = cells_to_test(view);
    const int width = view.intrinsics.width;
    std::size_t painted = 0;
    for (std::size_t iy = box.iy0; iy < box.iy1; ++iy) {
        for (std::size_t ix = box.ix0; ix < box.ix1; ++ix) {
            const Eigen::Vector3d p_camera = view.T_camera_map * cell_centre_map(ix, iy);
            const double range_m = p_camera.norm();
            if (range_m > config_.max_range_m) continue;
            const auto pixel = view.intrinsics.project(p_camera);
            if (!pixel) continue;
            const std::size_t i = index(ix, iy);
            if (ranges_m != nullptr) {
                if (!(range_m < (*ranges_m)[i])) continue;
                (*ranges_m)[i] = static_cast<float>(range_m);
            }
            // Pixel centres are at integers, so the nearest pixel is the rounded coordinate;
            // project() keeps it in [−0.5, size − 0.5), hence in the image.
            const auto u = static_cast<std::size_t>(std::floor(pixel->x() + 0.5));
            const auto v = static_cast<std::size_t>(std::floor(pixel->y() + 0.5));
            layer.colors[i] = view.image->pixels[v * static_cast<std::size_t>(width) + u];
            layer.states[i] = kSeen;
            ++painted;
        }
    }
    return painted;
}

std::size_t TextureMap::add_image(const io::RgbImage& image, const PinholeIntrinsics& intrinsics,
                                  const Eigen::Isometry3d& T_map_camera) {
    const View view = make_view(image, intrinsics, T_map_camera, "add_image");
    ++num_images_;
    return paint(view, live_, nullptr);
}

void TextureMap::begin_stop() {
    staged_ = empty_layer();
    staged_range_m_.assign(columns_ * rows_, std::numeric_limits<float>::infinity());
    in_stop_ = true;
}

std::size_t TextureMap::add_stop_image(const io::RgbImage& image,
                                       const PinholeIntrinsics& intrinsics,
                                       const Eigen::Isometry3d& T_map_camera) {
    if (!in_stop_) throw InputError("texture_map.add_stop_image: no stop begun (begin_stop)");
    const View view = make_view(image, intrinsics, T_map_camera, "add_stop_image");
    return paint(view, staged_, &staged_range_m_);
}

bool TextureMap::is_obstacle(SurfaceLabel label) const {
    return label == SurfaceLabel::kPositive || label == SurfaceLabel::kNegative ||
           (config_.uncertain_is_obstacle && label == SurfaceLabel::kUncertain);
}

void TextureMap::paint_obstacles(const SurfaceGrid& grid, const Eigen::Isometry3d& T_map_body) {
    if (grid.cells_per_side == 0) return;
    // The grid lies in the body's x-y plane; a map cell is tested through its centre's body
    // x-y, i.e. along body z, so the grid's shadow on the ground bounds the cells to test.
    const Eigen::Vector3d z_map = T_map_body.linear().col(2);
    CellBox box{0, 0, columns_, rows_};
    if (std::abs(z_map.z()) > kGrazingNormal) {
        const double side_m = grid.cell_size_m * grid.cells_per_side;
        Eigen::Vector2d lo = Eigen::Vector2d::Constant(std::numeric_limits<double>::infinity());
        Eigen::Vector2d hi = -lo;
        for (const double dx : {0.0, side_m}) {
            for (const double dy : {0.0, side_m}) {
                const Eigen::Vector2d xy_body = grid.origin_xy_m + Eigen::Vector2d(dx, dy);
                const Eigen::Vector3d c = T_map_body * Eigen::Vector3d(xy_body.x(), xy_body.y(), 0);
                const Eigen::Vector2d hit = (c - z_map * (c.z() / z_map.z())).head<2>();
                lo = lo.cwiseMin(hit);
                hi = hi.cwiseMax(hit);
            }
        }
        box = clip(lo.x(), lo.y(), hi.x(), hi.y());
    }
    const Eigen::Isometry3d T_body_map = T_map_body.inverse(Eigen::Isometry);
    for (std::size_t iy = box.iy0; iy < box.iy1; ++iy) {
        for (std::size_t ix = box.ix0; ix < box.ix1; ++ix) {
            const Eigen::Vector3d p_body = T_body_map * cell_centre_map(ix, iy);
            if (!is_obstacle(grid.label_at(p_body.head<2>()))) continue;
            staged_.colors[index(ix, iy)] = config_.obstacle_color;
            staged_.states[index(ix, iy)] |= kObstacle;
        }
    }
}

void TextureMap::end_stop(const SurfaceGrid& obstacles, const Eigen::Isometry3d& T_map_body) {
    if (!in_stop_) throw InputError("texture_map.end_stop: no stop begun (begin_stop)");
    require_rigid_input(T_map_body, "end_stop", "T_map_body");
    require_grid(obstacles);
    paint_obstacles(obstacles, T_map_body);
    clean_ = std::exchange(staged_, {});
    staged_range_m_ = {};
    in_stop_ = false;
    ++num_stops_;
}

Eigen::Vector3d TextureMap::cell_centre_map(std::size_t ix, std::size_t iy) const {
    return {config_.min_x_m + (static_cast<double>(ix) + 0.5) * config_.cell_size_m,
            config_.min_y_m + (static_cast<double>(iy) + 0.5) * config_.cell_size_m, 0.0};
}

TextureLayerStats TextureMap::stats(const Layer& layer) {
    TextureLayerStats stats;
    for (const std::uint8_t state : layer.states) {
        stats.observed_cells += (state & kSeen) != 0 ? 1 : 0;
        stats.obstacle_cells += (state & kObstacle) != 0 ? 1 : 0;
    }
    return stats;
}

io::RgbImage TextureMap::north_up(const Layer& layer) const {
    io::RgbImage image{static_cast<int>(columns_), static_cast<int>(rows_), {}};
    image.pixels.reserve(layer.colors.size());
    for (std::size_t v = 0; v < rows_; ++v) {
        const auto row =
            layer.colors.begin() + static_cast<std::ptrdiff_t>((rows_ - 1 - v) * columns_);
        image.pixels.insert(image.pixels.end(), row, row + static_cast<std::ptrdiff_t>(columns_));
    }
    return image;
}

io::RgbImage TextureMap::live_image() const { return north_up(live_); }
io::RgbImage TextureMap::clean_image() const { return north_up(clean_); }

std::string TextureMap::metadata_json() const {
    const TextureLayerStats live = live_stats();
    const TextureLayerStats clean = clean_stats();
    // max_*_m: the grid's extent in whole cells, to 12 digits, since min + n · cell adds
    // rounding noise (−0.5 + 160 · 0.005 = 0.30000000000000004).
    return fmt::format(
        "{{\n  \"cell_size_m\": {},\n  \"columns\": {},\n  \"rows\": {},\n"
        "  \"min_x_m\": {},\n  \"min_y_m\": {},\n  \"max_x_m\": {:.12g},\n  \"max_y_m\": {:.12g},\n"
        "  \"pixel_to_cell\": \"pixel (u, v) is cell (u, rows - 1 - v); x right, y up\",\n"
        "  \"T_world_map\": {},\n  \"max_range_m\": {},\n"
        "  \"unobserved_rgb\": {},\n  \"obstacle_rgb\": {},\n"
        "  \"images\": {},\n  \"stops\": {},\n"
        "  \"live\": {{\"file\": \"live.png\", \"observed_cells\": {}}},\n"
        "  \"clean\": {{\"file\": \"clean.png\", \"observed_cells\": {}, \"obstacle_cells\": {}}}\n"
        "}}\n",
        config_.cell_size_m, columns_, rows_, config_.min_x_m, config_.min_y_m,
        config_.min_x_m + static_cast<double>(columns_) * config_.cell_size_m,
        config_.min_y_m + static_cast<double>(rows_) * config_.cell_size_m,
        json_matrix(config_.T_world_map.matrix()), config_.max_range_m,
        json_rgb(config_.unobserved_color), json_rgb(config_.obstacle_color), num_images_,
        num_stops_, live.observed_cells, clean.observed_cells, clean.obstacle_cells);
}

void TextureMap::write(const std::string& directory) const {
    io::OutputTransaction transaction;
    transaction.create_folder(directory);
    const std::string prefix = directory + "/";
    transaction.write(prefix + "live.png",
                      [&](const std::string& path) { io::write_png(path, live_image()); });
    transaction.write(prefix + "clean.png",
                      [&](const std::string& path) { io::write_png(path, clean_image()); });
    transaction.write_stream(prefix + "metadata.json",
                             [&](std::ostream& out) { out << metadata_json(); });
    transaction.commit();
}

}  // namespace scantling::perception
