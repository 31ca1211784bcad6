// `scantling` on bad input or options: exit code 2, one stderr line, no file written.
#include "cli_fixture.hpp"

#include <fstream>
#include <string>

#include <scantling/core/point_cloud.hpp>
#include <scantling/io/cloud_io.hpp>

namespace scantling::cli_test {
namespace {

TEST_F(Cli, MissingInputFailsWithOneLineNamingThePath) {
    expect_one_error_line(run("info " + quoted(path("missing.pcd"))), path("missing.pcd"));
    expect_one_error_line(
        run("convert " + quoted(path("missing.pcd")) + " " + quoted(path("o.ply"))),
        path("missing.pcd"));
    expect_files({});
}

TEST_F(Cli, GarbageInputFailsAndWritesNothing) {
    std::ofstream(path("garbage.pcd")) << "this is not a point cloud\n";
    expect_one_error_line(
        run("convert " + quoted(path("garbage.pcd")) + " " + quoted(path("o.ply"))),
        path("garbage.pcd"));
    expect_one_error_line(run("info " + quoted(path("garbage.pcd"))), path("garbage.pcd"));
    expect_files({"garbage.pcd"});
}

TEST_F(Cli, UnknownExtensionFailsBeforeWriting) {
    scantling::io::write_cloud(path("in.pcd"), make_grid());
    expect_one_error_line(run("convert " + quoted(path("in.pcd")) + " " + quoted(path("out.xyz"))),
                          path("out.xyz"));
    expect_one_error_line(run("info " + quoted(path("in.xyz"))), path("in.xyz"));
    expect_files({"in.pcd"});
}

TEST_F(Cli, BadOptionsFailBeforeWriting) {
    scantling::io::write_cloud(path("in.pcd"), make_grid());
    const std::string in_out = quoted(path("in.pcd")) + " " + quoted(path("out.pcd"));
    expect_one_error_line(run("convert " + in_out + " --voxel -1"), "--voxel");
    expect_one_error_line(run("downsample " + in_out + " --voxel=-1"), "--voxel");
    expect_one_error_line(run("downsample " + in_out + " --voxel nan"), "--voxel");
    expect_one_error_line(run("downsample " + in_out + " --voxel 0.1 --threads -2"), "--threads");
    expect_one_error_line(run("downsample " + in_out), "--voxel");
    expect_one_error_line(
        run("convert " + quoted(path("in.pcd")) + " " + quoted(path("out.ply")) + " --ascii"),
        "--ascii");
    expect_files({"in.pcd"});
}

TEST_F(Cli, UnwritableOutputDirectoryFailsWithoutLeavingFiles) {
    scantling::io::write_cloud(path("in.pcd"), make_grid());
    const std::string missing_dir = path("no_such_dir/out.pcd");
    expect_one_error_line(run("convert " + quoted(path("in.pcd")) + " " + quoted(missing_dir)),
                          missing_dir);
    const std::string under_file = path("in.pcd/out.ply");
    expect_one_error_line(run("convert " + quoted(path("in.pcd")) + " " + quoted(under_file)),
                          under_file);
    expect_files({"in.pcd"});
}

TEST_F(Cli, ReadOnlyOutputDirectoryFailsWithoutLeavingFiles) {
    if (::geteuid() == 0) GTEST_SKIP() << "root writes into read-only directories";
    scantling::io::write_cloud(path("in.pcd"), make_grid());
    fs::create_directory(path("ro"));
    fs::permissions(path("ro"), fs::perms::owner_read | fs::perms::owner_exec);
    const std::string out = path("ro/out.pcd");
    expect_one_error_line(run("convert " + quoted(path("in.pcd")) + " " + quoted(out)), out);
    EXPECT_TRUE(fs::is_empty(path("ro")));
    fs::permissions(path("ro"), fs::perms::owner_all);
}

TEST_F(Cli, UsageErrorsAreOneLineWithExitCodeTwo) {
    expect_one_error_line(run(""), "subcommand");
    expect_one_error_line(run("frobnicate"), "frobnicate");
    expect_one_error_line(run("info"), "FILE");
    expect_one_error_line(run("convert a.pcd b.pcd --bogus"), "--bogus");
}

}  // namespace
}  // namespace scantling::cli_test
