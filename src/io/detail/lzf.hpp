#pragma once
// LZF (Marc Lehmann's liblzf format), as used by PCL's "DATA binary_compressed". Written from
// the format description, bounds-checked on every read and write.
//
// Stream = sequence of chunks, each starting with a control byte c:
//   c < 32:  literal run, the next c + 1 bytes are copied to the output;
//   c >= 32: back reference, length L = c >> 5 (if L == 7, L += next byte), offset
//            o = ((c & 31) << 8) + next byte; copies L + 2 bytes from (output end - o - 1).

#include <cstdint>
#include <span>
#include <string>
#include <vector>

namespace scantling::io::detail {

/// Decompresses `input` into exactly `output.size()` bytes. On a corrupt stream (reference
/// before the start, output overflow, truncated chunk, or fewer bytes than expected) throws
/// ParseError for `path` naming the byte offset `input_offset` + position of the bad chunk.
void lzf_decompress(std::span<const std::uint8_t> input, std::span<std::uint8_t> output,
                    const std::string& path, std::uint64_t input_offset);

/// Compresses `input` (greedy, hash of 3-byte prefixes). Never fails; the output may be
/// slightly larger than the input for incompressible data (one control byte per 32 literals).
std::vector<std::uint8_t> lzf_compress(std::span<const std::uint8_t> input);

}  // namespace scantling::io::detail
