#include <scantling/core/error.hpp>
#include <scantling/io/svg_plot.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include "test_files.hpp"

namespace scantling::io {
namespace {

// Coordinates are printed with 2 decimals.
constexpr double kPixelTol = 0.011;

SvgPlot two_series_plot() {
    SvgPlot plot;
    plot.title = "top view";
    plot.x_label = "x [m]";
    plot.y_label = "y [m]";
    plot.series.push_back({"ground truth", "", {{0, 0}, {50, 10}, {100, 0}}});
    plot.series.push_back({"estimate", "#123456", {{0, 1}, {50, 11}, {100, 2}, {101, 3}}});
    return plot;
}

/// Well-formedness without an XML library: every element closes in order, attributes quoted,
/// no bare '&' or '<' in text.
void expect_well_formed(const std::string& svg) {
    ASSERT_EQ(svg.rfind("<?xml version=\"1.0\"", 0), 0u);
    std::vector<std::string> open;
    const std::regex tag(R"(<(/?)([A-Za-z][\w:-]*)((?:\s+[\w:-]+="[^"<]*")*)\s*(/?)>)");
    std::size_t pos = svg.find("?>") + 2;
    while (true) {
        const std::size_t lt = svg.find('<', pos);
        const std::string text = svg.substr(pos, lt == std::string::npos ? lt : lt - pos);
        EXPECT_EQ(std::regex_search(text, std::regex(R"(&(?!amp;|lt;|gt;|quot;))")), false) << text;
        if (lt == std::string::npos) break;
        std::smatch m;
        const std::string rest = svg.substr(lt);
        ASSERT_TRUE(std::regex_search(rest, m, tag, std::regex_constants::match_continuous))
            << "malformed tag at " << rest.substr(0, 60);
        if (m[1] == "/") {
            ASSERT_FALSE(open.empty()) << "unexpected </" << m[2] << ">";
            EXPECT_EQ(open.back(), m[2]);
            open.pop_back();
        } else if (m[4] != "/") {
            open.push_back(m[2]);
        }
        pos = lt + static_cast<std::size_t>(m.length(0));
    }
    EXPECT_TRUE(open.empty()) << "unclosed <" << (open.empty() ? "" : open.back()) << ">";
}

/// The pixel coordinates of the n-th polyline.
std::vector<Eigen::Vector2d> polyline(const std::string& svg, int n) {
    std::size_t pos = 0;
    for (int k = 0; k <= n; ++k) {
        pos = svg.find("<polyline", pos);
        if (pos == std::string::npos) return {};
        pos += 1;
    }
    const std::size_t start = svg.find("points=\"", pos) + 8;
    std::istringstream in(svg.substr(start, svg.find('"', start) - start));
    std::vector<Eigen::Vector2d> points;
    double x = 0, y = 0;
    char comma = 0;
    while (in >> x >> comma >> y) points.emplace_back(x, y);
    return points;
}

std::size_t count(const std::string& text, const std::string& what) {
    std::size_t n = 0;
    for (std::size_t pos = text.find(what); pos != std::string::npos;
         pos = text.find(what, pos + 1))
        ++n;
    return n;
}

TEST(SvgPlot, IsWellFormedAndHoldsEverySeriesTitleLabelsAndLegend) {
    const std::string svg = render_svg(two_series_plot());
    expect_well_formed(svg);
    EXPECT_EQ(count(svg, "<polyline"), 2u);
    EXPECT_EQ(polyline(svg, 0).size(), 3u);
    EXPECT_EQ(polyline(svg, 1).size(), 4u);
    EXPECT_NE(svg.find(">top view</text>"), std::string::npos);
    EXPECT_NE(svg.find(">x [m]</text>"), std::string::npos);
    EXPECT_NE(svg.find(">y [m]</text>"), std::string::npos);
    EXPECT_NE(svg.find(">ground truth</text>"), std::string::npos);
    EXPECT_NE(svg.find(">estimate</text>"), std::string::npos);
    EXPECT_NE(svg.find("stroke=\"#123456\""), std::string::npos);  // given colour
    EXPECT_NE(svg.find("stroke=\"#1f77b4\""), std::string::npos);  // first palette colour
}

TEST(SvgPlot, TicksAreRoundNumbersCoveringTheData) {
    const std::string svg = render_svg(two_series_plot());
    // x spans 0..101: steps of 20 from 0 to 120; y spans 0..11: steps of 2 from 0 to 12.
    for (const char* label : {">0<", ">20<", ">100<", ">120<", ">2<", ">12<"}) {
        EXPECT_NE(svg.find(label), std::string::npos) << label;
    }
    EXPECT_EQ(svg.find(">140<"), std::string::npos);
    EXPECT_EQ(svg.find(">-"), std::string::npos);  // no negative tick, no "-0"
}

TEST(SvgPlot, MapsDataToTheFrameWithYUp) {
    const std::string svg = render_svg(two_series_plot());
    const std::vector<Eigen::Vector2d> gt = polyline(svg, 0);
    ASSERT_EQ(gt.size(), 3u);
    // x: 0..120 over the 700 px plot width from 80 px; y: 0..12 over 505 px, top at 40 px.
    EXPECT_NEAR(gt[0].x(), 80.0, kPixelTol);
    EXPECT_NEAR(gt[0].y(), 40.0 + 505.0, kPixelTol);
    EXPECT_NEAR(gt[1].x(), 80.0 + 700.0 * 50.0 / 120.0, kPixelTol);
    EXPECT_NEAR(gt[1].y(), 40.0 + 505.0 * (12.0 - 10.0) / 12.0, kPixelTol);
}

TEST(SvgPlot, EqualAspectGivesOneScaleOnBothAxes) {
    SvgPlot plot;
    plot.equal_aspect = true;
    plot.series.push_back({"path", "", {{0, 0}, {400, 0}, {400, 10}}});
    const std::vector<Eigen::Vector2d> px = polyline(render_svg(plot), 0);
    ASSERT_EQ(px.size(), 3u);
    const double x_scale = (px[1].x() - px[0].x()) / 400.0;
    const double y_scale = (px[1].y() - px[2].y()) / 10.0;  // y grows downwards in SVG
    EXPECT_NEAR(x_scale, y_scale, 0.01 * x_scale);
    EXPECT_GT(x_scale, 1.0);  // the long axis fills the width (700 px for ~412 m)
}

TEST(SvgPlot, EscapesTextAndHandlesASinglePointAndAConstantSeries) {
    SvgPlot plot;
    plot.title = "a < b & \"c\"";
    plot.series.push_back({"one <point>", "", {{3, 3}}});
    plot.series.push_back({"", "", {{0, 5}, {10, 5}}});  // flat: range widened, no legend entry
    const std::string svg = render_svg(plot);
    expect_well_formed(svg);
    EXPECT_NE(svg.find("a &lt; b &amp; &quot;c&quot;"), std::string::npos);
    EXPECT_NE(svg.find("one &lt;point&gt;"), std::string::npos);
    EXPECT_EQ(count(svg, "<circle"), 1u);
    EXPECT_EQ(count(svg, "<polyline"), 1u);
    for (const Eigen::Vector2d& p : polyline(svg, 0)) EXPECT_TRUE(p.allFinite());
}

TEST(SvgPlot, RejectsNanEmptyAndBadSizes) {
    SvgPlot plot = two_series_plot();
    plot.series[1].points[2].y() = std::nan("");
    try {
        render_svg(plot);
        FAIL() << "expected InputError";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("series 1 'estimate' point 2 is not finite"),
                  std::string::npos)
            << e.what();
    }
    plot = two_series_plot();
    plot.series[0].points.clear();
    EXPECT_THROW(render_svg(plot), InputError);
    plot.series.clear();
    EXPECT_THROW(render_svg(plot), InputError);
    plot = two_series_plot();
    plot.series[0].stroke_width_px = 0.0;
    EXPECT_THROW(render_svg(plot), InputError);
    plot = two_series_plot();
    plot.width_px = 10;
    EXPECT_THROW(render_svg(plot), ConfigError);
}

TEST(SvgPlot, WritesTheRenderedDocumentAndNothingOnError) {
    const test::TempDir dir;
    const SvgPlot plot = two_series_plot();
    write_svg(dir.file("plot.svg"), plot);
    EXPECT_EQ(test::read_bytes(dir.file("plot.svg")), render_svg(plot));
    SvgPlot bad = plot;
    bad.series[0].points[0].x() = INFINITY;
    EXPECT_THROW(write_svg(dir.file("bad.svg"), bad), InputError);
    EXPECT_EQ(dir.list(), std::vector<std::string>{"plot.svg"});
    EXPECT_THROW(write_svg(dir.file("missing/plot.svg"), plot), FileError);
}

}  // namespace
}  // namespace scantling::io
