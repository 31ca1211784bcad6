// images/camera.json of a recording: the RGB camera's pinhole intrinsics (recording.hpp).
#include <fmt/format.h>

#include <nlohmann/json.hpp>

#include <scantling/core/error.hpp>
#include <scantling/io/recording.hpp>

#include "detail/json_fields.hpp"
#include "detail/text_lines.hpp"

namespace scantling::io {

PinholeIntrinsics read_camera_intrinsics(const std::string& path) {
    // Six numbers: anything bigger than a few hundred values is not this file.
    const detail::Json root = detail::parse_bounded_json(detail::read_whole_file(path), path,
                                                         {.max_values = 256, .max_depth = 4});
    const detail::Fields top(path, root, "");
    top.require({"width", "height", "fx", "fy", "cx", "cy"});
    PinholeIntrinsics intrinsics{.width = top.integer("width"),
                                 .height = top.integer("height"),
                                 .fx = top.number("fx"),
                                 .fy = top.number("fy"),
                                 .cx = top.number("cx"),
                                 .cy = top.number("cy")};
    if (intrinsics.width < 1)
        top.fail("width", fmt::format("= {}, expected >= 1", intrinsics.width));
    if (intrinsics.height < 1) {
        top.fail("height", fmt::format("= {}, expected >= 1", intrinsics.height));
    }
    if (!(intrinsics.fx > 0.0)) top.fail("fx", fmt::format("= {}, expected > 0", intrinsics.fx));
    if (!(intrinsics.fy > 0.0)) top.fail("fy", fmt::format("= {}, expected > 0", intrinsics.fy));
    return intrinsics;
}

std::string camera_intrinsics_json(const PinholeIntrinsics& intrinsics) {
    nlohmann::ordered_json json;
    json["width"] = intrinsics.width;
    json["height"] = intrinsics.height;
    json["fx"] = intrinsics.fx;
    json["fy"] = intrinsics.fy;
    json["cx"] = intrinsics.cx;
    json["cy"] = intrinsics.cy;
    return json.dump(2) + "\n";
}

}  // namespace scantling::io
