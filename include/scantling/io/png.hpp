#pragma once
/// @file
/// 8-bit RGB PNG images: the simulator writes its camera and sonar images with write_png, and
/// the localiser reads them back (defect crops) with read_png. libpng inside; no libpng type
/// leaks out of here.

#include <cstddef>
#include <span>
#include <string>
#include <vector>

#include <scantling/core/point_cloud.hpp>

namespace scantling::io {

/// An 8-bit RGB image, row-major (index v · width + u).
struct RgbImage {
    int width = 0;
    int height = 0;
    std::vector<Rgb8> pixels;
};

/// Largest image read_png decodes (64 Mpx, 192 MB): a hostile header claiming more is refused
/// before anything is allocated.
inline constexpr std::size_t kMaxPngPixels = std::size_t{1} << 26;

/// Writes an 8-bit RGB PNG of `width` × `height` pixels from row-major `rgb`
/// (index v · width + u), atomically (io::AtomicFileWriter: readers see the old file or the
/// complete new one). Throws InputError unless width, height >= 1 and rgb.size() ==
/// width · height, and FileError naming `path` when it cannot be written (missing directory,
/// write error, libpng error).
void write_png(const std::string& path, int width, int height, std::span<const Rgb8> rgb);
inline void write_png(const std::string& path, const RgbImage& image) {
    write_png(path, image.width, image.height, image.pixels);
}

/// Reads any PNG (grey, palette, 16-bit and alpha are converted to 8-bit RGB by libpng).
/// Throws FileError naming `path` when it is missing, not a PNG, truncated or corrupt, and
/// ParseError when its header claims more than kMaxPngPixels.
RgbImage read_png(const std::string& path);

/// The pixels of `image` in the rectangle [u0, u0 + width) × [v0, v0 + height), clipped to the
/// image (an empty image when nothing is left).
RgbImage crop(const RgbImage& image, int u0, int v0, int width, int height);

}  // namespace scantling::io
