// Makes the seed files scripts/fuzz starts the corpora from, the same on every run:
//
//   fuzz_seeds gltf IN.gltf OUT.gltf [OUT.glb]
//       IN with every buffer and image it finds next to it embedded as a data URI, so that the
//       fuzzers, which read no files, get its data; and, when buffer 0 was such a file, the same
//       scene as a .glb with buffer 0 in the BIN chunk. A file that is not a JSON object (the
//       broken ones are seeds too) is copied as it is.
//   fuzz_seeds png DIR
//       A small image in every format frugal's PNG encoder writes (1 to 4 channels, 8 and 16 bits).
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "io/ImageIO.h"

namespace {

using Json = nlohmann::json;
namespace fs = std::filesystem;

std::optional<std::string> readAll(const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) return std::nullopt;
    return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

bool writeAll(const fs::path& path, const std::string& bytes) {
    std::ofstream out(path, std::ios::binary);
    out.write(bytes.data(), std::streamsize(bytes.size()));
    return bool(out);
}

std::string base64(const std::string& bytes) {
    static const char kDigits[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    std::string out;
    for (std::size_t i = 0; i < bytes.size(); i += 3) {
        std::uint32_t group = std::uint32_t(static_cast<unsigned char>(bytes[i])) << 16;
        if (i + 1 < bytes.size()) group |= std::uint32_t(static_cast<unsigned char>(bytes[i + 1])) << 8;
        if (i + 2 < bytes.size()) group |= std::uint32_t(static_cast<unsigned char>(bytes[i + 2]));
        for (std::size_t k = 0; k < 4; ++k) out += i + k <= bytes.size() ? kDigits[(group >> (18 - 6 * k)) & 63] : '=';
    }
    return out;
}

const char* mimeType(const std::string& bytes) {
    if (bytes.rfind("\x89PNG", 0) == 0) return "image/png";
    if (bytes.rfind("\xFF\xD8", 0) == 0) return "image/jpeg";
    return "application/octet-stream";
}

// The file a URI names next to the .gltf, if it is one (not a data URI, present).
std::optional<std::string> uriFile(const Json& item, const fs::path& dir) {
    if (!item.is_object() || !item.contains("uri") || !item["uri"].is_string()) return std::nullopt;
    const std::string& uri = item["uri"].get_ref<const std::string&>();
    if (uri.rfind("data:", 0) == 0) return std::nullopt;
    return readAll(dir / uri);
}

void packGlb(std::string& out, const std::string& json, const std::string& bin) {
    const auto put32 = [&out](std::size_t v) {
        for (int k = 0; k < 4; ++k) out += char((v >> (8 * k)) & 0xFF);
    };
    const std::size_t jsonLength = (json.size() + 3) / 4 * 4, binLength = (bin.size() + 3) / 4 * 4;
    put32(0x46546C67);  // "glTF"
    put32(2);
    put32(12 + 8 + jsonLength + 8 + binLength);
    put32(jsonLength);
    put32(0x4E4F534A);  // "JSON"
    out += json + std::string(jsonLength - json.size(), ' ');
    put32(binLength);
    put32(0x004E4942);  // "BIN\0"
    out += bin + std::string(binLength - bin.size(), '\0');
}

int gltfSeeds(const fs::path& in, const fs::path& outGltf, const fs::path* outGlb) {
    const std::optional<std::string> text = readAll(in);
    if (!text) {
        std::fprintf(stderr, "fuzz_seeds: cannot read %s\n", in.c_str());
        return 1;
    }
    Json root = Json::parse(*text, nullptr, /*allow_exceptions=*/false);
    if (!root.is_object()) return writeAll(outGltf, *text) ? 0 : 1;

    std::optional<std::string> bin;  // buffer 0, when it was a file
    for (const char* key : {"buffers", "images"}) {
        if (!root.contains(key) || !root[key].is_array()) continue;
        Json& items = root[key];
        for (std::size_t i = 0; i < items.size(); ++i) {
            const std::optional<std::string> bytes = uriFile(items[i], in.parent_path());
            if (!bytes) continue;
            const bool buffer = std::string(key) == "buffers";
            if (buffer && i == 0) bin = bytes;
            items[i]["uri"] = std::string("data:") + (buffer ? "application/octet-stream" : mimeType(*bytes)) +
                              ";base64," + base64(*bytes);
        }
    }
    if (!writeAll(outGltf, root.dump())) return 1;
    if (!outGlb || !bin) return 0;
    root["buffers"][0].erase("uri");
    std::string glb;
    packGlb(glb, root.dump(), *bin);
    return writeAll(*outGlb, glb) ? 0 : 1;
}

int pngSeeds(const fs::path& dir) {
    constexpr int kWidth = 3, kHeight = 2;
    for (int channels = 1; channels <= 4; ++channels)
        for (int bitDepth : {8, 16}) {
            std::vector<std::uint8_t> rows(std::size_t(kWidth * kHeight * channels * bitDepth / 8));
            for (std::size_t i = 0; i < rows.size(); ++i) rows[i] = std::uint8_t(37 * i + 11);
            const frugal::Result<frugal::Bytes> png =
                frugal::encodePng(kWidth, kHeight, channels, bitDepth, rows.data());
            const fs::path path = dir / ("c" + std::to_string(channels) + "-" + std::to_string(bitDepth) + ".png");
            if (!png || !writeAll(path, std::string(png->begin(), png->end()))) return 1;
        }
    return 0;
}

}  // namespace

int main(int argc, char** argv) {
    const std::vector<std::string> args(argv + 1, argv + argc);
    if (args.size() >= 3 && args.size() <= 4 && args[0] == "gltf") {
        const fs::path glb = args.size() == 4 ? fs::path(args[3]) : fs::path();
        return gltfSeeds(args[1], args[2], args.size() == 4 ? &glb : nullptr);
    }
    if (args.size() == 2 && args[0] == "png") return pngSeeds(args[1]);
    std::fprintf(stderr, "usage: fuzz_seeds gltf IN.gltf OUT.gltf [OUT.glb] | fuzz_seeds png DIR\n");
    return 2;
}
