// libFuzzer target: read_tum on arbitrary bytes (TUM trajectories).
#include <cmath>
#include <string>
#include <vector>

#include <scantling/io/tum.hpp>

#include "fuzz_support.hpp"
#include "invariants.hpp"

namespace {
// Quaternions are normalised on read, so the rotation is orthonormal to rounding.
constexpr double kRotationTolerance = 1e-9;
}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    using namespace scantling;
    const std::string path = fuzz::write_input_file({data, size}, "input.tum");
    fuzz::expect_only_scantling_errors([&] {
        const std::vector<io::StampedPose> poses = io::read_tum(path);
        for (std::size_t i = 0; i < poses.size(); ++i) {
            fuzz::require_valid_pose(poses[i].T_world_body, kRotationTolerance, "read_tum");
            // tum.hpp: stamps finite and strictly increasing.
            const bool increasing = i == 0 || poses[i].stamp_s > poses[i - 1].stamp_s;
            if (!std::isfinite(poses[i].stamp_s) || !increasing) {
                fuzz::report_finding("read_tum returned a bad stamp", "pose " + std::to_string(i));
            }
        }
    });
    return 0;
}
