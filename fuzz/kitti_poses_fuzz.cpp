// libFuzzer target: read_kitti_poses on arbitrary bytes (KITTI 3x4 pose lists).
#include <scantling/io/kitti.hpp>

#include "fuzz_support.hpp"
#include "invariants.hpp"

namespace {
constexpr double kRotationTolerance = 1e-3;  // the reader's documented orthonormality bound
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    using namespace scantling;
    const std::string path = fuzz::write_input_file({data, size}, "poses.txt");
    fuzz::expect_only_scantling_errors([&] {
        for (const Eigen::Isometry3d& T : io::read_kitti_poses(path)) {
            fuzz::require_valid_pose(T, kRotationTolerance, "read_kitti_poses");
        }
    });
    return 0;
}
