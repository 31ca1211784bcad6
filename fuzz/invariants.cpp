#include "invariants.hpp"

#include <string>

#include "fuzz_support.hpp"

namespace scantling::fuzz {
namespace {

template <class Field>
void require_empty_or_size(const Field& field, std::size_t size, std::string_view reader,
                           const char* name) {
    if (field.empty() || field.size() == size) return;
    report_finding(std::string(reader) + " returned an inconsistent cloud",
                   std::string(name) + " has " + std::to_string(field.size()) + " values for " +
                       std::to_string(size) + " points");
}

}  // namespace

void require_consistent_cloud(const PointCloud& cloud, std::string_view reader) {
    const std::size_t n = cloud.size();
    require_empty_or_size(cloud.normals, n, reader, "normals");
    require_empty_or_size(cloud.covariances, n, reader, "covariances");
    require_empty_or_size(cloud.intensities, n, reader, "intensities");
    require_empty_or_size(cloud.rings, n, reader, "rings");
    require_empty_or_size(cloud.times_s, n, reader, "times_s");
    require_empty_or_size(cloud.colors, n, reader, "colors");
}

void require_faces_in_range(std::span<const Eigen::Vector3i> faces, std::size_t num_vertices,
                            std::string_view reader) {
    for (const Eigen::Vector3i& face : faces) {
        for (int k = 0; k < 3; ++k) {
            if (face[k] >= 0 && static_cast<std::size_t>(face[k]) < num_vertices) continue;
            report_finding(
                std::string(reader) + " returned a face index out of range",
                std::to_string(face[k]) + " for " + std::to_string(num_vertices) + " vertices");
        }
    }
}

void require_valid_pose(const Eigen::Isometry3d& T, double tolerance, std::string_view reader) {
    if (!T.matrix().allFinite()) {
        report_finding(std::string(reader) + " returned a non-finite pose", "");
    }
    const Eigen::Matrix3d R = T.linear();
    const double error = (R.transpose() * R - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff();
    if (error > tolerance || !(R.determinant() > 0.0)) {
        report_finding(std::string(reader) + " returned a rotation that is not proper",
                       "max |R^T R - I| = " + std::to_string(error) +
                           ", det = " + std::to_string(R.determinant()));
    }
}

}  // namespace scantling::fuzz
