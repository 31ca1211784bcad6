#pragma once
/// @file
/// One ping of a forward-looking multibeam imaging sonar as the robot receives it (SPEC §1 ROV
/// sonar, §5 hull-relative adaptation): a polar image of beams × range bins. The simulator
/// (sim::to_sonar_ping) and a driver adapter both produce it; perception reads only this.
///
/// Sensor frame: x is the boresight, y left, z up; a beam's bearing is positive to the left.

#include <cstddef>
#include <string_view>
#include <vector>

namespace scantling::io {

struct SonarPing {
    double stamp_s = 0.0;              ///< time of the ping
    int num_beams = 0;                 ///< across the horizontal fan, >= 1
    int num_bins = 0;                  ///< along range, >= 1
    std::vector<float> intensity;      ///< echo amplitude, beam-major: beam · num_bins + bin
    std::vector<double> bearings_rad;  ///< per beam, sensor frame, positive left, increasing
    std::vector<double> ranges_m;      ///< per bin, bin centre, increasing
    double min_range_m = 0.0;          ///< near edge of bin 0
    double max_range_m = 0.0;          ///< far edge of the last bin
    double horizontal_fov_rad = 0.0;   ///< width of the fan

    float at(int beam, int bin) const {
        return intensity[static_cast<std::size_t>(beam) * num_bins + bin];
    }

    /// Throws InputError naming "<prefix>.<field>" when the sizes disagree (num_beams, num_bins,
    /// intensity, bearings_rad, ranges_m), a bearing or range is non-finite or not strictly
    /// increasing, the range window or field of view is not a positive finite interval, or an
    /// intensity is NaN. O(num_beams · num_bins).
    void validate(std::string_view prefix = "sonar_ping") const;
};

}  // namespace scantling::io
