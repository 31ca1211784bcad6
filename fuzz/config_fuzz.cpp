// libFuzzer target: the YAML config path of `scantling odometry --config` (parse_yaml_file,
// the config schema, validation) on arbitrary bytes.
#include <scantling/odometry/liodom.hpp>

#include "fuzz_support.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    using namespace scantling;
    const std::string path = fuzz::write_input_file({data, size}, "config.yaml");
    fuzz::expect_only_scantling_errors([&] {
        const odometry::LiodomConfig config = odometry::load_liodom_config(path);
        // A loaded config is a valid one: a ConfigError here would be a finding.
        try {
            config.validate();
        } catch (const Error& e) {
            fuzz::report_finding("load_liodom_config returned an invalid config", e.what());
        }
    });
    return 0;
}
