#pragma once
// The times.txt of a frame stream with the line of each stamp, shared by the stamps reader
// (recording_csv.cpp) and the frame-file check of open_recording (recording.cpp).

#include <string>
#include <vector>

namespace scantling::io::detail {

struct StampFile {
    std::vector<double> stamps_s;  ///< finite, strictly increasing
    std::vector<int> lines;        ///< 1-based line of each stamp (blank lines are skipped)
};

/// One number per non-blank line. Throws FileError when unreadable, ParseError naming the line
/// for a token that is not a finite number or a stamp that is not after the previous one.
StampFile read_stamp_file(const std::string& path);

}  // namespace scantling::io::detail
