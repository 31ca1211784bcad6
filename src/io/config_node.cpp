#include <scantling/io/config_node.hpp>

#include <yaml-cpp/eventhandler.h>
#include <yaml-cpp/yaml.h>

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <optional>
#include <sstream>
#include <string>
#include <system_error>

#include <scantling/core/error.hpp>

namespace scantling::io {
namespace {

FileLocation location_of(const YAML::Mark& mark) {
    // yaml-cpp marks are 0-based; a null mark (-1) has no position.
    if (mark.is_null()) return {};
    return FileLocation{
        .byte_offset = std::nullopt, .line = mark.line + 1, .column = mark.column + 1};
}

void set_position(ConfigNode& node, const YAML::Mark& mark) {
    const FileLocation location = location_of(mark);
    node.line = location.line.value_or(0);
    node.column = location.column.value_or(0);
}

/// "4 MiB" for a whole number of MiB, else the bytes.
std::string size_text(std::size_t bytes) {
    constexpr std::size_t kMiB = std::size_t{1} << 20;
    if (bytes % kMiB == 0) return std::to_string(bytes / kMiB) + " MiB";
    return std::to_string(bytes) + " bytes";
}

/// `bytes`: the size when known (a file that grows while read is only known to be larger).
[[noreturn]] void refuse_size(const std::string& file, std::optional<std::uintmax_t> bytes,
                              const YamlLimits& limits) {
    const std::string size = bytes ? std::to_string(*bytes) + " bytes" : "the text";
    throw ParseError(file, FileLocation{},
                     size + " is more than the " + size_text(limits.max_bytes) +
                         " a YAML config or scenario may have; refusing to parse it");
}

/// yaml-cpp's message, except for its nesting guard: its parser recurses once per level and
/// stops at 2000 levels (before the stack runs out) with the bare message "bad file".
std::string yaml_cpp_message(const YAML::Exception& e) {
    if (e.msg != YAML::ErrorMsg::BAD_FILE) return e.msg;
    return "nesting deeper than 2000 levels (yaml-cpp's limit; a config nests a few levels)";
}

/// Converts a yaml-cpp tree into ConfigNodes, expanding aliases, within `limits`: the node
/// count is checked before each node is made, so memory stays bounded by max_nodes.
class Converter {
  public:
    Converter(const std::string& file, const YamlLimits& limits) : file_(file), limits_(limits) {}

    ConfigNode convert(const YAML::Node& yaml, int depth) {
        count(yaml, depth);
        ConfigNode node;
        node.file = file_;
        set_position(node, yaml.Mark());
        switch (yaml.Type()) {
            case YAML::NodeType::Scalar:
                node.kind = ConfigNode::Kind::kScalar;
                node.scalar = yaml.Scalar();
                break;
            case YAML::NodeType::Sequence:
                node.kind = ConfigNode::Kind::kSequence;
                for (const auto& item : yaml) node.sequence.push_back(convert(item, depth + 1));
                break;
            case YAML::NodeType::Map:
                node.kind = ConfigNode::Kind::kMap;
                convert_map(yaml, depth, node);
                break;
            default:
                node.kind = ConfigNode::Kind::kNull;
        }
        return node;
    }

  private:
    void count(const YAML::Node& yaml, int depth) {
        if (depth > limits_.max_depth) {
            throw ParseError(file_, location_of(yaml.Mark()),
                             "nesting deeper than " + std::to_string(limits_.max_depth) +
                                 " levels (a recursive alias?)");
        }
        if (++nodes_ > limits_.max_nodes) {
            throw ParseError(file_, location_of(yaml.Mark()),
                             "the document expands to more than " +
                                 std::to_string(limits_.max_nodes) +
                                 " nodes (each use of an alias counts its whole subtree); "
                                 "refusing a possible alias bomb");
        }
    }

    void convert_map(const YAML::Node& yaml, int depth, ConfigNode& node) {
        for (const auto& entry : yaml) {
            const YAML::Mark key_mark = entry.first.Mark();
            if (!entry.first.IsScalar()) {
                throw ParseError(file_, location_of(key_mark), "map keys must be plain scalars");
            }
            const std::string key = entry.first.Scalar();
            if (node.find(key) != nullptr) {
                throw ParseError(file_, location_of(key_mark), "duplicate key '" + key + "'");
            }
            ConfigNode value = convert(entry.second, depth + 1);
            // The key's position is what a reader looks for, and null values have no mark.
            set_position(value, key_mark);
            node.map.emplace_back(key, std::move(value));
        }
    }

    const std::string& file_;
    const YamlLimits& limits_;
    std::size_t nodes_ = 0;
};

/// The bytes of `path`, refusing a file over limits.max_bytes before reading it (and while
/// reading it, should it grow meanwhile).
std::string read_bounded(const std::string& path, const YamlLimits& limits) {
    std::error_code ec;
    const std::uintmax_t size = std::filesystem::file_size(path, ec);
    if (!ec && size > limits.max_bytes) refuse_size(path, size, limits);
    std::ifstream in(path, std::ios::binary);
    if (!in.is_open()) throw FileError(path, "cannot open file for reading");
    constexpr std::size_t kChunkBytes = std::size_t{1} << 16;
    std::string text;
    while (in && text.size() <= limits.max_bytes) {
        const std::size_t old_size = text.size();
        text.resize(old_size + kChunkBytes);
        in.read(text.data() + old_size, static_cast<std::streamsize>(kChunkBytes));
        text.resize(old_size + static_cast<std::size_t>(in.gcount()));
    }
    if (in.bad()) throw FileError(path, "read failed");
    if (text.size() > limits.max_bytes) refuse_size(path, std::nullopt, limits);
    return text;
}

}  // namespace

ConfigNode::ConfigNode() = default;

const ConfigNode* ConfigNode::find(std::string_view key) const {
    for (const auto& [name, value] : map) {
        if (name == key) return &value;
    }
    return nullptr;
}

std::string describe_kind(const ConfigNode& node) {
    switch (node.kind) {
        case ConfigNode::Kind::kScalar:
            return "'" + node.scalar + "'";
        case ConfigNode::Kind::kSequence:
            return "a sequence";
        case ConfigNode::Kind::kMap:
            return "a map";
        default:
            return "an empty value";
    }
}

/// Consumes parser events without building nodes: only the document count matters.
struct DocumentCounter : YAML::EventHandler {
    void OnDocumentStart(const YAML::Mark&) override {}
    void OnDocumentEnd() override {}
    void OnNull(const YAML::Mark&, YAML::anchor_t) override {}
    void OnAlias(const YAML::Mark&, YAML::anchor_t) override {}
    void OnScalar(const YAML::Mark&, const std::string&, YAML::anchor_t,
                  const std::string&) override {}
    void OnSequenceStart(const YAML::Mark&, const std::string&, YAML::anchor_t,
                         YAML::EmitterStyle::value) override {}
    void OnSequenceEnd() override {}
    void OnMapStart(const YAML::Mark&, const std::string&, YAML::anchor_t,
                    YAML::EmitterStyle::value) override {}
    void OnMapEnd() override {}
};

/// Documents in `text`, counting at most two. Not YAML::LoadAll: yaml-cpp 0.7 yields endless
/// empty documents for a stray top-level ',' (found by the config fuzzer), so the count is capped.
int count_documents(const std::string& text) {
    std::istringstream in(text);
    YAML::Parser parser(in);
    DocumentCounter counter;
    int documents = 0;
    while (documents < 2 && parser.HandleNextDocument(counter)) ++documents;
    return documents;
}

ConfigNode parse_yaml_string(const std::string& text, const std::string& name,
                             const YamlLimits& limits) {
    if (text.size() > limits.max_bytes) refuse_size(name, text.size(), limits);
    YAML::Node document;
    try {
        const int documents = count_documents(text);
        if (documents == 0) {
            ConfigNode empty;
            empty.file = name;
            return empty;
        }
        if (documents > 1) {
            throw ParseError(name, FileLocation{},
                             "expected one YAML document, found more (a '---' separator or a "
                             "stray character at the top level)");
        }
        document = YAML::Load(text);
    } catch (const YAML::Exception& e) {
        throw ParseError(name, location_of(e.mark), yaml_cpp_message(e));
    }
    return Converter(name, limits).convert(document, 0);
}

ConfigNode parse_yaml_file(const std::string& path, const YamlLimits& limits) {
    std::error_code ec;
    if (!std::filesystem::is_regular_file(path, ec)) {
        throw FileError(path,
                        std::filesystem::exists(path, ec) ? "not a regular file" : "no such file");
    }
    return parse_yaml_string(read_bounded(path, limits), path, limits);
}

}  // namespace scantling::io
