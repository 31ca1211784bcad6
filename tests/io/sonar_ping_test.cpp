// io::SonarPing::validate: a consistent ping passes, and each inconsistency is refused naming
// its field (sizes, non-finite or non-increasing axes, NaN intensities, range limits, fan).
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>
#include <utility>

#include <scantling/core/error.hpp>
#include <scantling/io/sonar_ping.hpp>

namespace scantling::io {
namespace {

/// 4 beams over a 1 rad fan, 8 bins of 0.5 m from 0.5 m, all silent but one echo.
SonarPing small_ping() {
    SonarPing ping;
    ping.num_beams = 4;
    ping.num_bins = 8;
    ping.min_range_m = 0.5;
    ping.max_range_m = 4.5;
    ping.horizontal_fov_rad = 1.0;
    for (int b = 0; b < 4; ++b) ping.bearings_rad.push_back(-0.375 + 0.25 * b);
    for (int j = 0; j < 8; ++j) ping.ranges_m.push_back(0.75 + 0.5 * j);
    ping.intensity.assign(32, 0.0F);
    ping.intensity[2 * 8 + 3] = 1.0F;
    return ping;
}

TEST(SonarPing, AConsistentPingPasses) {
    const SonarPing ping = small_ping();
    EXPECT_NO_THROW(ping.validate());
    EXPECT_EQ(ping.at(2, 3), 1.0F);
}

TEST(SonarPing, ValidateNamesTheInconsistentField) {
    const auto expect_bad = [](auto edit, const std::string& field) {
        SonarPing ping = small_ping();
        edit(ping);
        try {
            ping.validate("ping");
            ADD_FAILURE() << "no InputError naming " << field;
        } catch (const InputError& e) {
            EXPECT_NE(std::string(e.what()).find("ping." + field), std::string::npos) << e.what();
        }
    };
    expect_bad([](SonarPing& p) { p.num_beams = 0; }, "num_beams");
    expect_bad([](SonarPing& p) { p.num_bins = -1; }, "num_bins");
    expect_bad([](SonarPing& p) { p.intensity.push_back(0.0F); }, "intensity");
    expect_bad([](SonarPing& p) { p.bearings_rad.pop_back(); }, "bearings_rad");
    expect_bad([](SonarPing& p) { p.ranges_m.push_back(6.0); }, "ranges_m");
    expect_bad([](SonarPing& p) { std::swap(p.bearings_rad[0], p.bearings_rad[1]); },
               "bearings_rad[1]");
    expect_bad([](SonarPing& p) { p.bearings_rad[0] = std::nan(""); }, "bearings_rad[0]");
    expect_bad([](SonarPing& p) { p.ranges_m[5] = std::numeric_limits<double>::infinity(); },
               "ranges_m[5]");
    expect_bad([](SonarPing& p) { p.ranges_m[5] = p.ranges_m[4]; }, "ranges_m[5]");
    expect_bad([](SonarPing& p) { p.intensity[17] = std::nanf(""); }, "intensity[17] (beam 2");
    expect_bad([](SonarPing& p) { p.max_range_m = p.min_range_m; }, "max_range_m");
    expect_bad([](SonarPing& p) { p.min_range_m = -1.0; }, "min_range_m");
    expect_bad([](SonarPing& p) { p.horizontal_fov_rad = 0.0; }, "horizontal_fov_rad");
}

}  // namespace
}  // namespace scantling::io
