#pragma once
/// @file
/// A small dependency-free line-plot writer (SVG 1.1): title, axes with "nice" ticks (1, 2, 5
/// × 10^k) and labels, a legend, one polyline per series, and an equal-aspect mode for top
/// views of trajectories. Enough for the evaluation plots; not a plotting library.

#include <Eigen/Core>
#include <string>
#include <vector>

namespace scantling::io {

/// One polyline.
struct SvgSeries {
    std::string label;  ///< legend text (empty: not in the legend)
    /// Any SVG colour ("#1f77b4", "red"); empty picks the next colour of a fixed palette.
    std::string color;
    std::vector<Eigen::Vector2d> points;  ///< data coordinates, >= 1, all finite
    double stroke_width_px = 1.5;         ///< > 0
};

struct SvgPlot {
    std::string title;
    std::string x_label;  ///< e.g. "x [m]"
    std::string y_label;
    /// One data unit is as long on both axes (top views); the shorter range is widened.
    bool equal_aspect = false;
    int width_px = 800;             ///< whole image, >= 200
    int height_px = 600;            ///< whole image, >= 150
    std::vector<SvgSeries> series;  ///< >= 1
};

/// The plot as an SVG document. Text is XML-escaped. A degenerate range (all points on one
/// value) is widened by ±1 (or ±0.5 % of the value) so that the plot stays readable.
/// Throws InputError naming the series and point for no series, an empty series, a non-finite
/// point or a non-positive stroke width; ConfigError for a size below the minimum.
std::string render_svg(const SvgPlot& plot);

/// Renders and writes `plot` to `path` atomically (io/atomic_file.hpp). Throws as render_svg,
/// FileError when the file cannot be written; nothing is written on error.
void write_svg(const std::string& path, const SvgPlot& plot);

}  // namespace scantling::io
