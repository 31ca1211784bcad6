#include "detail/lzf.hpp"

#include <scantling/core/error.hpp>

#include <algorithm>
#include <cstring>

namespace scantling::io::detail {
namespace {

constexpr std::size_t kMaxLiteralRun = 32;
constexpr std::size_t kMaxOffset = 1u << 13;    // 13 offset bits
constexpr std::size_t kMaxMatch = 2 + 7 + 255;  // L + 2 with L = 7 + extension byte
constexpr std::size_t kMinMatch = 3;
constexpr int kHashBits = 14;

struct Decoder {
    std::span<const std::uint8_t> in;
    std::span<std::uint8_t> out;
    const std::string& path;
    std::uint64_t input_offset;
    std::size_t ip = 0;
    std::size_t op = 0;

    [[noreturn]] void fail(std::size_t chunk_start, const std::string& what) const {
        throw ParseError(path, {input_offset + chunk_start, std::nullopt, std::nullopt},
                         "corrupt LZF stream: " + what);
    }

    void literal(std::size_t chunk_start, std::size_t length) {
        if (ip + length > in.size()) fail(chunk_start, "literal run past the end of the input");
        if (op + length > out.size()) fail(chunk_start, "literal run overflows the output");
        std::memcpy(out.data() + op, in.data() + ip, length);
        ip += length;
        op += length;
    }

    void back_reference(std::size_t chunk_start, unsigned control) {
        std::size_t length = control >> 5;
        if (length == 7) {
            if (ip >= in.size()) fail(chunk_start, "truncated length byte");
            length += in[ip++];
        }
        if (ip >= in.size()) fail(chunk_start, "truncated offset byte");
        const std::size_t distance = ((control & 0x1fu) << 8) + in[ip++] + 1;
        length += 2;
        if (distance > op) fail(chunk_start, "back reference before the start of the output");
        if (op + length > out.size()) fail(chunk_start, "back reference overflows the output");
        // Byte by byte: source and destination may overlap (run-length style references).
        for (std::size_t k = 0; k < length; ++k, ++op) out[op] = out[op - distance];
    }
};

std::uint32_t hash3(const std::uint8_t* p) {
    const std::uint32_t v = (std::uint32_t{p[0]} << 16) | (std::uint32_t{p[1]} << 8) | p[2];
    return (v * 2654435761u) >> (32 - kHashBits);
}

void flush_literals(std::vector<std::uint8_t>& out, std::span<const std::uint8_t> input,
                    std::size_t begin, std::size_t end) {
    while (begin < end) {
        const std::size_t run = std::min(kMaxLiteralRun, end - begin);
        out.push_back(static_cast<std::uint8_t>(run - 1));
        out.insert(out.end(), input.begin() + static_cast<std::ptrdiff_t>(begin),
                   input.begin() + static_cast<std::ptrdiff_t>(begin + run));
        begin += run;
    }
}

void emit_match(std::vector<std::uint8_t>& out, std::size_t length, std::size_t distance) {
    const std::size_t l = length - 2;
    const std::size_t o = distance - 1;
    const auto high = static_cast<std::uint8_t>(o >> 8);
    if (l < 7) {
        out.push_back(static_cast<std::uint8_t>((l << 5) | high));
    } else {
        out.push_back(static_cast<std::uint8_t>((7u << 5) | high));
        out.push_back(static_cast<std::uint8_t>(l - 7));
    }
    out.push_back(static_cast<std::uint8_t>(o & 0xffu));
}

std::size_t match_length(std::span<const std::uint8_t> input, std::size_t candidate,
                         std::size_t i) {
    const std::size_t limit = std::min(kMaxMatch, input.size() - i);
    std::size_t length = 0;
    while (length < limit && input[candidate + length] == input[i + length]) ++length;
    return length;
}

}  // namespace

void lzf_decompress(std::span<const std::uint8_t> input, std::span<std::uint8_t> output,
                    const std::string& path, std::uint64_t input_offset) {
    Decoder d{input, output, path, input_offset};
    while (d.ip < input.size()) {
        const std::size_t chunk_start = d.ip;
        const unsigned control = input[d.ip++];
        if (control < 32) {
            d.literal(chunk_start, control + 1);
        } else {
            d.back_reference(chunk_start, control);
        }
    }
    if (d.op != output.size()) {
        d.fail(input.size(), "decompressed " + std::to_string(d.op) + " bytes, expected " +
                                 std::to_string(output.size()));
    }
}

std::vector<std::uint8_t> lzf_compress(std::span<const std::uint8_t> input) {
    std::vector<std::uint8_t> out;
    out.reserve(input.size() + input.size() / 32 + 1);
    std::vector<std::size_t> table(std::size_t{1} << kHashBits, SIZE_MAX);
    std::size_t literal_start = 0;
    std::size_t i = 0;
    while (i + kMinMatch <= input.size()) {
        const std::uint32_t h = hash3(input.data() + i);
        const std::size_t candidate = table[h];
        table[h] = i;
        const bool near = candidate != SIZE_MAX && i - candidate <= kMaxOffset;
        const std::size_t length = near ? match_length(input, candidate, i) : 0;
        if (length < kMinMatch) {
            ++i;
            continue;
        }
        flush_literals(out, input, literal_start, i);
        emit_match(out, length, i - candidate);
        i += length;
        literal_start = i;
    }
    flush_literals(out, input, literal_start, input.size());
    return out;
}

}  // namespace scantling::io::detail
