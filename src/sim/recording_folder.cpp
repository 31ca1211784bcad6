// What a recording folder may hold, so that `--force` deletes nothing else
// (recording_writer.hpp, check_replaceable_recording).
#include <scantling/sim/recording_writer.hpp>

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <optional>
#include <string_view>
#include <system_error>

#include <scantling/core/error.hpp>
#include <scantling/io/mission_log.hpp>
#include <scantling/io/recording.hpp>

namespace scantling::sim {
namespace {

namespace fs = std::filesystem;
namespace layout = io::recording_layout;

constexpr std::size_t kFrameStemDigits = 6;  // layout::frame_stem, more digits past 999999

const char* const kTopFiles[] = {layout::kGroundTruth,   layout::kImu,      layout::kVio,
                                 layout::kSummary,       layout::kTiming,   layout::kRange,
                                 layout::kUwb,           layout::kPressure, layout::kDvl,
                                 layout::kWheelOdometry, layout::kBarometer};
const char* const kFrameFolders[] = {layout::kLidarDir, layout::kDepthDir,   layout::kImagesDir,
                                     layout::kSonarDir, layout::kRosetteDir, layout::kStereoDir};
// Files of the frame folders besides the frames (each folder has a subset).
const char* const kFrameFolderFiles[] = {
    layout::kTimes,     layout::kPoses,           layout::kExtrinsic,       layout::kVisibleDefects,
    layout::kSonarMeta, layout::kDefectSightings, layout::kCameraIntrinsics};
// write_world, and the descriptor cache `scantling localize` adds beside the map.
// What a closed-loop run adds (io/mission_log.hpp).
const char* const kMissionFiles[] = {layout::kMissionEstimates, layout::kMissionEstimatesTum,
                                     layout::kMissionCommands,  layout::kMissionEvents,
                                     layout::kMissionPath,      layout::kMissionSummary,
                                     layout::kMissionSonarMap,  layout::kMissionExplorationCurve,
                                     layout::kMissionPlans,     layout::kMissionOccupancyMap};
const char* const kTextureFiles[] = {"live.png", "clean.png", "metadata.json"};
const char* const kWorldFiles[] = {"map.ply", "mesh.ply", "metadata.json",
                                   layout::kWorldMapDescriptorCache};

template <std::size_t N>
bool is_one_of(std::string_view name, const char* const (&names)[N]) {
    return std::any_of(std::begin(names), std::end(names),
                       [&](const char* candidate) { return name == candidate; });
}

/// "000042.bin", ".ply" or ".png": a frame the writer numbers with layout::frame_stem.
bool is_frame_file(const fs::path& file) {
    const std::string stem = file.stem().string();
    const std::string extension = file.extension().string();
    const bool digits =
        stem.size() >= kFrameStemDigits &&
        std::all_of(stem.begin(), stem.end(), [](unsigned char c) { return std::isdigit(c) != 0; });
    return digits && (extension == ".bin" || extension == ".ply" || extension == ".png");
}

bool is_regular(const fs::directory_entry& entry) {
    std::error_code ec;
    return entry.symlink_status(ec).type() == fs::file_type::regular;
}

bool is_real_folder(const fs::directory_entry& entry) {
    std::error_code ec;
    return entry.symlink_status(ec).type() == fs::file_type::directory;
}

/// The first entry of mission/texture/ that the crawler's texture map does not write.
std::optional<std::string> foreign_in_texture(const fs::path& folder) {
    for (const fs::directory_entry& entry : fs::directory_iterator(folder)) {
        const std::string file = entry.path().filename().string();
        if (!is_one_of(file, kTextureFiles) || !is_regular(entry)) {
            return std::string(layout::kMissionDir) + "/" + layout::kMissionTextureDir + "/" + file;
        }
    }
    return std::nullopt;
}

/// The first entry of the sub-folder `name` that the writer does not write there.
std::optional<std::string> foreign_in_folder(const fs::path& folder, const std::string& name) {
    for (const fs::directory_entry& entry : fs::directory_iterator(folder)) {
        const std::string file = entry.path().filename().string();
        if (name == layout::kMissionDir && file == layout::kMissionTextureDir &&
            is_real_folder(entry)) {
            if (auto foreign = foreign_in_texture(entry.path())) return foreign;
            continue;
        }
        bool known = is_frame_file(entry.path()) || is_one_of(file, kFrameFolderFiles);
        if (name == layout::kWorldDir) known = is_one_of(file, kWorldFiles);
        if (name == layout::kMissionDir) known = is_one_of(file, kMissionFiles);
        if (!known || !is_regular(entry)) return name + "/" + file;
    }
    return std::nullopt;
}

std::optional<std::string> foreign_entry(const fs::path& directory) {
    for (const fs::directory_entry& entry : fs::directory_iterator(directory)) {
        const std::string name = entry.path().filename().string();
        if (is_one_of(name, kTopFiles) && is_regular(entry)) continue;
        const bool folder = is_one_of(name, kFrameFolders) || name == layout::kWorldDir ||
                            name == layout::kMissionDir;
        if (!folder || !is_real_folder(entry)) return name;
        if (auto foreign = foreign_in_folder(entry.path(), name)) return foreign;
    }
    return std::nullopt;
}

}  // namespace

void check_replaceable_recording(const std::string& directory) {
    std::optional<std::string> foreign;
    try {
        foreign = foreign_entry(directory);
    } catch (const fs::filesystem_error& e) {
        throw FileError(directory, std::string("cannot list the folder: ") + e.code().message());
    }
    if (foreign) {
        throw FileError(directory, "holds '" + *foreign +
                                       "', which is not part of a recording: --force replaces "
                                       "only a recording; move it away or choose another --out");
    }
}

}  // namespace scantling::sim
