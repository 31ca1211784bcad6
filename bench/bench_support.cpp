#include "bench_support.hpp"

#include <cstdio>
#include <filesystem>

#include <scantling/io/cloud_io.hpp>

namespace scantling::bench {
namespace {

double to_ms(double value, benchmark::TimeUnit unit) {
    switch (unit) {
        case benchmark::kNanosecond:
            return value * 1e-6;
        case benchmark::kMicrosecond:
            return value * 1e-3;
        case benchmark::kMillisecond:
            return value;
        case benchmark::kSecond:
            return value * 1e3;
    }
    return value;
}

/// "<case>/ours/<n>thr" -> {"<case>", "<n>thr"}; nullopt for other names.
std::optional<std::pair<std::string, std::string>> split_ours(const std::string& name) {
    const auto mid = name.find("/ours/");
    if (mid == std::string::npos) return std::nullopt;
    return std::pair(name.substr(0, mid), name.substr(mid + 6));
}

}  // namespace

std::optional<PointCloud> load_shared_cloud(const std::string& data_dir,
                                            const std::string& relative_path) {
    const std::filesystem::path path = std::filesystem::path(data_dir) / relative_path;
    if (!std::filesystem::exists(path)) {
        std::printf("SKIP: benchmark input %s is absent (shared data not checked out)\n",
                    path.c_str());
        return std::nullopt;
    }
    return io::read_cloud(path.string());
}

void RatioReporter::ReportRuns(const std::vector<Run>& runs) {
    ConsoleReporter::ReportRuns(runs);
    for (const Run& run : runs) {
        if (run.error_occurred) continue;
        const bool single = run.run_type == Run::RT_Iteration && run.repetitions <= 1;
        const bool median = run.run_type == Run::RT_Aggregate && run.aggregate_name == "median";
        if (single || median) {
            ms_by_name_[run.run_name.function_name] =
                to_ms(run.GetAdjustedRealTime(), run.time_unit);
        }
    }
}

void RatioReporter::Finalize() {
    std::printf("\n%-44s %10s %12s %10s %8s\n", "case / threads", "ours ms", "baseline", "base ms",
                "ratio");
    for (const auto& [name, ours_ms] : ms_by_name_) {
        const auto parts = split_ours(name);
        if (!parts) continue;
        for (const auto& [other, base_ms] : ms_by_name_) {
            const auto first = other.find('/');
            const auto last = other.rfind('/');
            if (other == name || other.substr(0, first) != parts->first ||
                other.substr(last + 1) != parts->second) {
                continue;
            }
            const std::string baseline = other.substr(first + 1, last - first - 1);
            std::printf("%-44s %10.2f %12s %10.2f %8.2f\n",
                        (parts->first + " / " + parts->second).c_str(), ours_ms, baseline.c_str(),
                        base_ms, ours_ms / base_ms);
        }
    }
    std::printf("ratio = ours / baseline wall-clock time: below 1 means scantling is faster\n");
    ConsoleReporter::Finalize();
}

int run_all(int argc, char** argv) {
    benchmark::Initialize(&argc, argv);
    if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
    RatioReporter reporter;
    benchmark::RunSpecifiedBenchmarks(&reporter);
    benchmark::Shutdown();
    return 0;
}

}  // namespace scantling::bench
