#pragma once
/// @file
/// PNG output of simulated camera images (libpng inside; no libpng type leaks out of here).

#include <span>
#include <string>

#include <scantling/core/point_cloud.hpp>

namespace scantling::sim {

/// Writes an 8-bit RGB PNG of `width` × `height` pixels from row-major `rgb`
/// (index v · width + u), atomically (io::AtomicFileWriter: readers see the old file or the
/// complete new one). Throws InputError unless width, height >= 1 and rgb.size() ==
/// width · height, and FileError naming `path` when it cannot be written (missing directory,
/// write error, libpng error).
void write_png(const std::string& path, int width, int height, std::span<const Rgb8> rgb);

}  // namespace scantling::sim
