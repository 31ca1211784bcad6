#pragma once
// Scalar types shared by the binary PCD and PLY codecs, loaded from unaligned bytes with an
// explicit byte order (files are little endian unless PLY says otherwise; hosts may be either).

#include <bit>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <string_view>

namespace scantling::io::detail {

enum class ScalarType : std::uint8_t { kI8, kU8, kI16, kU16, kI32, kU32, kI64, kU64, kF32, kF64 };

constexpr std::size_t scalar_size(ScalarType type) {
    switch (type) {
        case ScalarType::kI8:
        case ScalarType::kU8:
            return 1;
        case ScalarType::kI16:
        case ScalarType::kU16:
            return 2;
        case ScalarType::kI32:
        case ScalarType::kU32:
        case ScalarType::kF32:
            return 4;
        default:
            return 8;
    }
}

constexpr bool is_integer(ScalarType type) {
    return type != ScalarType::kF32 && type != ScalarType::kF64;
}

/// Name for messages: "uint8", "int32", "float64", ...
constexpr const char* scalar_type_name(ScalarType type) {
    constexpr const char* kNames[] = {"int8",   "uint8", "int16",  "uint16",  "int32",
                                      "uint32", "int64", "uint64", "float32", "float64"};
    return kNames[static_cast<std::size_t>(type)];
}

/// Whether an integer read from text is representable in `type` (an ascii body must not hold
/// values its declared type cannot store: "uint8" with 300 is a lying header, not a colour).
/// Floating types hold every integer the text parsers return.
constexpr bool integer_fits(ScalarType type, std::int64_t value) {
    switch (type) {
        case ScalarType::kI8:
            return value >= INT8_MIN && value <= INT8_MAX;
        case ScalarType::kU8:
            return value >= 0 && value <= UINT8_MAX;
        case ScalarType::kI16:
            return value >= INT16_MIN && value <= INT16_MAX;
        case ScalarType::kU16:
            return value >= 0 && value <= UINT16_MAX;
        case ScalarType::kI32:
            return value >= INT32_MIN && value <= INT32_MAX;
        case ScalarType::kU32:
            return value >= 0 && value <= std::int64_t{UINT32_MAX};
        case ScalarType::kU64:
            return value >= 0;
        default:
            return true;
    }
}

/// Same for a value parsed as unsigned (UINT64 values above INT64_MAX included).
constexpr bool integer_fits(ScalarType type, std::uint64_t value) {
    if (type == ScalarType::kU64 || !is_integer(type)) return true;
    return value <= std::uint64_t{INT64_MAX} &&
           integer_fits(type, static_cast<std::int64_t>(value));
}

/// `size` bytes at `bytes`, reversed when the data's byte order differs from the host's.
template <typename T>
T load_scalar(const unsigned char* bytes, std::endian order) {
    unsigned char buffer[sizeof(T)];
    std::memcpy(buffer, bytes, sizeof(T));
    if (order != std::endian::native) {
        for (std::size_t i = 0; i < sizeof(T) / 2; ++i) {
            const unsigned char tmp = buffer[i];
            buffer[i] = buffer[sizeof(T) - 1 - i];
            buffer[sizeof(T) - 1 - i] = tmp;
        }
    }
    T value;
    std::memcpy(&value, buffer, sizeof(T));
    return value;
}

/// The value at `bytes` converted to double (exact for every type but 64-bit integers > 2^53).
inline double load_as_double(const unsigned char* bytes, ScalarType type, std::endian order) {
    switch (type) {
        case ScalarType::kI8:
            return load_scalar<std::int8_t>(bytes, order);
        case ScalarType::kU8:
            return load_scalar<std::uint8_t>(bytes, order);
        case ScalarType::kI16:
            return load_scalar<std::int16_t>(bytes, order);
        case ScalarType::kU16:
            return load_scalar<std::uint16_t>(bytes, order);
        case ScalarType::kI32:
            return load_scalar<std::int32_t>(bytes, order);
        case ScalarType::kU32:
            return load_scalar<std::uint32_t>(bytes, order);
        case ScalarType::kI64:
            return static_cast<double>(load_scalar<std::int64_t>(bytes, order));
        case ScalarType::kU64:
            return static_cast<double>(load_scalar<std::uint64_t>(bytes, order));
        case ScalarType::kF32:
            return load_scalar<float>(bytes, order);
        case ScalarType::kF64:
            return load_scalar<double>(bytes, order);
    }
    return 0.0;
}

/// Appends `value` to `out` in little-endian byte order.
template <typename T>
void append_le(std::string& out, T value) {
    unsigned char buffer[sizeof(T)];
    std::memcpy(buffer, &value, sizeof(T));
    if constexpr (std::endian::native == std::endian::big) {
        for (std::size_t i = 0; i < sizeof(T) / 2; ++i) {
            const unsigned char tmp = buffer[i];
            buffer[i] = buffer[sizeof(T) - 1 - i];
            buffer[sizeof(T) - 1 - i] = tmp;
        }
    }
    out.append(reinterpret_cast<const char*>(buffer), sizeof(T));
}

}  // namespace scantling::io::detail
