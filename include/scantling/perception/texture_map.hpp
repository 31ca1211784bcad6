#pragma once
/// @file
/// The magnetic crawler's texture map for its operators (SPEC §6, issue 15 item 3): the camera
/// image projected onto the locally flat ground around the robot, p = A [R|t] P_g, each ground
/// cell taking the colour of the pixel nearest to where its centre projects. Unobserved ground
/// is black, obstacles are red, free space keeps its colour. Three layers:
///   - live (bottom): every image the caller adds, drawn at the pose estimated when it was
///     taken; the latest image wins a cell, so the layer follows the robot as it drives;
///   - clean (middle): rewritten at every stop from that stop's images at the stop pose, with
///     the stop's obstacle labels (perception/surface_obstacles.hpp) painted red on top;
///   - metadata (top): metadata.json beside live.png and clean.png (write()).
///
/// Frames: the map frame is a local surface frame, T_world_map, with z the surface normal into
/// free space; the ground is its plane z = 0 (SPEC: locally flat). Camera (optical) frame and
/// pixel centres as in core/pinhole_intrinsics.hpp. The SPEC's [R|t] is the LiDAR→camera
/// extrinsic because its P_g is in the LiDAR frame; here the caller passes the composed
/// T_map_camera = T_map_body · T_body_camera, so one call serves any mount.
///
/// Grid: cell (ix, iy) spans (min_x_m, min_y_m) + cell_size_m · [ix, ix + 1] × [iy, iy + 1], its
/// centre the sample point; columns() × rows() cells (each side rounded up to whole cells). In
/// the PNGs, like a plan, x is to the right and y up: pixel (u, v) is cell (u, rows() − 1 − v).
///
/// Design choices (why):
///   - The clean layer is replaced as a whole at each end_stop, not merged: the obstacle labels
///     are relative to the current stop, and older stops drawn at poses that have drifted since
///     would show stale red where the robot may now drive. Cells this stop did not see are
///     black there; the live layer keeps the history.
///   - A stop's images are staged until end_stop, so the clean layer never shows half a stop;
///     among them, a cell keeps the colour of the view nearest to it (finest resolution), the
///     first such view on ties. The live layer is "latest wins" instead: it is the live picture.
///   - A cell is seen when its centre is in front of the camera, projects inside the image and
///     is within max_range_m, and the camera is on the free side (z > 0 in the map frame): a
///     magnetic wall is opaque. Nothing else occludes (the ground is flat).
///
/// Cost: each image tests only the cells in the bounding box of what it can see (the range disc
/// on the ground, intersected with the image's footprint when all four image corners see the
/// ground): O(cells seen). Memory: 8 bytes per cell, 16 during a stop.
/// Thread-safety: const members may run concurrently; the others must not run alongside
/// anything. @note Deterministic: serial loops in a fixed order.

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include <scantling/core/pinhole_intrinsics.hpp>
#include <scantling/core/point_cloud.hpp>
#include <scantling/io/png.hpp>
#include <scantling/perception/surface_obstacles.hpp>

namespace scantling::perception {

/// Most cells a texture map may have: 2^24 (≈ 20 m × 20 m at 5 mm, ~270 MB during a stop, and
/// well under io::kMaxPngPixels so the PNGs read back). A mistyped cell size is refused instead
/// of allocating gigabytes.
inline constexpr double kMaxTextureMapCells = 16777216.0;

struct TextureMapConfig {
    double cell_size_m = 0.005;  ///< edge of a square ground cell, > 0
    double min_x_m = -1.0;       ///< map extent in the map frame's x-y plane, metres;
    double max_x_m = 1.0;        ///< max > min on each axis
    double min_y_m = -1.0;
    double max_y_m = 1.0;
    /// The map (local surface) frame in the world: z the surface normal, ground at z = 0.
    /// Written to metadata.json for whoever places the PNGs; rotation orthonormal (1e-6).
    Eigen::Isometry3d T_world_map = Eigen::Isometry3d::Identity();
    double max_range_m = 1.5;  ///< camera-to-cell-centre distance at most this, > 0
    Rgb8 unobserved_color = Rgb8(0, 0, 0);
    Rgb8 obstacle_color = Rgb8(255, 0, 0);
    /// Also paint kUncertain cells (between the inlier and obstacle thresholds) as obstacles.
    bool uncertain_is_obstacle = false;

    /// Throws ConfigError naming "<prefix>.<field>", including the cell count above
    /// kMaxTextureMapCells (named "<prefix>.cell_size_m").
    void validate(std::string_view prefix = "texture_map") const;
};

/// Counts of one layer.
struct TextureLayerStats {
    std::size_t observed_cells = 0;  ///< cells some image coloured
    std::size_t obstacle_cells = 0;  ///< cells painted as obstacles (clean layer only)
};

class TextureMap {
  public:
    /// Both layers start unobserved. Throws ConfigError ("texture_map.*") for a bad config.
    explicit TextureMap(const TextureMapConfig& config = {});

    /// Paints the live layer from `image`, taken by a camera with `intrinsics` at T_map_camera
    /// (the estimated pose). Returns the number of cells painted (0 when the camera is below the
    /// ground or sees none of the map). Throws ConfigError ("texture_map.intrinsics.*") for bad
    /// intrinsics, InputError when the image's size differs from the intrinsics' or the pose
    /// is not finite or its rotation not orthonormal (1e-6); the map is then unchanged.
    std::size_t add_image(const io::RgbImage& image, const PinholeIntrinsics& intrinsics,
                          const Eigen::Isometry3d& T_map_camera);

    /// Starts a stop: an empty staged clean layer (a stop already begun is discarded).
    void begin_stop();
    /// Stages `image` for the stop's clean layer (the live layer is untouched: call add_image
    /// too to show it there). Returns the cells it saw. Throws as add_image, and InputError
    /// outside begin_stop() … end_stop().
    std::size_t add_stop_image(const io::RgbImage& image, const PinholeIntrinsics& intrinsics,
                               const Eigen::Isometry3d& T_map_camera);
    /// Paints the obstacle cells (kPositive, kNegative; kUncertain if so configured) of
    /// `obstacles`, a grid in the body frame of the stop at T_map_body, in obstacle_color onto
    /// the staged layer, which then replaces the clean layer. A map cell is an obstacle when
    /// its centre, taken into the body frame, falls (in x-y) in an obstacle grid cell. An empty
    /// grid (no surface found) paints nothing. Throws InputError outside a stop, for a
    /// non-finite or non-rigid T_map_body, or a grid whose cell count or cell size is
    /// inconsistent; the stop is then still open.
    void end_stop(const SurfaceGrid& obstacles, const Eigen::Isometry3d& T_map_body);
    bool in_stop() const { return in_stop_; }

    /// Writes <directory>/live.png, clean.png and metadata.json (cell size, extent, grid size,
    /// T_world_map, colours, counts of images, stops, observed and obstacle cells), all or none
    /// (io::OutputTransaction); `directory` is created when missing. Throws FileError.
    void write(const std::string& directory) const;

    /// A layer as a north-up image (see the file comment): columns() × rows() pixels.
    io::RgbImage live_image() const;
    io::RgbImage clean_image() const;

    std::size_t columns() const { return columns_; }
    std::size_t rows() const { return rows_; }
    const TextureMapConfig& config() const { return config_; }
    /// Centre of cell (ix, iy), map frame (z = 0).
    Eigen::Vector3d cell_centre_map(std::size_t ix, std::size_t iy) const;
    /// Colours and observed flags of cell (ix, iy); index iy · columns() + ix.
    Rgb8 live_color(std::size_t ix, std::size_t iy) const { return live_.colors[index(ix, iy)]; }
    Rgb8 clean_color(std::size_t ix, std::size_t iy) const { return clean_.colors[index(ix, iy)]; }
    bool live_observed(std::size_t ix, std::size_t iy) const {
        return (live_.states[index(ix, iy)] & kSeen) != 0;
    }
    bool clean_observed(std::size_t ix, std::size_t iy) const {
        return (clean_.states[index(ix, iy)] & kSeen) != 0;
    }
    TextureLayerStats live_stats() const { return stats(live_); }  ///< O(cells)
    TextureLayerStats clean_stats() const { return stats(clean_); }
    std::size_t num_images() const { return num_images_; }  ///< add_image calls
    std::size_t num_stops() const { return num_stops_; }    ///< completed stops

  private:
    struct View;
    struct CellBox {
        std::size_t ix0 = 0, iy0 = 0, ix1 = 0, iy1 = 0;  // half-open [ix0, ix1) × [iy0, iy1)
    };
    enum CellState : std::uint8_t { kUnseen = 0, kSeen = 1, kObstacle = 2 };  // bits
    struct Layer {
        std::vector<Rgb8> colors;          // index iy · columns + ix
        std::vector<std::uint8_t> states;  // CellState bits
    };

    Layer empty_layer() const;
    View make_view(const io::RgbImage& image, const PinholeIntrinsics& intrinsics,
                   const Eigen::Isometry3d& T_map_camera, std::string_view caller) const;
    CellBox cells_to_test(const View& view) const;
    CellBox clip(double x0, double y0, double x1, double y1) const;
    std::size_t paint(const View& view, Layer& layer, std::vector<float>* ranges_m) const;
    void paint_obstacles(const SurfaceGrid& obstacles, const Eigen::Isometry3d& T_map_body);
    bool is_obstacle(SurfaceLabel label) const;
    std::size_t index(std::size_t ix, std::size_t iy) const { return iy * columns_ + ix; }
    static TextureLayerStats stats(const Layer& layer);
    io::RgbImage north_up(const Layer& layer) const;
    std::string metadata_json() const;

    TextureMapConfig config_;
    std::size_t columns_ = 0;
    std::size_t rows_ = 0;
    Layer live_;
    Layer clean_;
    Layer staged_;                       // the stop in progress
    std::vector<float> staged_range_m_;  // its nearest view's range per cell
    bool in_stop_ = false;
    std::size_t num_images_ = 0;
    std::size_t num_stops_ = 0;
};

}  // namespace scantling::perception
