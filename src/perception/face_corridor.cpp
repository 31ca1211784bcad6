// The crawler's face corridor (face_corridor.hpp).
#include <scantling/perception/face_corridor.hpp>

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <span>
#include <vector>

#include <scantling/core/config_checks.hpp>
#include <scantling/core/error.hpp>

namespace scantling::perception {
namespace {

/// More cells than this is a config mistake (a micrometre cell), not a grid to allocate.
constexpr double kMaxGridCells = 1e7;
constexpr std::size_t kOutside = std::numeric_limits<std::size_t>::max();

enum class CellKind : std::uint8_t { kEmpty, kFace, kWall, kDrop };

struct LateralPoint {
    double y_m = 0.0;
    double z_m = 0.0;
};

/// The window's points binned by cell (compressed rows: cell i holds points
/// [begin[i], begin[i + 1])), and each cell's kind. Column `cols / 2` starts at y = 0.
struct Grid {
    FaceCorridorConfig config;
    int rows = 0;
    int cols = 0;
    std::vector<std::size_t> begin;
    std::vector<LateralPoint> points;
    std::vector<CellKind> kinds;

    std::size_t index(int row, int col) const {
        return static_cast<std::size_t>(row) * static_cast<std::size_t>(cols) +
               static_cast<std::size_t>(col);
    }
    std::span<const LateralPoint> cell(int row, int col) const {
        const std::size_t i = index(row, col);
        return std::span<const LateralPoint>(points).subspan(begin[i], begin[i + 1] - begin[i]);
    }
    CellKind kind(int row, int col) const { return kinds[index(row, col)]; }
    /// The row's x: the middle of its extent (the last row may be cut short by max_x_m).
    double row_x_m(int row) const {
        const double lo = config.min_x_m + row * config.cell_size_m;
        return 0.5 * (lo + std::min(lo + config.cell_size_m, config.max_x_m));
    }
};

int grid_rows(const FaceCorridorConfig& c) {
    return std::max(1, static_cast<int>(std::ceil((c.max_x_m - c.min_x_m) / c.cell_size_m)));
}

int grid_cols(const FaceCorridorConfig& c) {
    return 2 * static_cast<int>(std::ceil(c.max_half_width_m / c.cell_size_m));
}

/// The cell index of p, kOutside when p is out of the window.
std::size_t cell_of(const Eigen::Vector3d& p, const Grid& g) {
    const FaceCorridorConfig& c = g.config;
    if (p.x() < c.min_x_m || p.x() > c.max_x_m || std::abs(p.y()) > c.max_half_width_m) {
        return kOutside;
    }
    const int row = std::min(static_cast<int>((p.x() - c.min_x_m) / c.cell_size_m), g.rows - 1);
    const int col = static_cast<int>(std::floor(p.y() / c.cell_size_m)) + g.cols / 2;
    return g.index(row, std::clamp(col, 0, g.cols - 1));
}

/// Median of `values` (reordered). An order statistic, so independent of the input order.
double median(std::vector<double>& values) {
    const auto mid = values.begin() + static_cast<std::ptrdiff_t>(values.size() / 2);
    std::nth_element(values.begin(), mid, values.end());
    if (values.size() % 2 == 1) return *mid;
    return 0.5 * (*mid + *std::max_element(values.begin(), mid));
}

CellKind classify(std::span<const LateralPoint> cell, double tolerance_m,
                  std::vector<double>& scratch) {
    if (cell.empty()) return CellKind::kEmpty;
    scratch.clear();
    for (const LateralPoint& p : cell) scratch.push_back(p.z_m);
    const double z_m = median(scratch);
    if (std::abs(z_m) < tolerance_m) return CellKind::kFace;
    return z_m > 0.0 ? CellKind::kWall : CellKind::kDrop;
}

/// Bins the finite points of the window by cell (a counting sort: compressed rows).
void bin_points(const PointCloud& cloud, Grid& g, std::size_t& points_dropped) {
    const std::size_t num_cells = g.index(g.rows, 0);
    std::vector<std::size_t> cell_of_point(cloud.size(), kOutside);
    g.begin.assign(num_cells + 1, 0);
    for (std::size_t i = 0; i < cloud.size(); ++i) {
        if (!cloud.points[i].allFinite()) {
            ++points_dropped;
            continue;
        }
        cell_of_point[i] = cell_of(cloud.points[i], g);
        if (cell_of_point[i] != kOutside) ++g.begin[cell_of_point[i] + 1];
    }
    for (std::size_t i = 0; i < num_cells; ++i) g.begin[i + 1] += g.begin[i];
    g.points.resize(g.begin[num_cells]);
    std::vector<std::size_t> next(g.begin.begin(), g.begin.end() - 1);
    for (std::size_t i = 0; i < cloud.size(); ++i) {
        if (cell_of_point[i] == kOutside) continue;
        g.points[next[cell_of_point[i]]++] = {cloud.points[i].y(), cloud.points[i].z()};
    }
}

Grid make_grid(const PointCloud& cloud, const FaceCorridorConfig& config,
               std::size_t& points_dropped) {
    Grid g;
    g.config = config;
    g.rows = grid_rows(config);
    g.cols = grid_cols(config);
    bin_points(cloud, g, points_dropped);
    std::vector<double> scratch;
    for (int row = 0; row < g.rows; ++row) {
        for (int col = 0; col < g.cols; ++col) {
            g.kinds.push_back(classify(g.cell(row, col), config.face_tolerance_m, scratch));
        }
    }
    return g;
}

struct RowBoundary {
    CorridorBound bound = CorridorBound::kNone;
    double y_m = 0.0;
};

/// A wall's foot: the median y of the points rising out of the face in the last face cell and
/// the wall cell. A vertical wall gives its own y whatever part of the cell it crosses; the
/// face's noise spikes in the two cells are a small minority against the wall's returns.
double wall_y_m(const Grid& g, int row, int last_face, int wall) {
    std::vector<double> ys;
    for (const int col : {last_face, wall}) {
        for (const LateralPoint& p : g.cell(row, col)) {
            if (p.z_m >= g.config.face_tolerance_m) ys.push_back(p.y_m);
        }
    }
    return median(ys);  // not empty: the wall cell's upper middle value rises
}

/// An edge: the outermost face point of the last face cell and the next one (a cell across
/// the edge whose median fell below the face may still hold face points up to the edge).
/// Without any (an even count's median can fall between two points off the face, as with
/// z = ±4 cm), the last face cell's outer side.
double edge_y_m(const Grid& g, int row, int last_face, int step) {
    const double cell_m = g.config.cell_size_m;
    double outermost = step * (last_face - g.cols / 2 + (step > 0 ? 1 : 0)) * cell_m;
    bool seen = false;
    for (const int col : {last_face, last_face + step}) {
        for (const LateralPoint& p : g.cell(row, col)) {
            if (std::abs(p.z_m) >= g.config.face_tolerance_m) continue;
            outermost = seen ? std::max(outermost, step * p.y_m) : step * p.y_m;
            seen = true;
        }
    }
    return step * outermost;
}

/// Walks the face from `start` in direction `step` (+1 left, −1 right); see the file comment.
RowBoundary walk(const Grid& g, int row, int start, int step) {
    int last_face = start;
    std::size_t gap = 0;
    for (int col = start + step; col >= 0 && col < g.cols; col += step) {
        const CellKind kind = g.kind(row, col);
        if (kind == CellKind::kFace) {
            last_face = col;
            gap = 0;
        } else if (kind == CellKind::kWall) {
            return {CorridorBound::kWall, wall_y_m(g, row, last_face, col)};
        } else if (kind == CellKind::kDrop || ++gap > g.config.max_gap_cells) {
            return {CorridorBound::kEdge, edge_y_m(g, row, last_face, step)};
        }
    }
    return {};  // the face (or a short gap) runs on to max_half_width_m: nothing seen
}

/// The face cell nearest y = 0 (the left one of an equidistant pair), −1 when none.
int start_col(const Grid& g, int row) {
    for (int k = 0; k < g.cols / 2; ++k) {
        for (const int col : {g.cols / 2 + k, g.cols / 2 - 1 - k}) {
            if (g.kind(row, col) == CellKind::kFace) return col;
        }
    }
    return -1;
}

struct RowSample {
    double x_m = 0.0;
    RowBoundary left;
    RowBoundary right;
};

struct RowCounts {
    std::size_t with_face = 0, left = 0, right = 0, both = 0;
};

/// True when the row's boundaries are of the kinds `bounds` asks for.
bool wanted(const RowSample& s, CorridorBounds bounds) {
    const CorridorBound l = s.left.bound, r = s.right.bound;
    switch (bounds) {
        case CorridorBounds::kWalls:
            return l == CorridorBound::kWall && r == CorridorBound::kWall;
        case CorridorBounds::kEdges:
            return l == CorridorBound::kEdge && r == CorridorBound::kEdge;
        case CorridorBounds::kWallAndEdge:
            return (l == CorridorBound::kWall) != (r == CorridorBound::kWall);
        default:
            return true;
    }
}

/// kWallAndEdge: only the rows with the wall on the side most rows have it (ties: left).
void keep_one_way_round(std::vector<RowSample>& rows) {
    const auto left_wall = [](const RowSample& s) { return s.left.bound == CorridorBound::kWall; };
    const auto n_left =
        static_cast<std::size_t>(std::count_if(rows.begin(), rows.end(), left_wall));
    const bool keep_left = 2 * n_left >= rows.size();
    std::erase_if(rows, [&](const RowSample& s) { return left_wall(s) != keep_left; });
}

/// The rows with both boundaries of the kinds wanted, nearest first; `counts` says what the
/// others lacked.
std::vector<RowSample> row_samples(const Grid& g, RowCounts& counts) {
    std::vector<RowSample> out;
    for (int row = 0; row < g.rows; ++row) {
        const int start = start_col(g, row);
        if (start < 0) continue;
        const RowSample s{.x_m = g.row_x_m(row),
                          .left = walk(g, row, start, +1),
                          .right = walk(g, row, start, -1)};
        ++counts.with_face;
        counts.left += s.left.bound != CorridorBound::kNone;
        counts.right += s.right.bound != CorridorBound::kNone;
        if (s.left.bound != CorridorBound::kNone && s.right.bound != CorridorBound::kNone) {
            counts.both += 1;
            if (wanted(s, g.config.bounds)) out.push_back(s);
        }
    }
    if (g.config.bounds == CorridorBounds::kWallAndEdge) keep_one_way_round(out);
    return out;
}

/// y = left_m + slope x and y = right_m + slope x.
struct ParallelLines {
    double left_m = 0.0;
    double right_m = 0.0;
    double slope = 0.0;

    /// Perpendicular distances of the row's boundaries from their lines, m.
    Eigen::Vector2d residuals_m(const RowSample& s) const {
        const double scale = 1.0 / std::sqrt(1.0 + slope * slope);
        return scale * Eigen::Vector2d(s.left.y_m - left_m - slope * s.x_m,
                                       s.right.y_m - right_m - slope * s.x_m);
    }
};

/// Least squares with a common slope. The rows share their x, so the slope is the mean of the
/// two sides' own slopes, and each line passes through its side's centroid.
ParallelLines fit_parallel(std::span<const RowSample> rows) {
    double x = 0.0, left = 0.0, right = 0.0;
    for (const RowSample& s : rows) {
        x += s.x_m;
        left += s.left.y_m;
        right += s.right.y_m;
    }
    const double n = static_cast<double>(rows.size());
    x /= n;
    left /= n;
    right /= n;
    double sxx = 0.0, sxy = 0.0;
    for (const RowSample& s : rows) {
        sxx += (s.x_m - x) * (s.x_m - x);
        sxy += (s.x_m - x) * (s.left.y_m - left + s.right.y_m - right);
    }
    const double slope = sxx > 0.0 ? sxy / (2.0 * sxx) : 0.0;  // one row: no slope to see
    return {.left_m = left - slope * x, .right_m = right - slope * x, .slope = slope};
}

/// Drops the worst row while it is beyond max_boundary_residual_m (one at a time: an outlier
/// pulls the first fit towards it, so good rows near it may look bad until it is gone).
ParallelLines fit_robust(std::vector<RowSample>& rows, const FaceCorridorConfig& config) {
    ParallelLines lines;
    while (rows.size() >= config.min_rows) {
        lines = fit_parallel(rows);
        const auto worst =
            std::max_element(rows.begin(), rows.end(), [&](const RowSample& a, const RowSample& b) {
                return lines.residuals_m(a).cwiseAbs().maxCoeff() <
                       lines.residuals_m(b).cwiseAbs().maxCoeff();
            });
        if (lines.residuals_m(*worst).cwiseAbs().maxCoeff() <= config.max_boundary_residual_m) {
            break;
        }
        rows.erase(worst);
    }
    return lines;
}

/// The kind seen on most rows; a tie is an edge (the kind that must not be driven over).
CorridorBound majority(std::span<const RowSample> rows, RowBoundary RowSample::*side) {
    std::size_t walls = 0;
    for (const RowSample& s : rows) walls += (s.*side).bound == CorridorBound::kWall;
    return 2 * walls > rows.size() ? CorridorBound::kWall : CorridorBound::kEdge;
}

void fill_corridor(std::span<const RowSample> rows, const ParallelLines& lines, FaceCorridor& out) {
    const double norm = std::sqrt(1.0 + lines.slope * lines.slope);
    const double centre_m = 0.5 * (lines.left_m + lines.right_m);
    const double x0_m = rows.front().x_m;
    double sum_sq = 0.0;
    for (const RowSample& s : rows) sum_sq += lines.residuals_m(s).squaredNorm();
    out.found = true;
    out.status = "ok";
    out.origin_m = Eigen::Vector3d(x0_m, centre_m + lines.slope * x0_m, 0.0);
    out.direction = Eigen::Vector3d(1.0, lines.slope, 0.0) / norm;
    out.left_offset_m = (lines.left_m - centre_m) / norm;
    out.right_offset_m = (lines.right_m - centre_m) / norm;
    out.width_m = out.left_offset_m - out.right_offset_m;
    out.left_bound = majority(rows, &RowSample::left);
    out.right_bound = majority(rows, &RowSample::right);
    out.rows_used = rows.size();
    out.boundary_rms_m = std::sqrt(sum_sq / (2.0 * static_cast<double>(rows.size())));
}

}  // namespace

void FaceCorridorConfig::validate(std::string_view prefix) const {
    config_checks::require_positive(cell_size_m, prefix, "cell_size_m");
    config_checks::require_positive(face_tolerance_m, prefix, "face_tolerance_m");
    config_checks::require(std::isfinite(min_x_m), prefix, "min_x_m", min_x_m, "finite");
    config_checks::require(std::isfinite(max_x_m) && max_x_m > min_x_m, prefix, "max_x_m", max_x_m,
                           fmt::format("finite > min_x_m = {}", min_x_m));
    config_checks::require(std::isfinite(max_half_width_m) && max_half_width_m > cell_size_m,
                           prefix, "max_half_width_m", max_half_width_m,
                           fmt::format("finite > cell_size_m = {}", cell_size_m));
    const double cells = (max_x_m - min_x_m) * 2.0 * max_half_width_m / (cell_size_m * cell_size_m);
    config_checks::require(cells <= kMaxGridCells, prefix, "cell_size_m", cell_size_m,
                           fmt::format("a grid of at most {} cells", kMaxGridCells));
    config_checks::require_count_at_least(min_rows, 1, prefix, "min_rows");
    config_checks::require_positive(max_boundary_residual_m, prefix, "max_boundary_residual_m");
}

FaceCorridor extract_face_corridor(const PointCloud& cloud, const FaceCorridorConfig& config) {
    config.validate();
    FaceCorridor out;
    const Grid grid = make_grid(cloud, config, out.points_dropped);
    if (grid.points.empty()) {
        out.status = fmt::format("no finite points within x in [{}, {}] m, |y| <= {} m",
                                 config.min_x_m, config.max_x_m, config.max_half_width_m);
        return out;
    }
    RowCounts counts;
    std::vector<RowSample> rows = row_samples(grid, counts);
    if (rows.size() < config.min_rows) {
        out.status = fmt::format(
            "only {} rows have both boundaries of the kinds wanted ({}; {} of {} rows with face "
            "have a left one, {} a right one, {} both), expected >= {}",
            rows.size(), to_string(config.bounds), counts.left, counts.with_face, counts.right,
            counts.both, config.min_rows);
        return out;
    }
    const ParallelLines lines = fit_robust(rows, config);
    if (rows.size() < config.min_rows) {
        out.status = fmt::format(
            "only {} rows have boundaries within {} m of the fitted lines, expected >= {}",
            rows.size(), config.max_boundary_residual_m, config.min_rows);
        return out;
    }
    fill_corridor(rows, lines, out);
    return out;
}

const char* to_string(CorridorBounds b) {
    constexpr const char* kNames[] = {"any", "walls", "edges",
                                      "wall and edge"};  // in the enum's order
    return kNames[static_cast<int>(b)];
}

const char* to_string(CorridorBound b) {
    constexpr const char* kNames[] = {"none", "wall", "edge"};  // in the enum's order
    return kNames[static_cast<int>(b)];
}

}  // namespace scantling::perception
