// libFuzzer target: the YAML config paths of `scantling odometry --config` and `scantling
// localize --config` (parse_yaml_file, the config schemas, validation) on arbitrary bytes.
#include <scantling/localization/localizer_config.hpp>
#include <scantling/odometry/liodom.hpp>

#include "fuzz_support.hpp"

namespace {

/// Loads `path` with `load`; a loaded config is a valid one: a ConfigError from its own
/// validate() would be a finding.
template <class Load>
void check_loaded(const std::string& path, Load&& load, std::string_view name) {
    using namespace scantling;
    fuzz::expect_only_scantling_errors([&] {
        const auto config = load(path);
        try {
            config.validate();
        } catch (const Error& e) {
            fuzz::report_finding(std::string(name) + " returned an invalid config", e.what());
        }
    });
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    using namespace scantling;
    const std::string path = fuzz::write_input_file({data, size}, "config.yaml");
    check_loaded(path, odometry::load_liodom_config, "load_liodom_config");
    check_loaded(path, localization::load_localizer_config, "load_localizer_config");
    return 0;
}
