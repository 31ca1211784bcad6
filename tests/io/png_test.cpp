#include <scantling/core/error.hpp>
#include <scantling/io/png.hpp>

#include <gtest/gtest.h>
#include <png.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <vector>

namespace scantling::io {
namespace {

std::filesystem::path temp_dir() {
    const auto dir = std::filesystem::temp_directory_path() /
                     ("scantling_png_test_" + std::to_string(::getpid()));
    std::filesystem::create_directories(dir);
    return dir;
}

TEST(Png, WrittenImageDecodesToTheSamePixels) {
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

TEST(Png, BadSizesAndPathsThrow) {
    const std::vector<Rgb8> rgb(6, Rgb8(1, 2, 3));
    const std::string path = (temp_dir() / "bad.png").string();
    EXPECT_THROW(write_png(path, 4, 2, rgb), InputError);
    EXPECT_THROW(write_png(path, 0, 6, rgb), InputError);
    EXPECT_FALSE(std::filesystem::exists(path));
    EXPECT_THROW(write_png((temp_dir() / "missing" / "x.png").string(), 3, 2, rgb), FileError);
    std::filesystem::remove_all(temp_dir());
}

TEST(Png, ReadPngReturnsWhatWritePngWrote) {
    RgbImage image{3, 2, {}};
    for (int i = 0; i < 6; ++i) image.pixels.emplace_back(i, 2 * i, 255 - i);
    const std::string path = (temp_dir() / "round_trip.png").string();
    write_png(path, image);
    const RgbImage read = read_png(path);
    ASSERT_EQ(read.width, 3);
    ASSERT_EQ(read.height, 2);
    EXPECT_EQ(read.pixels, image.pixels);
    std::filesystem::remove_all(temp_dir());
}

TEST(Png, ReadPngRefusesMissingTruncatedAndHostileFiles) {
    EXPECT_THROW(read_png((temp_dir() / "absent.png").string()), FileError);
    RgbImage image{40, 30, std::vector<Rgb8>(1200, Rgb8(9, 8, 7))};
    const std::string path = (temp_dir() / "cut.png").string();
    write_png(path, image);
    std::filesystem::resize_file(path, std::filesystem::file_size(path) / 2);
    EXPECT_THROW(read_png(path), FileError);
    // A valid signature and IHDR claiming 2^20 x 2^20 pixels: refused before allocation.
    write_png(path, image);
    std::fstream file(path, std::ios::in | std::ios::out | std::ios::binary);
    const unsigned char huge[8] = {0, 16, 0, 0, 0, 16, 0, 0};
    file.seekp(16);
    file.write(reinterpret_cast<const char*>(huge), 8);
    file.close();
    EXPECT_ANY_THROW(read_png(path));
    std::filesystem::remove_all(temp_dir());
}

TEST(Png, CropClipsToTheImage) {
    RgbImage image{4, 3, {}};
    for (int i = 0; i < 12; ++i) image.pixels.emplace_back(i, 0, 0);
    const RgbImage inside = crop(image, 1, 1, 2, 2);
    ASSERT_EQ(inside.width, 2);
    ASSERT_EQ(inside.height, 2);
    EXPECT_EQ(inside.pixels[0][0], 5);
    EXPECT_EQ(inside.pixels[3][0], 10);
    const RgbImage clipped = crop(image, -2, 2, 10, 10);
    EXPECT_EQ(clipped.width, 4);
    EXPECT_EQ(clipped.height, 1);
    EXPECT_EQ(crop(image, 5, 0, 3, 3).pixels.size(), 0u);
}

}  // namespace
}  // namespace scantling::io
