// Outputs as transactions (issue 10, items 4 and 5): all of a command's files or none, temporary
// names that fit NAME_MAX, outputs refused when they are inputs, and a full disk reported with
// the OS reason.
#include <gtest/gtest.h>

#include <sys/resource.h>
#include <unistd.h>

#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <stdexcept>
#include <string>

#include <scantling/core/error.hpp>
#include <scantling/io/atomic_file.hpp>
#include <scantling/io/checked_output_file.hpp>
#include <scantling/io/cloud_io.hpp>
#include <scantling/io/file_path.hpp>
#include <scantling/io/output_transaction.hpp>

#include "test_files.hpp"

namespace scantling::io {
namespace {

namespace fs = std::filesystem;
using test::read_bytes;
using test::TempDir;
using test::write_bytes;

constexpr std::size_t kMiB = 1024 * 1024;

void write_text(OutputTransaction& outputs, const std::string& path, const std::string& text) {
    outputs.write_stream(path, [&](std::ostream& out) { out << text; });
}

TEST(OutputTransaction, FailureOnTheSecondOfThreeFilesLeavesNoneAndKeepsTheOldOnes) {
    TempDir dir;
    write_bytes(dir.file("a.txt"), "old a");
    {
        OutputTransaction outputs;
        write_text(outputs, dir.file("a.txt"), "new a");
        EXPECT_THROW(outputs.write_stream(dir.file("b.txt"),
                                          [](std::ostream& out) {
                                              out << "half of b";
                                              throw std::runtime_error("b failed");
                                          }),
                     std::runtime_error);
        // The command never gets to the third file nor to commit().
    }
    EXPECT_EQ(dir.list(), std::vector<std::string>{"a.txt"});
    EXPECT_EQ(read_bytes(dir.file("a.txt")), "old a");
}

TEST(OutputTransaction, NothingIsInPlaceBeforeCommitAndEverythingAfter) {
    TempDir dir;
    write_bytes(dir.file("a.txt"), "old a");
    OutputTransaction outputs;
    write_text(outputs, dir.file("a.txt"), "new a");
    write_text(outputs, dir.file("b.txt"), "new b");
    outputs.write(dir.file("c.pcd"), [](const std::string& staged) {
        // Writers that pick the format from the extension see the destination's.
        EXPECT_EQ(lower_extension(staged), ".pcd");
        write_cloud(staged, test::make_full_cloud(3));
    });
    EXPECT_EQ(read_bytes(dir.file("a.txt")), "old a");
    EXPECT_FALSE(fs::exists(dir.file("b.txt")));
    outputs.commit();
    EXPECT_EQ(dir.list(), (std::vector<std::string>{"a.txt", "b.txt", "c.pcd"}));
    EXPECT_EQ(read_bytes(dir.file("a.txt")), "new a");
    EXPECT_EQ(read_bytes(dir.file("b.txt")), "new b");
    EXPECT_EQ(read_cloud(dir.file("c.pcd")).size(), 3u);
    EXPECT_THROW(outputs.commit(), Error);
}

TEST(OutputTransaction, AMoveFailingAtCommitRollsBackTheEarlierOnes) {
    TempDir dir;
    write_bytes(dir.file("a.txt"), "old a");
    OutputTransaction outputs;
    write_text(outputs, dir.file("a.txt"), "new a");
    write_text(outputs, dir.file("b.txt"), "new b");
    fs::create_directory(dir.file("b.txt"));  // appears between the writing and the commit
    test::expect_file_error([&] { outputs.commit(); }, dir.file("b.txt"));
    EXPECT_EQ(dir.list(), (std::vector<std::string>{"a.txt", "b.txt"}));
    EXPECT_EQ(read_bytes(dir.file("a.txt")), "old a");
    EXPECT_TRUE(fs::is_empty(dir.file("b.txt")));
}

TEST(OutputTransaction, RefusesBadDestinationsBeforeAnythingIsWritten) {
    TempDir dir;
    OutputTransaction outputs;
    write_text(outputs, dir.file("a.txt"), "a");
    test::expect_file_error([&] { outputs.stage_file(dir.file("a.txt")); }, dir.file("a.txt"));
    const std::string same = (dir.path() / "." / "a.txt").string();
    test::expect_file_error([&] { outputs.stage_file(same); }, same);
    test::expect_file_error([&] { outputs.stage_file(dir.file("none/b.txt")); },
                            dir.file("none/b.txt"));
    fs::create_directory(dir.file("folder"));
    test::expect_file_error([&] { outputs.stage_file(dir.file("folder")); }, dir.file("folder"));
    EXPECT_EQ(outputs.size(), 1u);
}

TEST(OutputTransaction, AStagedFolderIsRenamedIntoPlaceOrRemoved) {
    TempDir dir;
    const std::string rec = dir.file("rec");
    {
        OutputTransaction outputs;
        const std::string staged = outputs.stage_folder(rec);
        EXPECT_EQ(fs::path(staged).parent_path(), dir.path());
        write_bytes(staged + "/x.txt", "partial");
    }
    EXPECT_TRUE(dir.list().empty());
    OutputTransaction outputs;
    write_bytes(outputs.stage_folder(rec + "/") + "/x.txt", "complete");
    outputs.commit();
    EXPECT_EQ(dir.list(), std::vector<std::string>{"rec"});
    EXPECT_EQ(read_bytes(rec + "/x.txt"), "complete");
}

TEST(OutputTransaction, AFolderIsReplacedOnlyWhenTheCheckAcceptsIt) {
    TempDir dir;
    const std::string rec = dir.file("rec");
    fs::create_directory(rec);
    write_bytes(rec + "/old.txt", "old");
    OutputTransaction refused;
    test::expect_file_error([&] { refused.stage_folder(rec); }, rec);
    const auto refuse = [](const std::string& folder) { throw FileError(folder, "not mine"); };
    EXPECT_THROW(refused.stage_folder(rec, refuse), FileError);
    EXPECT_EQ(dir.list(), std::vector<std::string>{"rec"});

    int checks = 0;
    OutputTransaction accepted;
    const std::string staged = accepted.stage_folder(rec, [&](const std::string&) { ++checks; });
    write_bytes(staged + "/new.txt", "new");
    EXPECT_TRUE(fs::exists(rec + "/old.txt"));  // replaced only once the new one is complete
    accepted.commit();
    EXPECT_EQ(checks, 2);  // when staged and again at commit
    EXPECT_EQ(dir.list(), std::vector<std::string>{"rec"});
    EXPECT_FALSE(fs::exists(rec + "/old.txt"));
    EXPECT_EQ(read_bytes(rec + "/new.txt"), "new");
}

TEST(OutputTransaction, FoldersItCreatedAreRemovedUnlessItCommits) {
    TempDir dir;
    {
        OutputTransaction outputs;
        outputs.create_folder(dir.file("a/b/c"));
        EXPECT_TRUE(fs::is_directory(dir.file("a/b/c")));
    }
    EXPECT_TRUE(dir.list().empty());
    fs::create_directory(dir.file("keep"));
    {
        OutputTransaction outputs;
        outputs.create_folder(dir.file("keep/plots"));
        write_bytes(dir.file("keep/plots/mine.txt"), "x");  // someone else's file: kept
    }
    EXPECT_TRUE(fs::exists(dir.file("keep/plots/mine.txt")));
    OutputTransaction outputs;
    outputs.create_folder(dir.file("new/plots"));
    write_text(outputs, dir.file("new/plots/p.svg"), "svg");
    outputs.commit();
    EXPECT_EQ(read_bytes(dir.file("new/plots/p.svg")), "svg");
    test::write_bytes(dir.file("file"), "x");
    test::expect_file_error([&] { OutputTransaction().create_folder(dir.file("file")); },
                            dir.file("file"));
}

TEST(TemporarySibling, NamesFitNameMaxAndStayDistinct) {
    TempDir dir;
    for (const std::size_t length : {5u, 200u, 240u, 250u, 255u}) {
        const std::string name = std::string(length - 4, 'n') + ".pcd";
        const std::string path = dir.file(name);
        const std::string a = temporary_sibling(path, "partial", true);
        const std::string b = temporary_sibling(path, "partial", true);
        EXPECT_NE(a, b);
        EXPECT_EQ(fs::path(a).parent_path(), dir.path());
        EXPECT_LE(fs::path(a).filename().string().size(), kMaxFileNameBytes) << length;
        EXPECT_EQ(lower_extension(a), ".pcd") << length;
        EXPECT_LE(fs::path(temporary_sibling(path, "tmp")).filename().string().size(),
                  kMaxFileNameBytes);
    }
    // Two long names that differ only past the cut get different (hashed) names.
    const auto base_of = [](const std::string& temporary) {
        const std::string name = fs::path(temporary).filename().string();
        return name.substr(0, name.rfind(".t-"));
    };
    const std::string stem(250, 'x');
    EXPECT_NE(base_of(temporary_sibling(dir.file(stem + "1"), "t")),
              base_of(temporary_sibling(dir.file(stem + "2"), "t")));
}

TEST(TemporarySibling, CutsLongUtf8NamesAtACharacterBoundary) {
    std::string name;
    while (name.size() < 250) name += "\xC3\xA9";  // "é", two bytes
    const std::string temporary = fs::path(temporary_sibling("/d/" + name, "tmp")).filename();
    ASSERT_LE(temporary.size(), kMaxFileNameBytes);
    const std::size_t cut = temporary.find('~');
    ASSERT_NE(cut, std::string::npos);
    EXPECT_EQ(cut % 2, 0u) << "a two-byte character was split";
}

TEST(AtomicFileWriter, WritesAFileWhoseNameIsNearNameMax) {
    TempDir dir;
    // A 250-byte name: "<name>.tmp-<pid>-<n>" used to exceed NAME_MAX (ENAMETOOLONG).
    const std::string path = dir.file(std::string(246, 'a') + ".pcd");
    write_cloud(path, test::make_full_cloud(4));
    EXPECT_EQ(read_cloud(path).size(), 4u);
    OutputTransaction outputs;
    const std::string longest = dir.file(std::string(251, 'b') + ".ply");
    outputs.write(longest,
                  [](const std::string& staged) { write_cloud(staged, test::make_full_cloud(2)); });
    outputs.commit();
    EXPECT_EQ(read_cloud(longest).size(), 2u);
    EXPECT_EQ(dir.list().size(), 2u);  // no temporary left
}

TEST(ResolvedPath, IsAbsoluteAndNormalEvenWhenNothingOfItExists) {
    const fs::path resolved = resolved_path("no_such_folder/./sub/../rec/");
    EXPECT_TRUE(resolved.is_absolute()) << resolved;
    EXPECT_EQ(resolved, fs::weakly_canonical(fs::current_path()) / "no_such_folder" / "rec");
}

TEST(EnsureOutputDistinct, RefusesAnInputUnderAnySpelling) {
    TempDir dir;
    write_bytes(dir.file("in.pcd"), "x");
    fs::create_directory(dir.file("sub"));
    const std::string in = dir.file("in.pcd");
    test::expect_file_error([&] { ensure_output_distinct(in, {in}); }, in);
    const std::string dotted = (dir.path() / "sub" / ".." / "." / "in.pcd").string();
    test::expect_file_error([&] { ensure_output_distinct(dotted, {in}); }, dotted);
    fs::create_symlink(in, dir.file("link.pcd"));
    test::expect_file_error([&] { ensure_output_distinct(dir.file("link.pcd"), {in}); },
                            dir.file("link.pcd"));
    fs::create_hard_link(in, dir.file("hard.pcd"));
    test::expect_file_error([&] { ensure_output_distinct(dir.file("hard.pcd"), {in}); },
                            dir.file("hard.pcd"));
    EXPECT_NO_THROW(ensure_output_distinct(dir.file("out.pcd"), {in, ""}));
    EXPECT_NO_THROW(ensure_output_distinct(dir.file("in.pcd.bak"), {in}));
}

TEST(EnsureOutputDistinct, RefusesAnOutputInsideAnInputFolderAndAFolderHoldingAnInput) {
    TempDir dir;
    fs::create_directories(dir.file("rec/lidar"));
    const std::string inside = dir.file("rec/lidar/traj.txt");
    test::expect_file_error([&] { ensure_output_distinct(inside, {dir.file("rec")}); }, inside);
    write_bytes(dir.file("rec/s.yaml"), "x");
    test::expect_file_error(
        [&] { ensure_output_distinct(dir.file("rec"), {dir.file("rec/s.yaml")}); },
        dir.file("rec"));
    EXPECT_NO_THROW(ensure_output_distinct(dir.file("recording/t.txt"), {dir.file("rec")}));
}

TEST(CheckedOutputFile, DevFullReportsNoSpaceLeftOnDevice) {
    if (!fs::exists("/dev/full")) GTEST_SKIP() << "no /dev/full";
    for (const std::size_t bytes : {std::size_t{10}, kMiB}) {  // fails at close, or mid-write
        CheckedOutputFile file("/dev/full", /*exclusive=*/false);
        ASSERT_FALSE(file.error()) << file.error().message();
        file.stream() << std::string(bytes, 'x');
        const std::error_code error = file.close();
        EXPECT_EQ(error, std::errc::no_space_on_device) << bytes;
        EXPECT_EQ(error.message(), "No space left on device");
        EXPECT_EQ(file.close(), error);
    }
}

TEST(CheckedOutputFile, ExclusiveCreationRefusesAnExistingFile) {
    TempDir dir;
    write_bytes(dir.file("a"), "x");
    CheckedOutputFile file(dir.file("a"), /*exclusive=*/true);
    EXPECT_EQ(file.error(), std::errc::file_exists);
    EXPECT_FALSE(file.stream());
    EXPECT_EQ(read_bytes(dir.file("a")), "x");
}

/// In a forked child: writes 1 MiB under a 64 KiB file-size limit, prints the error and exits
/// 0 when nothing was left behind.
[[noreturn]] void write_past_the_size_limit(const TempDir& dir, const std::string& path) {
    std::signal(SIGXFSZ, SIG_IGN);  // EFBIG instead of a killed process
    const rlimit limit{64 * 1024, 64 * 1024};
    setrlimit(RLIMIT_FSIZE, &limit);
    try {
        write_file_atomically(path, [](std::ostream& out) { out << std::string(kMiB, 'x'); });
    } catch (const FileError& e) {
        std::fprintf(stderr, "%s\n", e.what());
        std::_Exit(dir.list().empty() ? 0 : 3);
    }
    std::_Exit(4);
}

// A failing write in the middle of a large output (the file-size limit stands in for a full
// disk, which a test cannot make) must be reported with the OS reason. std::ofstream lost it:
// "write failed: stream error". Run in a forked child: the limit is process-wide.
TEST(AtomicFileWriterDeathTest, AFailedWriteNamesTheOsReasonAndLeavesNothing) {
    TempDir dir;
    const std::string path = dir.file("big.bin");
    EXPECT_EXIT(write_past_the_size_limit(dir, path), testing::ExitedWithCode(0),
                "big.bin: write failed: File too large");
}

}  // namespace
}  // namespace scantling::io
