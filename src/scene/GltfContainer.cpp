#include "scene/GltfContainer.h"

#include <algorithm>
#include <cctype>
#include <cstdint>
#include <filesystem>

namespace frugal::gltf {

namespace {

constexpr std::uint32_t kGlbMagic = 0x46546C67;   // "glTF", little-endian
constexpr std::uint32_t kChunkJson = 0x4E4F534A;  // "JSON"
constexpr std::uint32_t kChunkBin = 0x004E4942;   // "BIN\0"

// GLB fields are little-endian; assembled byte by byte so the host's order does not matter.
std::uint32_t readU32(std::string_view bytes, std::size_t offset) {
    std::uint32_t value = 0;
    for (std::size_t k = 0; k < 4; ++k)
        value |= std::uint32_t(static_cast<unsigned char>(bytes[offset + k])) << (8 * k);
    return value;
}

void checkNesting(std::string_view text) {
    int depth = 0;
    bool inString = false;
    for (std::size_t i = 0; i < text.size(); ++i) {
        const char c = text[i];
        if (inString) {
            if (c == '\\')
                ++i;
            else if (c == '"')
                inString = false;
        } else if (c == '"') {
            inString = true;
        } else if (c == '{' || c == '[') {
            if (++depth > kMaxJsonDepth) fail("JSON nested deeper than ", kMaxJsonDepth, " levels (at byte ", i, ")");
        } else if (c == '}' || c == ']') {
            --depth;
        }
    }
}

}  // namespace

bool isBinary(const std::string& path, std::string_view bytes) {
    std::string ext = std::filesystem::path(path).extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
    return ext == ".glb" || (bytes.size() >= 4 && bytes.substr(0, 4) == "glTF");
}

GlbParts splitGlb(std::string_view file) {
    if (file.size() < 12) fail("truncated GLB: ", file.size(), " bytes, the header alone needs 12");
    if (readU32(file, 0) != kGlbMagic) fail("not a binary glTF file (the first 4 bytes are not 'glTF')");
    const std::uint32_t version = readU32(file, 4);
    if (version != 2) fail("GLB container version ", version, ", frugal reads version 2");
    const std::uint32_t length = readU32(file, 8);
    if (length > file.size()) fail("truncated GLB: the header declares ", length, " bytes, the file has ", file.size());
    if (length < file.size()) fail("GLB header declares ", length, " bytes but the file has ", file.size());

    GlbParts parts;
    std::size_t offset = 12;
    int chunk = 0;
    for (; offset < length; ++chunk) {
        if (length - offset < 8)
            fail("truncated GLB: chunk ", chunk, " at byte ", offset, " needs an 8-byte header, ", length - offset,
                 " bytes remain");
        const std::uint32_t chunkLength = readU32(file, offset);
        const std::uint32_t type = readU32(file, offset + 4);
        if (chunkLength > length - offset - 8)
            fail("truncated GLB: chunk ", chunk, " at byte ", offset, " declares ", chunkLength, " bytes, ",
                 length - offset - 8, " remain");
        const std::string_view data = file.substr(offset + 8, chunkLength);
        if (chunk == 0) {
            if (type != kChunkJson) fail("GLB chunk 0 is not the JSON chunk (type 0x", std::hex, type, ")");
            parts.json = data;
        } else if (chunk == 1 && type == kChunkBin) {
            parts.bin = data;
            parts.hasBin = true;
        }
        // Other chunk types are allowed by the spec and ignored.
        offset += 8 + std::size_t(chunkLength);
    }
    if (chunk == 0) fail("GLB has no JSON chunk");
    parts.canonical = parts.json.size() % 4 == 0 && chunk == (parts.hasBin ? 2 : 1) &&
                      (!parts.hasBin || (parts.bin.size() % 4 == 0 && parts.bin.size() >= 4));
    return parts;
}

std::string canonicalGlb(const GlbParts& parts) {
    auto put32 = [](std::string& out, std::size_t v) {
        for (int k = 0; k < 4; ++k) out += char((v >> (8 * k)) & 0xFF);
    };
    const std::size_t jsonLength = (parts.json.size() + 3) / 4 * 4;
    const bool bin = parts.hasBin && !parts.bin.empty();
    const std::size_t binLength = bin ? (parts.bin.size() + 3) / 4 * 4 : 0;
    std::string out;
    out.reserve(12 + 8 + jsonLength + (bin ? 8 + binLength : 0));
    put32(out, kGlbMagic);
    put32(out, 2);
    put32(out, 12 + 8 + jsonLength + (bin ? 8 + binLength : 0));
    put32(out, jsonLength);
    put32(out, kChunkJson);
    out.append(parts.json);
    out.append(jsonLength - parts.json.size(), ' ');
    if (bin) {
        put32(out, binLength);
        put32(out, kChunkBin);
        out.append(parts.bin);
        out.append(binLength - parts.bin.size(), '\0');
    }
    return out;
}

Json parseJson(std::string_view text) {
    checkNesting(text);
    Json root;
    try {
        root = Json::parse(text.begin(), text.end());
    } catch (const Json::exception& e) {
        std::string what = e.what();
        // "[json.exception.parse_error.101] parse error at line 1, ..." → "parse error at line 1, ..."
        const std::size_t close = what.find("] ");
        if (what.rfind("[json.exception.", 0) == 0 && close != std::string::npos) what.erase(0, close + 2);
        fail("invalid JSON: ", oneLine(what));
    }
    if (!root.is_object()) fail("the JSON root is ", describe(root), ", expected an object");
    return root;
}

}  // namespace frugal::gltf
