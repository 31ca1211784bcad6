// libFuzzer target: the recording reader (open_recording and its lazily read frames) and the
// sweep source that the odometry opens (a recording, a KITTI sequence or a folder of clouds).
// The input is a folder packed as an archive (recording_archive.hpp).
#include <algorithm>
#include <cstddef>

#include <scantling/io/recording.hpp>
#include <scantling/io/sweep_source.hpp>

#include "fuzz_support.hpp"
#include "invariants.hpp"
#include "recording_archive.hpp"

namespace {

using namespace scantling;

/// Frames read per stream: enough to reach a second file, bounded so a run stays fast.
constexpr std::size_t kFramesPerStream = 3;

/// Calls read(i) for the first frames of a stream, each on its own (an error in one frame
/// must not hide a crash in the next).
template <class Read>
void read_frames(std::size_t count, Read read) {
    for (std::size_t i = 0; i < std::min(count, kFramesPerStream); ++i) {
        fuzz::expect_only_scantling_errors([&] { read(i); });
    }
}

void read_everything(const io::Recording& recording) {
    read_frames(recording.num_sweeps(), [&](std::size_t i) {
        fuzz::require_consistent_cloud(recording.read_sweep(i), "Recording::read_sweep");
        static_cast<void>(recording.sweep_pose_gt(i));
    });
    read_frames(recording.num_depth_frames(), [&](std::size_t i) {
        fuzz::require_consistent_cloud(recording.read_depth_frame(i), "read_depth_frame");
    });
    read_frames(recording.rosette_frames().size(), [&](std::size_t i) {
        fuzz::require_consistent_cloud(recording.read_rosette_frame(i), "read_rosette_frame");
    });
    read_frames(recording.stereo_frames().size(), [&](std::size_t i) {
        fuzz::require_consistent_cloud(recording.read_stereo_frame(i), "read_stereo_frame");
    });
    read_frames(recording.sonar_pings().size(),
                [&](std::size_t i) { static_cast<void>(recording.read_sonar_intensity(i)); });
    read_frames(recording.num_images(),
                [&](std::size_t i) { static_cast<void>(recording.image_path(i)); });
}

void read_sweep_source(const io::SweepSource& source) {
    static_cast<void>(source.ground_truth());
    read_frames(source.size(), [&](std::size_t i) {
        static_cast<void>(source.stamp_s(i));
        static_cast<void>(source.file_of(i));
        fuzz::require_consistent_cloud(source.read(i), "SweepSource::read");
    });
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    fuzz::write_input_file({data, size}, "input.rec");  // kept if the run hangs
    const std::string directory = fuzz::fresh_directory("recording");
    fuzz::write_archive(fuzz::split_archive(fuzz::as_text({data, size})), directory);
    fuzz::expect_only_scantling_errors([&] { read_everything(io::open_recording(directory)); });
    fuzz::expect_only_scantling_errors(
        [&] { read_sweep_source(*io::open_sweep_source(directory)); });
    return 0;
}
