#include <scantling/core/error.hpp>
#include <scantling/sim/png_writer.hpp>

#include <gtest/gtest.h>
#include <png.h>
#include <unistd.h>

#include <filesystem>
#include <vector>

namespace scantling::sim {
namespace {

std::filesystem::path temp_dir() {
    const auto dir = std::filesystem::temp_directory_path() /
                     ("scantling_png_test_" + std::to_string(::getpid()));
    std::filesystem::create_directories(dir);
    return dir;
}

TEST(PngWriter, WrittenImageDecodesToTheSamePixels) {
    const int width = 7, height = 5;
    std::vector<Rgb8> rgb;
    for (int i = 0; i < width * height; ++i) rgb.emplace_back(i * 7, 255 - i, (i * 37) % 256);
    const std::string path = (temp_dir() / "image.png").string();
    write_png(path, width, height, rgb);

    png_image image{};
    image.version = PNG_IMAGE_VERSION;
    ASSERT_NE(png_image_begin_read_from_file(&image, path.c_str()), 0) << image.message;
    EXPECT_EQ(image.width, 7u);
    EXPECT_EQ(image.height, 5u);
    image.format = PNG_FORMAT_RGB;
    std::vector<png_byte> decoded(PNG_IMAGE_SIZE(image));
    ASSERT_NE(png_image_finish_read(&image, nullptr, decoded.data(), 0, nullptr), 0)
        << image.message;
    for (int i = 0; i < width * height; ++i) {
        for (int c = 0; c < 3; ++c) ASSERT_EQ(decoded[3 * i + c], rgb[i][c]) << i;
    }
    std::filesystem::remove_all(temp_dir());
}

TEST(PngWriter, BadSizesAndPathsThrow) {
    const std::vector<Rgb8> rgb(6, Rgb8(1, 2, 3));
    const std::string path = (temp_dir() / "bad.png").string();
    EXPECT_THROW(write_png(path, 4, 2, rgb), InputError);
    EXPECT_THROW(write_png(path, 0, 6, rgb), InputError);
    EXPECT_FALSE(std::filesystem::exists(path));
    EXPECT_THROW(write_png((temp_dir() / "missing" / "x.png").string(), 3, 2, rgb), FileError);
    std::filesystem::remove_all(temp_dir());
}

}  // namespace
}  // namespace scantling::sim
