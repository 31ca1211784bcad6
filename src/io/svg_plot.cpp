#include <scantling/core/error.hpp>
#include <scantling/io/atomic_file.hpp>
#include <scantling/io/svg_plot.hpp>

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>

namespace scantling::io {
namespace {

// Room around the plot area for the title (top), tick labels and axis labels (left, bottom).
constexpr double kMarginLeftPx = 80.0;
constexpr double kMarginRightPx = 20.0;
constexpr double kMarginTopPx = 40.0;
constexpr double kMarginBottomPx = 55.0;
constexpr int kMinWidthPx = 200;
constexpr int kMinHeightPx = 150;
constexpr double kTargetTicks = 6.0;
constexpr double kEqualAspectPadding = 0.03;  // so that the extreme points do not touch the frame
// matplotlib's "tab10" colours: distinct and readable for colour-blind viewers.
constexpr std::array<const char*, 6> kPalette = {"#1f77b4", "#d62728", "#2ca02c",
                                                 "#ff7f0e", "#9467bd", "#8c564b"};

struct Range {
    double lo = 0.0;
    double hi = 0.0;
    double span() const { return hi - lo; }
};

struct Frame {  // the plot area in pixels and the data ranges it shows
    double left, top, width, height;
    Range x, y;
    double px(double v) const { return left + (v - x.lo) / x.span() * width; }
    double py(double v) const { return top + (y.hi - v) / y.span() * height; }
};

std::string escape_xml(const std::string& text) {
    std::string out;
    for (const char c : text) {
        switch (c) {
            case '&':
                out += "&amp;";
                break;
            case '<':
                out += "&lt;";
                break;
            case '>':
                out += "&gt;";
                break;
            case '"':
                out += "&quot;";
                break;
            default:
                out += c;
        }
    }
    return out;
}

void check_plot(const SvgPlot& plot) {
    if (plot.width_px < kMinWidthPx || plot.height_px < kMinHeightPx) {
        throw ConfigError(fmt::format("svg_plot size = {} x {} px, expected >= {} x {}",
                                      plot.width_px, plot.height_px, kMinWidthPx, kMinHeightPx));
    }
    if (plot.series.empty()) throw InputError("render_svg: the plot has no series");
    for (std::size_t s = 0; s < plot.series.size(); ++s) {
        const SvgSeries& series = plot.series[s];
        if (series.points.empty()) {
            throw InputError(
                fmt::format("render_svg: series {} '{}' has no points", s, series.label));
        }
        if (!(series.stroke_width_px > 0.0)) {
            throw InputError(
                fmt::format("render_svg: series {} '{}' stroke_width_px = {}, expected > 0", s,
                            series.label, series.stroke_width_px));
        }
        for (std::size_t i = 0; i < series.points.size(); ++i) {
            if (!series.points[i].allFinite()) {
                throw InputError(fmt::format("render_svg: series {} '{}' point {} is not finite", s,
                                             series.label, i));
            }
        }
    }
}

/// Data range of coordinate `k` over all series, widened when all values are equal.
Range data_range(const SvgPlot& plot, int k) {
    Range r{plot.series[0].points[0][k], plot.series[0].points[0][k]};
    for (const SvgSeries& series : plot.series) {
        for (const Eigen::Vector2d& p : series.points) {
            r.lo = std::min(r.lo, p[k]);
            r.hi = std::max(r.hi, p[k]);
        }
    }
    if (r.span() <= 1e-9 * std::max(1.0, std::abs(r.lo))) {
        const double half = std::max(1.0, 0.005 * std::abs(r.lo));
        r = {r.lo - half, r.hi + half};
    }
    return r;
}

/// 1, 2 or 5 × 10^k, the step giving about kTargetTicks ticks over `span`.
double nice_step(double span) {
    const double raw = span / kTargetTicks;
    const double magnitude = std::pow(10.0, std::floor(std::log10(raw)));
    for (const double m : {1.0, 2.0, 5.0}) {
        if (m * magnitude >= raw) return m * magnitude;
    }
    return 10.0 * magnitude;
}

Range snapped_to_ticks(Range r) {
    const double step = nice_step(r.span());
    return {std::floor(r.lo / step) * step, std::ceil(r.hi / step) * step};
}

/// Widens one range so that a data unit has the same length in pixels on both axes.
void equalise_aspect(Frame& f) {
    const double pad_x = kEqualAspectPadding * f.x.span(), pad_y = kEqualAspectPadding * f.y.span();
    f.x = {f.x.lo - pad_x, f.x.hi + pad_x};
    f.y = {f.y.lo - pad_y, f.y.hi + pad_y};
    const double px_per_unit = std::min(f.width / f.x.span(), f.height / f.y.span());
    const double grow_x = 0.5 * (f.width / px_per_unit - f.x.span());
    const double grow_y = 0.5 * (f.height / px_per_unit - f.y.span());
    f.x = {f.x.lo - grow_x, f.x.hi + grow_x};
    f.y = {f.y.lo - grow_y, f.y.hi + grow_y};
}

std::vector<double> ticks(const Range& r) {
    const double step = nice_step(r.span());
    std::vector<double> values;
    const double eps = 1e-9 * step;
    for (double k = std::ceil((r.lo - eps) / step); k * step <= r.hi + eps; k += 1.0) {
        values.push_back(k * step + 0.0);  // + 0.0: no "-0" label
    }
    return values;
}

std::string tick_label(double value, double step) {
    if (std::abs(value) < 1e-9 * step) return "0";
    return fmt::format("{:g}", value);
}

void draw_axes(std::string& svg, const Frame& f, const SvgPlot& plot) {
    const double bottom = f.top + f.height, right = f.left + f.width;
    const double x_step = nice_step(f.x.span()), y_step = nice_step(f.y.span());
    for (const double v : ticks(f.x)) {
        const double x = f.px(v);
        svg += fmt::format(
            "<line class=\"grid\" x1=\"{0:.2f}\" y1=\"{1:.2f}\" x2=\"{0:.2f}\" y2=\"{2:.2f}\"/>\n"
            "<text x=\"{0:.2f}\" y=\"{3:.2f}\" text-anchor=\"middle\">{4}</text>\n",
            x, f.top, bottom, bottom + 16.0, tick_label(v, x_step));
    }
    for (const double v : ticks(f.y)) {
        const double y = f.py(v);
        svg += fmt::format(
            "<line class=\"grid\" x1=\"{0:.2f}\" y1=\"{1:.2f}\" x2=\"{2:.2f}\" y2=\"{1:.2f}\"/>\n"
            "<text x=\"{3:.2f}\" y=\"{4:.2f}\" text-anchor=\"end\">{5}</text>\n",
            f.left, y, right, f.left - 6.0, y + 4.0, tick_label(v, y_step));
    }
    svg += fmt::format(
        "<rect class=\"frame\" x=\"{:.2f}\" y=\"{:.2f}\" width=\"{:.2f}\" height=\"{:.2f}\"/>\n",
        f.left, f.top, f.width, f.height);
    svg += fmt::format("<text x=\"{:.2f}\" y=\"{:.2f}\" text-anchor=\"middle\">{}</text>\n",
                       f.left + 0.5 * f.width, bottom + 40.0, escape_xml(plot.x_label));
    svg += fmt::format(
        "<text x=\"18\" y=\"{0:.2f}\" text-anchor=\"middle\" transform=\"rotate(-90 18 {0:.2f})\">"
        "{1}</text>\n",
        f.top + 0.5 * f.height, escape_xml(plot.y_label));
    svg += fmt::format(
        "<text class=\"title\" x=\"{:.2f}\" y=\"24\" text-anchor=\"middle\">{}</text>\n",
        0.5 * plot.width_px, escape_xml(plot.title));
}

std::string color_of(const SvgPlot& plot, std::size_t s) {
    const std::string& color = plot.series[s].color;
    return escape_xml(color.empty() ? kPalette[s % kPalette.size()] : color);
}

void draw_series(std::string& svg, const Frame& f, const SvgPlot& plot) {
    svg += "<g clip-path=\"url(#plot-area)\" fill=\"none\">\n";
    for (std::size_t s = 0; s < plot.series.size(); ++s) {
        const SvgSeries& series = plot.series[s];
        if (series.points.size() == 1) {
            svg += fmt::format("<circle cx=\"{:.2f}\" cy=\"{:.2f}\" r=\"3\" fill=\"{}\"/>\n",
                               f.px(series.points[0].x()), f.py(series.points[0].y()),
                               color_of(plot, s));
            continue;
        }
        svg += fmt::format("<polyline stroke=\"{}\" stroke-width=\"{:g}\" points=\"",
                           color_of(plot, s), series.stroke_width_px);
        for (const Eigen::Vector2d& p : series.points) {
            svg += fmt::format("{:.2f},{:.2f} ", f.px(p.x()), f.py(p.y()));
        }
        svg += "\"/>\n";
    }
    svg += "</g>\n";
}

void draw_legend(std::string& svg, const Frame& f, const SvgPlot& plot) {
    std::vector<std::size_t> labelled;
    for (std::size_t s = 0; s < plot.series.size(); ++s) {
        if (!plot.series[s].label.empty()) labelled.push_back(s);
    }
    if (labelled.empty()) return;
    std::size_t longest = 0;
    for (const std::size_t s : labelled) longest = std::max(longest, plot.series[s].label.size());
    const double width = 40.0 + 7.0 * static_cast<double>(longest);
    const double x = f.left + f.width - width - 8.0, y = f.top + 8.0;
    svg += fmt::format(
        "<rect class=\"legend\" x=\"{:.2f}\" y=\"{:.2f}\" width=\"{:.2f}\" height=\"{:.2f}\"/>\n",
        x, y, width, 8.0 + 18.0 * static_cast<double>(labelled.size()));
    for (std::size_t k = 0; k < labelled.size(); ++k) {
        const double row = y + 16.0 + 18.0 * static_cast<double>(k);
        svg += fmt::format(
            "<line x1=\"{:.2f}\" y1=\"{:.2f}\" x2=\"{:.2f}\" y2=\"{:.2f}\" stroke=\"{}\" "
            "stroke-width=\"2\"/>\n<text x=\"{:.2f}\" y=\"{:.2f}\">{}</text>\n",
            x + 6.0, row - 4.0, x + 26.0, row - 4.0, color_of(plot, labelled[k]), x + 32.0, row,
            escape_xml(plot.series[labelled[k]].label));
    }
}

}  // namespace

std::string render_svg(const SvgPlot& plot) {
    check_plot(plot);
    Frame f{kMarginLeftPx,
            kMarginTopPx,
            plot.width_px - kMarginLeftPx - kMarginRightPx,
            plot.height_px - kMarginTopPx - kMarginBottomPx,
            data_range(plot, 0),
            data_range(plot, 1)};
    if (plot.equal_aspect) {
        equalise_aspect(f);
    } else {
        f.x = snapped_to_ticks(f.x);
        f.y = snapped_to_ticks(f.y);
    }
    std::string svg = fmt::format(
        "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
        "<svg xmlns=\"http://www.w3.org/2000/svg\" version=\"1.1\" width=\"{0}\" height=\"{1}\" "
        "viewBox=\"0 0 {0} {1}\" font-family=\"sans-serif\" font-size=\"12\">\n"
        "<style>.grid{{stroke:#e0e0e0;stroke-width:1}} .frame{{fill:none;stroke:#000}} "
        ".legend{{fill:#fff;fill-opacity:0.85;stroke:#999}} .title{{font-size:15px}}</style>\n"
        "<rect width=\"100%\" height=\"100%\" fill=\"#fff\"/>\n"
        "<defs><clipPath id=\"plot-area\"><rect x=\"{2:.2f}\" y=\"{3:.2f}\" width=\"{4:.2f}\" "
        "height=\"{5:.2f}\"/></clipPath></defs>\n",
        plot.width_px, plot.height_px, f.left, f.top, f.width, f.height);
    draw_axes(svg, f, plot);
    draw_series(svg, f, plot);
    draw_legend(svg, f, plot);
    svg += "</svg>\n";
    return svg;
}

void write_svg(const std::string& path, const SvgPlot& plot) {
    const std::string svg = render_svg(plot);  // before the file is opened: nothing on error
    write_file_atomically(path, [&](std::ostream& out) { out << svg; });
}

}  // namespace scantling::io
