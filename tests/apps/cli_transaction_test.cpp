// Outputs are transactions, end to end (issue 10, items 4 and 5): an interrupted, failing or
// disk-limited command leaves no partial output and no temporary; --force replaces only a
// complete recording over a folder that is a recording; an output that is an input is refused.
#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <fstream>
#include <map>
#include <thread>

#include <scantling/io/cloud_io.hpp>

#include "cli_fixture.hpp"

namespace scantling::cli_test {
namespace {

// Minutes of simulated time: still running when the test interrupts it after the first
// progress line, whatever the machine.
const char* const kLongScenario = R"(world: {type: cylinder}
vehicle:
  type: scripted
  trajectory: {type: helix, helix: {radius_m: 3.0, z0_m: 1.0}}
sensors:
  - {type: spinning_lidar, columns: 512, rate_hz: 10}
duration_s: 300
export: {world: false}
)";

// Safety nets only (a hung child must not hang the suite); nothing is asserted on time.
constexpr auto kGiveUpAfter = std::chrono::minutes(5);
constexpr auto kPollPeriod = std::chrono::milliseconds(20);

std::map<std::string, std::string> read_files(const fs::path& dir) {
    std::map<std::string, std::string> files;
    for (const auto& entry : fs::recursive_directory_iterator(dir)) {
        if (entry.is_regular_file()) files[fs::relative(entry.path(), dir)] = read_text(entry);
    }
    files.erase("timing.json");
    return files;
}

class CliTransaction : public Cli {
  protected:
    void SetUp() override {
        Cli::SetUp();
        std::ofstream(path("tiny.yaml")) << kTinyScenario;
        std::ofstream(path("long.yaml")) << kLongScenario;
    }

    CliRun sim(const std::string& scenario, const std::string& out, const std::string& extra = "") {
        return run("sim " + quoted(path(scenario)) + " --out " + quoted(out) + " --no-progress" +
                   extra);
    }

    /// Starts `scantling ARGS...` with SIGINT and SIGTERM at their defaults.
    pid_t spawn(const std::vector<std::string>& args) const {
        posix_spawn_file_actions_t files;
        posix_spawn_file_actions_init(&files);
        posix_spawn_file_actions_addopen(&files, STDOUT_FILENO, out_file().c_str(),
                                         O_WRONLY | O_CREAT | O_TRUNC, 0644);
        posix_spawn_file_actions_addopen(&files, STDERR_FILENO, err_file().c_str(),
                                         O_WRONLY | O_CREAT | O_TRUNC, 0644);
        posix_spawnattr_t attributes;
        posix_spawnattr_init(&attributes);
        sigset_t signals;
        sigemptyset(&signals);
        sigaddset(&signals, SIGINT);
        sigaddset(&signals, SIGTERM);
        posix_spawnattr_setsigdefault(&attributes, &signals);
        sigemptyset(&signals);
        posix_spawnattr_setsigmask(&attributes, &signals);
        posix_spawnattr_setflags(&attributes, POSIX_SPAWN_SETSIGDEF | POSIX_SPAWN_SETSIGMASK);
        std::vector<std::string> all = {SCANTLING_CLI};
        all.insert(all.end(), args.begin(), args.end());
        std::vector<char*> argv;
        for (std::string& arg : all) argv.push_back(arg.data());
        argv.push_back(nullptr);
        pid_t pid = -1;
        const int error =
            posix_spawn(&pid, SCANTLING_CLI, &files, &attributes, argv.data(), environ);
        posix_spawnattr_destroy(&attributes);
        posix_spawn_file_actions_destroy(&files);
        return error == 0 ? pid : -1;
    }

    /// Waits until the child's stderr holds `text` (true) or the child ended (false).
    bool wait_for_stderr(pid_t pid, const std::string& text) const {
        const auto give_up = std::chrono::steady_clock::now() + kGiveUpAfter;
        while (std::chrono::steady_clock::now() < give_up) {
            if (read_text(err_file()).find(text) != std::string::npos) return true;
            if (::waitpid(pid, nullptr, WNOHANG) == pid) return false;
            std::this_thread::sleep_for(kPollPeriod);
        }
        return false;
    }

    /// The child's wait status once it ended (killed and reported after kGiveUpAfter).
    int wait_for_exit(pid_t pid) const {
        const auto give_up = std::chrono::steady_clock::now() + kGiveUpAfter;
        int status = 0;
        while (::waitpid(pid, &status, WNOHANG) == 0) {
            if (std::chrono::steady_clock::now() > give_up) {
                ::kill(pid, SIGKILL);
                ::waitpid(pid, &status, 0);
                ADD_FAILURE() << "scantling did not stop after the signal";
                return status;
            }
            std::this_thread::sleep_for(kPollPeriod);
        }
        return status;
    }

    /// Runs the long scenario into `out`, sends `signal_number` once it simulates, and
    /// returns the exit status; checks that the recording was being staged beside `out`.
    int interrupt_long_run(const std::string& out, int signal_number, const std::string& extra) {
        std::vector<std::string> args = {"sim", path("long.yaml"), "--out", out};
        if (!extra.empty()) args.push_back(extra);
        const pid_t pid = spawn(args);
        if (pid < 0) {
            ADD_FAILURE() << "cannot start " << SCANTLING_CLI;
            return -1;
        }
        const bool simulating = wait_for_stderr(pid, "simulating:");
        EXPECT_TRUE(simulating) << read_text(err_file());
        EXPECT_TRUE(has_entry_starting_with(fs::path(out).filename().string() + ".partial-"));
        ::kill(pid, signal_number);
        return wait_for_exit(pid);
    }

    bool has_entry_starting_with(const std::string& prefix) const {
        for (const auto& entry : fs::directory_iterator(dir_)) {
            if (entry.path().filename().string().rfind(prefix, 0) == 0) return true;
        }
        return false;
    }

    /// Runs `script` with /bin/sh in the test folder, output captured like run().
    CliRun run_script(const std::string& script) const {
        std::ofstream(path("script.sh")) << script;
        return run_shell("sh " + quoted(path("script.sh")));
    }

    CliRun run_shell(const std::string& command) const {
        const int status = std::system(
            (command + " > " + quoted(out_file().string()) + " 2> " + quoted(err_file().string()))
                .c_str());
        CliRun result;
        result.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
        result.out = read_text(out_file());
        result.err = read_text(err_file());
        return result;
    }

    fs::path out_file() const { return dir_.parent_path() / "transaction_stdout.txt"; }
    fs::path err_file() const { return dir_.parent_path() / "transaction_stderr.txt"; }
};

TEST_F(CliTransaction, SigintStopsASimulationAndLeavesNoRecordingAndNoTemporary) {
    const int status = interrupt_long_run(path("rec"), SIGINT, "");
    ASSERT_TRUE(WIFEXITED(status)) << "ended by signal " << WTERMSIG(status);
    EXPECT_EQ(WEXITSTATUS(status), 130);
    const std::string err = read_text(err_file());
    EXPECT_NE(err.find("scantling: error: SIGINT: interrupted at simulated t = "),
              std::string::npos)
        << err;
    EXPECT_NE(err.find("nothing was written to " + path("rec")), std::string::npos) << err;
    expect_files({"long.yaml", "tiny.yaml"});
}

TEST_F(CliTransaction, SigtermDuringAForcedRunKeepsTheOldRecording) {
    ASSERT_EQ(sim("tiny.yaml", path("rec")).exit_code, 0);
    const auto old_files = read_files(path("rec"));
    const int status = interrupt_long_run(path("rec"), SIGTERM, "--force");
    ASSERT_TRUE(WIFEXITED(status)) << "ended by signal " << WTERMSIG(status);
    EXPECT_EQ(WEXITSTATUS(status), 143);
    expect_files({"long.yaml", "rec", "tiny.yaml"});
    EXPECT_TRUE(read_files(path("rec")) == old_files) << "the old recording was changed";
}

TEST_F(CliTransaction, ForceReplacesARecordingWithTheCompleteNewOne) {
    ASSERT_EQ(sim("tiny.yaml", path("rec"), " --seed 1").exit_code, 0);
    const CliRun r = sim("tiny.yaml", path("rec"), " --seed 2 --force");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    expect_files({"long.yaml", "rec", "tiny.yaml"});  // no temporary and no old copy left
    EXPECT_NE(read_text(path("rec/summary.json")).find("\"seed\": 2"), std::string::npos);
}

TEST_F(CliTransaction, ForceRefusesAFolderWithForeignFilesAndKeepsThem) {
    ASSERT_EQ(sim("tiny.yaml", path("rec")).exit_code, 0);
    const std::string summary = read_text(path("rec/summary.json"));
    std::ofstream(path("rec/notes.txt")) << "mine";
    expect_one_error_line(sim("tiny.yaml", path("rec"), " --seed 2 --force"), "notes.txt");
    EXPECT_EQ(read_text(path("rec/notes.txt")), "mine");
    EXPECT_EQ(read_text(path("rec/summary.json")), summary);
    fs::remove(path("rec/notes.txt"));
    std::ofstream(path("rec/lidar/mine.bin")) << "mine";
    expect_one_error_line(sim("tiny.yaml", path("rec"), " --force"), "lidar/mine.bin");
    EXPECT_TRUE(fs::exists(path("rec/lidar/mine.bin")));
    expect_files({"long.yaml", "rec", "tiny.yaml"});
}

TEST_F(CliTransaction, SimRefusesAnOutputFolderHoldingItsScenario) {
    fs::create_directory(path("rec"));
    std::ofstream(path("rec/s.yaml")) << kTinyScenario;
    expect_one_error_line(run("sim " + quoted(path("rec/s.yaml")) + " --out " +
                              quoted(path("rec/.")) + " --force --no-progress"),
                          "s.yaml");
    EXPECT_EQ(fs::directory_iterator(path("rec"))->path().filename(), "s.yaml");
    EXPECT_EQ(std::distance(fs::directory_iterator(path("rec")), fs::directory_iterator()), 1);
}

// A file-size limit stands in for a full disk (a test cannot fill one): the write fails in
// the middle, and the error must carry the OS reason and leave nothing behind.
TEST_F(CliTransaction, AFailedWriteLeavesNoPartialRecordingAndNamesTheReason) {
    const CliRun r = run_script("trap '' XFSZ\nulimit -f 16\nexec " + quoted(SCANTLING_CLI) +
                                " sim " + quoted(path("tiny.yaml")) + " --out " +
                                quoted(path("rec")) + " --no-progress\n");
    expect_one_error_line(r, "File too large");
    expect_files({"long.yaml", "script.sh", "tiny.yaml"});
}

TEST_F(CliTransaction, AFailedCloudWriteNamesTheReason) {
    PointCloud big;
    for (int i = 0; i < 20000; ++i) big.points.emplace_back(0.001f * i, 1.0f, 2.0f);
    io::write_cloud(path("in.pcd"), big);
    const CliRun r =
        run_script("trap '' XFSZ\nulimit -f 16\nexec " + quoted(SCANTLING_CLI) + " convert " +
                   quoted(path("in.pcd")) + " " + quoted(path("out.ply")) + "\n");
    expect_one_error_line(r, path("out.ply") + ": write failed: File too large");
    expect_files({"in.pcd", "long.yaml", "script.sh", "tiny.yaml"});
}

TEST_F(CliTransaction, RelativeOutputPathsWork) {
    io::write_cloud(path("a.pcd"), make_grid());
    const std::string cd = "cd " + quoted(dir_.string()) + " && " + quoted(SCANTLING_CLI);
    const CliRun r =
        run_shell(cd + " sim tiny.yaml --out rec --no-progress && " + quoted(SCANTLING_CLI) +
                  " sim tiny.yaml --out rec/ --force " + "--no-progress && " +
                  quoted(SCANTLING_CLI) + " convert a.pcd b.ply");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    expect_files({"a.pcd", "b.ply", "long.yaml", "rec", "tiny.yaml"});
    EXPECT_TRUE(fs::exists(path("rec/summary.json")));
    expect_one_error_line(run_shell(cd + " convert a.pcd ./a.pcd"), "a.pcd");
}

TEST_F(CliTransaction, ConvertRefusesToWriteOverItsInput) {
    io::write_cloud(path("a.pcd"), make_grid());
    const std::string before = read_text(path("a.pcd"));
    expect_one_error_line(run("convert " + quoted(path("a.pcd")) + " " +
                              quoted(dir_.string() + "/./a.pcd") + " --ascii"),
                          "a.pcd");
    fs::create_symlink(path("a.pcd"), path("link.pcd"));
    expect_one_error_line(
        run("convert " + quoted(path("a.pcd")) + " " + quoted(path("link.pcd")) + " --ascii"),
        "link.pcd");
    EXPECT_EQ(read_text(path("a.pcd")), before);
}

TEST_F(CliTransaction, ConvertWritesAFileWhoseNameIsNearNameMax) {
    io::write_cloud(path("a.pcd"), make_grid());
    const std::string name = std::string(246, 'n') + ".ply";
    const CliRun r = run("convert " + quoted(path("a.pcd")) + " " + quoted(path(name)));
    ASSERT_EQ(r.exit_code, 0) << r.err;
    expect_files({"a.pcd", "long.yaml", name, "tiny.yaml"});
}

TEST_F(CliTransaction, OdometryRefusesAnOutputInsideItsInputRecording) {
    ASSERT_EQ(sim("tiny.yaml", path("rec")).exit_code, 0);
    const auto files = read_files(path("rec"));
    expect_one_error_line(run("odometry " + quoted(path("rec")) + " --out " +
                              quoted(path("rec/lidar/traj.txt")) + " --no-progress"),
                          "rec");
    EXPECT_TRUE(read_files(path("rec")) == files);
}

TEST_F(CliTransaction, OdometryWritesAllItsFilesOrNone) {
    ASSERT_EQ(sim("tiny.yaml", path("rec")).exit_code, 0);
    fs::create_directory(path("traj_frames.csv"));  // the second of its three files
    expect_one_error_line(run("odometry " + quoted(path("rec")) + " --out " +
                              quoted(path("traj.txt")) + " --no-progress"),
                          "traj_frames.csv");
    expect_files({"long.yaml", "rec", "tiny.yaml", "traj_frames.csv"});
}

TEST_F(CliTransaction, EvalRefusesAPlotThatWouldOverwriteTheGroundTruth) {
    std::string poses;
    for (int i = 0; i < 20; ++i) poses += "1 0 0 " + std::to_string(i) + " 0 1 0 0 0 0 1 0\n";
    std::ofstream(path("est_top.svg")) << poses;  // where the top-view plot of est.txt goes
    std::ofstream(path("est.txt")) << poses;
    expect_one_error_line(
        run("eval --gt " + quoted(path("est_top.svg")) + " --est " + quoted(path("est.txt"))),
        "est_top.svg");
    EXPECT_EQ(read_text(path("est_top.svg")), poses);
    expect_files({"est.txt", "est_top.svg", "long.yaml", "tiny.yaml"});
}

}  // namespace
}  // namespace scantling::cli_test
