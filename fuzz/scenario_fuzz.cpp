// libFuzzer target: the scenario loader of `scantling sim` (YAML, scenario schema, validation)
// on arbitrary bytes. Worlds are not built: a mesh path would read files outside the input.
#include <scantling/sim/scenario.hpp>

#include "fuzz_support.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    using namespace scantling;
    const std::string text(fuzz::as_text({data, size}));
    fuzz::write_input_file({data, size}, "scenario.yaml");  // kept if the run hangs
    fuzz::expect_only_scantling_errors([&] {
        const sim::Scenario scenario = sim::parse_scenario(text, "fuzz.yaml");
        // A parsed scenario is a valid one: a ConfigError here would be a finding.
        try {
            scenario.validate();
        } catch (const Error& e) {
            fuzz::report_finding("parse_scenario returned an invalid scenario", e.what());
        }
    });
    return 0;
}
