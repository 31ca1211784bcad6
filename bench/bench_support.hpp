#pragma once
/// @file Shared pieces of the scantling benchmarks: input loading and a console reporter that
/// ends with a table of ours / baseline time ratios.
///
/// Naming contract: a benchmark registered as "<case>/ours/<n>thr" is paired with
/// "<case>/<baseline>/<n>thr" (any other middle component) in the ratio table.

#include <map>
#include <optional>
#include <string>
#include <vector>

#include <benchmark/benchmark.h>

#include <scantling/core/point_cloud.hpp>

namespace scantling::bench {

/// Reads `data_dir/relative_path` with scantling::io::read_cloud; prints a skip message and
/// returns nullopt when the shared data is absent.
std::optional<PointCloud> load_shared_cloud(const std::string& data_dir,
                                            const std::string& relative_path);

/// Console output as usual, then "ratio = ours / baseline" per case and thread count. Uses the
/// median aggregate when repetitions are on, else the single run; real (wall-clock) time.
class RatioReporter : public benchmark::ConsoleReporter {
  public:
    RatioReporter() : ConsoleReporter(OO_Tabular) {}  // no colour codes: output goes to logs
    void ReportRuns(const std::vector<Run>& runs) override;
    void Finalize() override;

  private:
    std::map<std::string, double> ms_by_name_;
};

/// benchmark::Initialize, run every registered benchmark with a RatioReporter, Shutdown.
int run_all(int argc, char** argv);

}  // namespace scantling::bench
