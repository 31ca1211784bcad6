// libFuzzer target: read_structural_map on arbitrary bytes (world/metadata.json), and the
// queries the localiser runs on what it returns.
#include <cmath>
#include <string>

#include <scantling/io/structural_map.hpp>

#include "fuzz_support.hpp"

namespace {

/// structural_map.hpp: ids are positions, compartment boxes are finite with min <= max, and
/// every reference names an existing compartment.
void check(const scantling::io::StructuralMap& map) {
    using scantling::fuzz::report_finding;
    const int n = static_cast<int>(map.compartments.size());
    for (int i = 0; i < n; ++i) {
        const auto& c = map.compartments[static_cast<std::size_t>(i)];
        if (c.id != i) report_finding("compartment id is not its position", std::to_string(i));
        if (!c.bounds.min.allFinite() || !c.bounds.max.allFinite() || c.bounds.empty()) {
            report_finding("compartment with a bad box", std::to_string(i));
        }
    }
    for (const auto& l : map.landmarks) {
        if (l.compartment < 0 || l.compartment >= n) {
            report_finding("landmark in a missing compartment", std::to_string(l.id));
        }
    }
    for (const auto& c : map.compartments) {
        const Eigen::Vector3d centre = 0.5 * (c.bounds.min + c.bounds.max);
        const auto at = scantling::io::compartment_at(map, centre);
        if (!at || *at < 0 || *at >= n)
            report_finding("compartment_at missed a box centre", c.name);
        (void)scantling::io::nearest_frame(map, centre);
        (void)scantling::io::nearest_longitudinal(map, centre);
    }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    using namespace scantling;
    const std::string path = fuzz::write_input_file({data, size}, "metadata.json");
    fuzz::expect_only_scantling_errors([&] { check(io::read_structural_map(path)); });
    return 0;
}
