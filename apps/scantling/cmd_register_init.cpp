// The --init file of `scantling register`: a 4×4 rigid transform as text.
#include <fmt/format.h>

#include <array>
#include <cmath>
#include <fstream>
#include <sstream>

#include <Eigen/SVD>

#include <scantling/core/error.hpp>

#include "scantling/commands.hpp"

namespace scantling::app {
namespace {

/// An --init rotation further than this from orthonormal (Frobenius norm of RᵀR − I) is a typo,
/// not rounding of printed digits; closer ones are projected onto SO(3).
constexpr double kMaxInitOrthonormalityError = 1e-3;

FileLocation at_line(int line) { return {.byte_offset = {}, .line = line, .column = {}}; }

std::array<double, 4> parse_row(const std::string& line, const std::string& path, int line_no) {
    std::istringstream in(line);
    std::array<double, 4> row{};
    for (double& v : row) {
        if (!(in >> v) || !std::isfinite(v)) {
            throw ParseError(path, at_line(line_no), "expected 4 finite numbers (a matrix row)");
        }
    }
    std::string rest;
    if (in >> rest) throw ParseError(path, at_line(line_no), "more than 4 numbers on the line");
    return row;
}

/// `row_lines`: the file line of each matrix row (comments and blank lines come between).
Eigen::Isometry3d rigid_from(Eigen::Matrix4d M, const std::string& path,
                             const std::array<int, 4>& row_lines) {
    if ((M.row(3) - Eigen::RowVector4d(0, 0, 0, 1)).norm() > 1e-9) {
        throw ParseError(path, at_line(row_lines[3]), "expected the last row 0 0 0 1");
    }
    const Eigen::Matrix3d R = M.topLeftCorner<3, 3>();
    const double error = (R.transpose() * R - Eigen::Matrix3d::Identity()).norm();
    if (!(error <= kMaxInitOrthonormalityError) || !(R.determinant() > 0.0)) {
        throw ParseError(path, at_line(row_lines[0]),
                         fmt::format("lines {}-{} do not hold a rotation (|RᵀR − I| = {:.3g}, "
                                     "det {:.3g}; expected orthonormal within {:g}, det 1)",
                                     row_lines[0], row_lines[2], error, R.determinant(),
                                     kMaxInitOrthonormalityError));
    }
    Eigen::JacobiSVD<Eigen::Matrix3d> svd(R, Eigen::ComputeFullU | Eigen::ComputeFullV);
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    T.linear() = svd.matrixU() * svd.matrixV().transpose();
    T.translation() = M.topRightCorner<3, 1>();
    return T;
}

}  // namespace

Eigen::Isometry3d read_transform_file(const std::string& path) {
    std::ifstream in(path);
    if (!in) throw FileError(path, "cannot open the --init file");
    Eigen::Matrix4d M;
    std::array<int, 4> row_lines{};
    int rows = 0, line_no = 0;
    for (std::string line; std::getline(in, line);) {
        ++line_no;
        const std::size_t first = line.find_first_not_of(" \t\r");
        if (first == std::string::npos || line[first] == '#') continue;
        if (rows == 4) throw ParseError(path, at_line(line_no), "more than 4 matrix rows");
        const auto row = parse_row(line, path, line_no);
        for (int c = 0; c < 4; ++c) M(rows, c) = row[c];
        row_lines[static_cast<std::size_t>(rows)] = line_no;
        ++rows;
    }
    if (rows < 4) {
        throw ParseError(path, at_line(line_no + 1),
                         fmt::format("{} matrix rows, expected 4 lines of 4 numbers", rows));
    }
    return rigid_from(M, path, row_lines);
}

}  // namespace scantling::app
