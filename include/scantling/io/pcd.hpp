#pragma once
/// @file
/// PCL's PCD point-cloud files (format v0.7).
///
/// Field mapping (other fields, e.g. curvature, padding "_" or histograms, are skipped):
///   x y z → points; normal_x normal_y normal_z → normals; intensity → intensities;
///   ring → rings; time / t / timestamp → times_s; rgb / rgba (packed 0x00RRGGBB in a float
///   or uint32) → colors.
/// Time conversions: integer-typed time fields are nanoseconds (Ouster's `t`), floating ones
/// seconds; absolute stamps (> 1e5 s) set `stamp_s` to the earliest and `times_s` to offsets.
/// Organised clouds (HEIGHT > 1) are returned row-major, NaN points included, so that
/// index = row * WIDTH + column still holds; call remove_non_finite() to drop them.
/// VIEWPOINT is validated but not applied (as in PCL). Byte order: little endian.

#include <string>

#include <scantling/core/point_cloud.hpp>

namespace scantling::io {

// Thread-safety: the functions keep no shared state; concurrent calls on different files are
// safe. Writers go through AtomicFileWriter, so a reader never sees a partial file.

/// Reads DATA ascii, binary and binary_compressed; field types F (4, 8 bytes), I and U
/// (1, 2, 4, 8 bytes), COUNT >= 1 (mapped fields need COUNT 1).
/// Throws FileError (missing, unreadable, directory) or ParseError naming the file and the
/// line (header, ascii data) or byte offset (binary data): missing header keys, POINTS !=
/// WIDTH * HEIGHT, unknown DATA type, garbage tokens, data shorter than declared, no x y z,
/// corrupt compressed stream.
/// Hostile headers: every size the header implies (SIZE x COUNT summed into the record, field
/// offsets, WIDTH x HEIGHT, POINTS x record, the compressed block sizes) is computed with
/// overflow checks and bounded by the bytes present before anything is allocated, so memory
/// stays within a small multiple of the file size. Also refused: a field name used twice ("_"
/// padding aside), two fields feeding one member (intensity and reflectance), an ascii integer
/// outside its TYPE and SIZE, and bytes after binary data (POINTS or SIZE smaller than the data)
/// other than up to 64 KiB of zeros or whitespace (PCL up to 1.8 pads files to a page).
/// Cost: one read of the file plus O(points × fields); a 124k-point binary file takes a few ms.
PointCloud read_pcd(const std::string& path);

enum class PcdEncoding { kAscii, kBinary };

/// Writes every present field as float32 (x y z, normal_*, intensity, time), uint16 (ring)
/// and PCL's packed float rgb; covariances and `stamp_s` are not stored. Positions are
/// rounded to float32 (~1e-7 relative). Written atomically (no partial file on failure).
/// Ascii numbers use the shortest text that reads back to the same float.
/// Throws InputError for an inconsistent cloud, FileError when the file cannot be written.
void write_pcd(const std::string& path, const PointCloud& cloud,
               PcdEncoding encoding = PcdEncoding::kBinary);

}  // namespace scantling::io
