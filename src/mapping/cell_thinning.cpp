#include <scantling/core/voxel_grid.hpp>
#include <scantling/mapping/cell_thinning.hpp>

#include <utility>

namespace scantling::mapping {

double thin_cell(std::vector<Eigen::Vector3f>& offsets, const Eigen::Vector3d& cell_size_m,
                 double voxel_m, std::size_t budget) {
    // Corner-relative coordinates: core's grid is anchored at the origin, so it becomes
    // anchored at the cell's corner. Clamped into [0, size] (float offsets of points on a face
    // can overshoot by an ulp) so that once the voxel exceeds the cell every point falls into
    // voxel 0, which ends the doubling.
    const Eigen::Vector3d half_m = 0.5 * cell_size_m;
    PointCloud local;
    local.points.reserve(offsets.size());
    for (const Eigen::Vector3f& o : offsets) {
        local.points.push_back((o.cast<double>() + half_m).cwiseMax(0.0).cwiseMin(cell_size_m));
    }
    VoxelGridConfig config;
    config.voxel_size_m = voxel_m;
    config.parallel.num_threads = 1;  // a cell is far below a useful parallel grain
    PointCloud thinned = voxel_downsample(local, config);
    while (thinned.size() > budget) {
        config.voxel_size_m *= 2.0;
        thinned = voxel_downsample(local, config);
    }
    // A new buffer rather than clear(): the old one's capacity is the pre-thinning size.
    std::vector<Eigen::Vector3f> out;
    out.reserve(thinned.size());
    for (const Eigen::Vector3d& p : thinned.points) out.push_back((p - half_m).cast<float>());
    offsets = std::move(out);
    return config.voxel_size_m;
}

}  // namespace scantling::mapping
