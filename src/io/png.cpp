#include <scantling/core/error.hpp>
#include <scantling/io/atomic_file.hpp>
#include <scantling/io/png.hpp>

#include <fmt/format.h>
#include <png.h>

#include <algorithm>
#include <csetjmp>
#include <cstring>
#include <ostream>
#include <vector>

namespace scantling::io {
namespace {

// libpng reports errors through longjmp; the message is kept here for the FileError.
struct PngSink {
    std::ostream* out = nullptr;
    char error[256] = {};
};

void on_write(png_structp png, png_bytep data, png_size_t length) {
    auto* sink = static_cast<PngSink*>(png_get_io_ptr(png));
    sink->out->write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(length));
    if (!*sink->out) png_error(png, "stream write failed");
}

void on_flush(png_structp png) { static_cast<PngSink*>(png_get_io_ptr(png))->out->flush(); }

[[noreturn]] void on_error(png_structp png, png_const_charp message) {
    auto* sink = static_cast<PngSink*>(png_get_error_ptr(png));
    std::strncpy(sink->error, message, sizeof(sink->error) - 1);
    png_longjmp(png, 1);
}

void on_warning(png_structp, png_const_charp) {}  // libraries never print

// Only C objects live in this frame, so the longjmp of a libpng error skips no destructor.
bool encode(PngSink& sink, int width, int height, png_bytepp rows) {
    png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, &sink, on_error, on_warning);
    if (png == nullptr) return false;
    png_infop info = png_create_info_struct(png);
    if (info == nullptr || setjmp(png_jmpbuf(png))) {
        png_destroy_write_struct(&png, &info);
        return false;
    }
    png_set_write_fn(png, &sink, on_write, on_flush);
    png_set_IHDR(png, info, static_cast<png_uint_32>(width), static_cast<png_uint_32>(height), 8,
                 PNG_COLOR_TYPE_RGB, PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT,
                 PNG_FILTER_TYPE_DEFAULT);
    png_set_rows(png, info, rows);
    png_write_png(png, info, PNG_TRANSFORM_IDENTITY, nullptr);
    png_destroy_write_struct(&png, &info);
    return true;
}

}  // namespace

void write_png(const std::string& path, int width, int height, std::span<const Rgb8> rgb) {
    if (width < 1 || height < 1 ||
        rgb.size() != static_cast<std::size_t>(width) * static_cast<std::size_t>(height)) {
        throw InputError(
            fmt::format("write_png {}: {} pixels for {} x {}, expected width, "
                        "height >= 1 and width * height pixels",
                        path, rgb.size(), width, height));
    }
    // Rgb8 is three packed bytes; copy into contiguous rows rather than rely on its layout.
    std::vector<png_byte> bytes(rgb.size() * 3);
    for (std::size_t i = 0; i < rgb.size(); ++i) {
        std::memcpy(&bytes[3 * i], rgb[i].data(), 3);
    }
    std::vector<png_bytep> rows(static_cast<std::size_t>(height));
    for (int v = 0; v < height; ++v) rows[v] = &bytes[static_cast<std::size_t>(v) * width * 3];
    AtomicFileWriter writer(path);
    PngSink sink;
    sink.out = &writer.stream();
    if (!encode(sink, width, height, rows.data())) {
        throw FileError(path, fmt::format("PNG encoding failed: {}",
                                          sink.error[0] != '\0' ? sink.error : "out of memory"));
    }
    writer.commit();
}

RgbImage read_png(const std::string& path) {
    png_image image{};
    image.version = PNG_IMAGE_VERSION;
    if (png_image_begin_read_from_file(&image, path.c_str()) == 0) {
        throw FileError(path, fmt::format("not a readable PNG: {}", image.message));
    }
    const std::size_t pixels = std::size_t{image.width} * std::size_t{image.height};
    if (image.width == 0 || image.height == 0 || pixels > kMaxPngPixels) {
        png_image_free(&image);
        throw ParseError(path, FileLocation{.byte_offset = 16, .line = {}, .column = {}},
                         fmt::format("PNG header claims {} x {} pixels, expected 1 to {}",
                                     image.width, image.height, kMaxPngPixels));
    }
    image.format = PNG_FORMAT_RGB;
    std::vector<png_byte> bytes(PNG_IMAGE_SIZE(image));
    if (png_image_finish_read(&image, nullptr, bytes.data(), 0, nullptr) == 0) {
        throw FileError(path, fmt::format("corrupt PNG: {}", image.message));
    }
    RgbImage out{static_cast<int>(image.width), static_cast<int>(image.height), {}};
    out.pixels.resize(pixels);
    for (std::size_t i = 0; i < pixels; ++i) std::memcpy(out.pixels[i].data(), &bytes[3 * i], 3);
    return out;
}

RgbImage crop(const RgbImage& image, int u0, int v0, int width, int height) {
    const int u_begin = std::clamp(u0, 0, image.width);
    const int v_begin = std::clamp(v0, 0, image.height);
    const int u_end = std::clamp(u0 + std::max(width, 0), u_begin, image.width);
    const int v_end = std::clamp(v0 + std::max(height, 0), v_begin, image.height);
    RgbImage out{u_end - u_begin, v_end - v_begin, {}};
    out.pixels.reserve(static_cast<std::size_t>(out.width) * static_cast<std::size_t>(out.height));
    for (int v = v_begin; v < v_end; ++v) {
        const auto row = image.pixels.begin() + static_cast<std::ptrdiff_t>(v) * image.width;
        out.pixels.insert(out.pixels.end(), row + u_begin, row + u_end);
    }
    if (out.pixels.empty()) out.width = out.height = 0;
    return out;
}

}  // namespace scantling::io
