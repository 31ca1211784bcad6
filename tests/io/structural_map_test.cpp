#include <scantling/core/error.hpp>
#include <scantling/io/structural_map.hpp>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <filesystem>
#include <string>

#include "test_files.hpp"

namespace scantling::io {
namespace {

using Json = nlohmann::ordered_json;
const std::string kName = "world/metadata.json";  // the file the messages name

/// Two compartments side by side (aft x 0..2, fore x 2..4) and a sump nested in the fore one,
/// a manhole between them and an entry from above; frames 10, 11, 12 at x = 0, 2, 4;
/// longitudinals 1 and 2 along x at y = 0.5 and 1.5 (z = 0.1).
StructuralMap small_map() {
    StructuralMap m;
    m.name = "test_tank";
    m.surfaces = {{.tag = 0, .name = "shell", .textured = true, .albedo = 0.5},
                  {.tag = 1, .name = "web_frame", .textured = false, .albedo = 0.25}};
    m.compartments = {
        {.id = 0, .name = "aft", .bounds = {{0, 0, 0}, {2, 2, 2}}, .level = 0},
        {.id = 1, .name = "fore", .bounds = {{2, 0, 0}, {4, 2, 2}}, .level = 0},
        {.id = 2, .name = "sump", .bounds = {{3, 0, 0}, {3.5, 0.5, 0.5}}, .level = 0}};
    m.connections = {{.id = 0,
                      .kind = ConnectionKind::Manhole,
                      .compartment_a = 0,
                      .compartment_b = 1,
                      .centre = {2, 1, 1},
                      .normal = Eigen::Vector3d::UnitX(),
                      .width_m = 0.6,
                      .height_m = 0.8},
                     {.id = 1,
                      .kind = ConnectionKind::Entry,
                      .compartment_a = 0,
                      .compartment_b = Connection::kOutside,
                      .centre = {1, 1, 2},
                      .normal = Eigen::Vector3d::UnitZ(),
                      .width_m = 0.6,
                      .height_m = 0.8}};
    for (int k = 0; k < 3; ++k) {
        m.frames.push_back({.number = 10 + k,
                            .point = {2.0 * k, 1, 1},
                            .axis = Eigen::Vector3d::UnitX(),
                            .surface = "web_frame"});
    }
    m.longitudinals = {
        {.number = 1, .point = {0, 0.5, 0.1}, .axis = Eigen::Vector3d::UnitX(), .surface = "shell"},
        {.number = 2,
         .point = {0, 1.5, 0.1},
         .axis = Eigen::Vector3d::UnitX(),
         .surface = "shell"}};
    m.landmarks = {{.id = 0,
                    .kind = LandmarkKind::FrameLongitudinal,
                    .position = {2, 0.5, 0.1},
                    .compartment = 0,
                    .frame = 11,
                    .longitudinal = 1,
                    .connection = -1},
                   {.id = 1,
                    .kind = LandmarkKind::ManholeCentre,
                    .position = {2, 1, 1},
                    .compartment = 1,
                    .frame = -1,
                    .longitudinal = -1,
                    .connection = 0}};
    m.defects = {{.id = 0,
                  .kind = DefectKind::Crack,
                  .centre = {3, 1, 0},
                  .normal = Eigen::Vector3d::UnitZ(),
                  .direction = Eigen::Vector3d(0.6, 0.8, 0.0),
                  .radius_m = 0.05,
                  .surface_tag = 0,
                  .compartment = 1},
                 {.id = 1,
                  .kind = DefectKind::Corrosion,
                  .centre = {5, 1, 0},
                  .normal = -Eigen::Vector3d::UnitZ(),
                  .direction = Eigen::Vector3d::UnitX(),
                  .radius_m = 0.1,
                  .surface_tag = 0,
                  .compartment = -1}};
    return m;
}

Json small_map_json() { return Json::parse(structural_map_to_json(small_map())); }

/// The message of the ParseError parsing `text` throws ("accepted" when it throws none).
std::string refusal(const std::string& text) {
    try {
        parse_structural_map(text, kName);
    } catch (const ParseError& e) {
        return e.what();
    }
    return "accepted";
}

/// Expects parsing `j` to be refused with "<kName>: <message>...".
void expect_refused(const Json& j, const std::string& message) {
    const std::string what = refusal(j.dump());
    EXPECT_EQ(what.rfind(kName + ": " + message, 0), 0u) << what;
}

void expect_refused_text(const std::string& text, const std::string& message) {
    const std::string what = refusal(text);
    EXPECT_NE(what.find(message), std::string::npos) << what;
}

TEST(StructuralMap, WriterThenReaderGivesTheSameMap) {
    const test::TempDir dir;
    const StructuralMap map = small_map();
    const int tags[] = {0, 0, 1, 0};
    test::write_bytes(dir.file("metadata.json"), structural_map_to_json(map, tags));
    const StructuralMap read = read_structural_map(dir.file("metadata.json"));
    EXPECT_EQ(read, map);
    EXPECT_EQ(read.defects[1].normal.z(), -1.0);
    EXPECT_EQ(read.connections[1].compartment_b, Connection::kOutside);
    EXPECT_EQ(read.compartments[2].bounds.max, Eigen::Vector3d(3.5, 0.5, 0.5));
}

TEST(StructuralMap, JsonListsTheTagsRunLengthEncoded) {
    const int tags[] = {0, 0, 1, 0};
    const Json j = Json::parse(structural_map_to_json(small_map(), tags));
    EXPECT_EQ(j["triangle_surface_tags"], Json::parse("[[0, 2], [1, 1], [0, 1]]"));
    EXPECT_FALSE(small_map_json().contains("triangle_surface_tags"));
}

TEST(StructuralMap, RefusesAMissingFile) {
    const test::TempDir dir;
    test::expect_file_error([&] { read_structural_map(dir.file("absent.json")); },
                            dir.file("absent.json"));
}

TEST(StructuralMap, RefusesMalformedJson) {
    expect_refused_text("{\"name\": \"x\", ", "malformed JSON");
    expect_refused_text("", "malformed JSON");
    expect_refused_text("{\"name\": \"x\", \"name\": \"y\"}", "the key \"name\" appears twice");
}

TEST(StructuralMap, RefusesMissingKeys) {
    Json j = small_map_json();
    j["compartments"][1].erase("min");
    expect_refused(j, "compartments[1].min: missing");
    j = small_map_json();
    j.erase("defects");
    expect_refused(j, "defects: missing");
}

TEST(StructuralMap, RefusesUnknownKeys) {
    Json j = small_map_json();
    j["colour"] = "red";
    expect_refused(j, "colour: unknown key");
    j = small_map_json();
    j["landmarks"][0]["note"] = 1;
    expect_refused(j, "landmarks[0].note: unknown key");
}

TEST(StructuralMap, RefusesWrongTypes) {
    const auto refused = [](const char* pointer, const Json& value, const std::string& message) {
        Json j = small_map_json();
        j[Json::json_pointer(pointer)] = value;
        expect_refused(j, message);
    };
    refused("/compartments/1/min", Json::array({0, 0}), "compartments[1].min: expected 3 numbers");
    refused("/compartments/1/min", "0 0 0", "compartments[1].min: expected 3 numbers");
    refused("/compartments/0/id", 0.5, "compartments[0].id: expected an integer, found a fraction");
    refused("/compartments/0/id", 4294967296LL, "compartments[0].id: expected an integer in");
    refused("/name", 3, "name: expected a string, found an integer");
    refused("/surfaces", Json::object(), "surfaces: expected an array, found an object");
    refused("/surfaces/0/textured", 1, "surfaces[0].textured: expected true or false");
    refused("/frames/0", 7, "frames[0]: expected an object, found an integer");
    refused("/connections/0/kind", "door", "connections[0].kind = \"door\", expected one of:");
    expect_refused_text("[]", "expected an object, found an array");
}

TEST(StructuralMap, RefusesNonFiniteNumbers) {
    // JSON has no NaN or infinity; a number too large for a double is how one arrives.
    std::string text = small_map_json().dump();
    text.replace(text.find("0.6"), 3, "1e999");
    expect_refused_text(text, "malformed JSON: number overflow");
}

TEST(StructuralMap, RefusesImpossibleValues) {
    Json j = small_map_json();
    j["compartments"][1]["min"][2] = 3.0;  // above max z = 2
    expect_refused(j, "compartments[1].min: is above max");
    j = small_map_json();
    j["connections"][0]["normal"] = Json::array({2.0, 0.0, 0.0});
    expect_refused(j, "connections[0].normal: has norm 2, expected a unit vector");
    j = small_map_json();
    j["defects"][0]["radius_m"] = -0.1;
    expect_refused(j, "defects[0].radius_m = -0.1, expected >= 0");
    j = small_map_json();
    j["surfaces"][1]["albedo"] = 1.5;
    expect_refused(j, "surfaces[1].albedo = 1.5, expected in [0, 1]");
}

TEST(StructuralMap, RefusesReferencesToCompartmentsThatDoNotExist) {
    Json j = small_map_json();
    j["connections"][0]["compartment_b"] = 3;
    expect_refused(j, "connections[0].compartment_b = 3: no such compartment");
    j = small_map_json();
    j["landmarks"][1]["compartment"] = -1;  // -1 means "outside" only for connections, defects
    expect_refused(j, "landmarks[1].compartment = -1: no such compartment");
    j = small_map_json();
    j["defects"][0]["compartment"] = 7;
    expect_refused(j, "defects[0].compartment = 7: no such compartment");
}

TEST(StructuralMap, RefusesOtherDanglingReferences) {
    Json j = small_map_json();
    j["landmarks"][0]["frame"] = 13;
    expect_refused(j, "landmarks[0].frame = 13: no such frame number");
    j = small_map_json();
    j["landmarks"][1]["connection"] = 2;
    expect_refused(j, "landmarks[1].connection = 2: no such connection");
    j = small_map_json();
    j["defects"][1]["surface_tag"] = 2;
    expect_refused(j, "defects[1].surface_tag = 2: no such surface");
    j = small_map_json();
    j["longitudinals"][0]["surface"] = "deck";
    expect_refused(j, "longitudinals[0].surface = \"deck\": no surface has that name");
}

TEST(StructuralMap, RefusesDuplicateIdsAndIdsThatAreNotPositions) {
    Json j = small_map_json();
    j["compartments"][1]["id"] = 0;
    expect_refused(j, "compartments[1].id = 0 repeats the id of item 0");
    j = small_map_json();
    j["landmarks"][0]["id"] = 5;
    expect_refused(j, "landmarks[0].id = 5, expected 0 (ids are the positions in the list)");
    j = small_map_json();
    j["frames"][2]["number"] = 10;
    expect_refused(j, "frames[2].number = 10 repeats an earlier number");
}

TEST(StructuralMap, ChecksTheTriangleTagsItSkips) {
    Json j = small_map_json();
    j["triangle_surface_tags"] = Json::parse("[[0, 2], [1, 1]]");
    EXPECT_EQ(parse_structural_map(j.dump(), kName), small_map());
    j["triangle_surface_tags"] = Json::parse("[[2, 1]]");
    expect_refused(j, "triangle_surface_tags[0]: tag 2 is not a surface");
    j["triangle_surface_tags"] = Json::parse("[[0, 0]]");
    expect_refused(j, "triangle_surface_tags[0]: count 0, expected >= 1");
    j["triangle_surface_tags"] = Json::parse("[[0]]");
    expect_refused(j, "triangle_surface_tags[0]: expected [tag, count]");
}

TEST(StructuralMap, RefusesHostileSizesBeforeBuildingThem) {
    const test::TempDir dir;
    const std::string big = dir.file("big.json");
    test::write_bytes(big, "{");
    std::filesystem::resize_file(big, kMaxStructuralMapBytes + 1);  // sparse: no disk used
    try {
        read_structural_map(big);
        ADD_FAILURE() << "accepted a file over the size limit";
    } catch (const ParseError& e) {
        EXPECT_NE(std::string(e.what()).find("more than the 64 MiB"), std::string::npos)
            << e.what();
    }
    expect_refused_text(std::string(100'000, '['), "nesting deeper than 16 levels");
    std::string many = "[0";
    for (std::size_t i = 0; i < kMaxStructuralMapValues; ++i) many += ",0";
    expect_refused_text(many + "]", "more than 2000000 JSON values");
}

TEST(StructuralMap, CompartmentAtPrefersTheSmallestBoxContainingThePoint) {
    const StructuralMap map = small_map();
    EXPECT_EQ(compartment_at(map, {1, 1, 1}), 0);
    EXPECT_EQ(compartment_at(map, {3, 1, 1}), 1);
    EXPECT_EQ(compartment_at(map, {3.2, 0.2, 0.2}), 2);  // in the sump, nested in "fore"
    EXPECT_EQ(compartment_at(map, {2, 1, 1}), 0);        // shared wall, equal volumes: first
    EXPECT_EQ(compartment_at(map, {5, 1, 1}), std::nullopt);
    EXPECT_EQ(compartment_at(StructuralMap{}, {1, 1, 1}), std::nullopt);
}

TEST(StructuralMap, FindCompartmentById) {
    const StructuralMap map = small_map();
    ASSERT_NE(find_compartment(map, 2), nullptr);
    EXPECT_EQ(find_compartment(map, 2)->name, "sump");
    EXPECT_EQ(find_compartment(map, 3), nullptr);
    EXPECT_EQ(find_compartment(map, -1), nullptr);
}

TEST(StructuralMap, NearestFrameIsThePlaneNearestAlongItsAxis) {
    const StructuralMap map = small_map();
    EXPECT_EQ(nearest_frame(map, {0.9, 1, 1}), 10);
    EXPECT_EQ(nearest_frame(map, {1.1, -5, 9}), 11);  // height and breadth do not matter
    EXPECT_EQ(nearest_frame(map, {1.0, 1, 1}), 10);   // halfway: the first listed
    EXPECT_EQ(nearest_frame(map, {9.0, 1, 1}), 12);
    EXPECT_EQ(nearest_frame(StructuralMap{}, {0, 0, 0}), std::nullopt);
}

TEST(StructuralMap, NearestLongitudinalIsTheLineNearestAcrossIt) {
    const StructuralMap map = small_map();
    EXPECT_EQ(nearest_longitudinal(map, {3.0, 0.6, 0.5}), 1);
    EXPECT_EQ(nearest_longitudinal(map, {-40.0, 1.2, 0.1}), 2);  // x along the lines: ignored
    EXPECT_EQ(nearest_longitudinal(map, {1.0, 1.0, 5.0}), 1);    // equidistant: the first
    EXPECT_EQ(nearest_longitudinal(StructuralMap{}, {0, 0, 0}), std::nullopt);
}

}  // namespace
}  // namespace scantling::io
