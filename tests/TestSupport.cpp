#include "TestSupport.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <iterator>
#include <sstream>

#include <sys/wait.h>

#include <glm/gtc/matrix_transform.hpp>

namespace frugal::test {

std::string base64(const std::string& bytes) {
    static const char* kDigits = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    std::string out;
    for (std::size_t i = 0; i < bytes.size(); i += 3) {
        std::uint32_t v = std::uint32_t(std::uint8_t(bytes[i])) << 16;
        if (i + 1 < bytes.size()) v |= std::uint32_t(std::uint8_t(bytes[i + 1])) << 8;
        if (i + 2 < bytes.size()) v |= std::uint8_t(bytes[i + 2]);
        out += kDigits[(v >> 18) & 63];
        out += kDigits[(v >> 12) & 63];
        out += i + 1 < bytes.size() ? kDigits[(v >> 6) & 63] : '=';
        out += i + 2 < bytes.size() ? kDigits[v & 63] : '=';
    }
    return out;
}

namespace fs = std::filesystem;

fs::path outputDir() {
    fs::path dir = FRUGAL_TEST_OUTPUT_DIR;
    fs::create_directories(dir);
    return dir;
}

fs::path freshDir(const std::string& name) {
    fs::path dir = outputDir() / name;
    fs::remove_all(dir);
    fs::create_directories(dir);
    return dir;
}

void writeFile(const fs::path& path, const std::string& text) {
    if (path.has_parent_path()) fs::create_directories(path.parent_path());
    std::ofstream(path, std::ios::binary) << text;
}

std::string readAll(const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

std::vector<std::string> filesIn(const fs::path& dir) {
    std::vector<std::string> names;
    for (const auto& entry : fs::directory_iterator(dir)) names.push_back(entry.path().filename().string());
    std::sort(names.begin(), names.end());
    return names;
}

std::vector<std::string> lines(const std::string& text) {
    std::vector<std::string> out;
    std::stringstream in(text);
    for (std::string line; std::getline(in, line);) out.push_back(line);
    return out;
}

std::vector<std::string> csvFields(const std::string& line) {
    std::vector<std::string> fields;
    std::stringstream in(line);
    for (std::string field; std::getline(in, field, ',');) fields.push_back(field);
    if (!line.empty() && line.back() == ',') fields.emplace_back();
    return fields;
}

std::string joined(const std::vector<std::string>& args) {
    std::string line;
    for (const std::string& a : args) line += (line.empty() ? "" : " ") + a;
    return line;
}

std::string shellQuoted(const std::string& text) {
    std::string quoted = "'";
    for (char c : text) quoted += c == '\'' ? std::string("'\\''") : std::string(1, c);
    return quoted + "'";
}

bool strictSkips() {
    const char* strict = std::getenv("FRUGAL_TEST_STRICT");
    return strict != nullptr && std::string(strict) == "1";
}

void skipOrFail(const char* what, const std::string& message) {
    if (strictSkips())
        GTEST_FAIL() << what << ", and FRUGAL_TEST_STRICT=1 forbids skipping: " << message;
    else
        GTEST_SKIP() << what << ": " << message;
}

bool haveGnuplot() { return std::system("command -v gnuplot > /dev/null 2>&1") == 0; }

int runGnuplot(const fs::path& script, std::string& messages) {
    const fs::path log = script.parent_path() / "gnuplot.log";
    const int status = std::system(("gnuplot " + shellQuoted(script.string()) + " > " + shellQuoted(log.string()) +
                                    " 2>&1").c_str());
    messages = readAll(log);
    return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + (WIFSIGNALED(status) ? WTERMSIG(status) : 0);
}

std::vector<std::string> CliRun::errLines() const { return lines(err); }

const char* binaryFor(const std::vector<std::string>& args) {
    const auto lab = [](const std::string& name) {
        return std::find(kLabCommands.begin(), kLabCommands.end(), name) != kLabCommands.end();
    };
    if (!args.empty() && (lab(args[0]) || (args[0] == "help" && args.size() > 1 && lab(args[1]))))
        return FRUGAL_LAB_CLI;
    return FRUGAL_CLI;
}

namespace {
CliRun runBinary(const char* binary, const fs::path& dir, const std::vector<std::string>& args, const std::string& env) {
    // (An ostringstream, not string +: GCC 12 -O3 reports a false -Wrestrict on the latter.)
    std::ostringstream line;
    line << "cd " << shellQuoted(dir.string()) << " && " << env << " " << shellQuoted(binary);
    for (const std::string& a : args) line << " " << shellQuoted(a);
    line << " >stdout.txt 2>stderr.txt";
    const std::string command = line.str();
    CliRun run;
    const int raw = std::system(command.c_str());
    run.status = WIFEXITED(raw) ? WEXITSTATUS(raw) : 128 + WTERMSIG(raw);
    run.out = readAll(dir / "stdout.txt");
    run.err = readAll(dir / "stderr.txt");
    fs::remove(dir / "stdout.txt");
    fs::remove(dir / "stderr.txt");
    return run;
}
}  // namespace

CliRun runFrugal(const fs::path& dir, const std::vector<std::string>& args, const std::string& env) {
    return runBinary(binaryFor(args), dir, args, env);
}

CliRun runLab(const fs::path& dir, const std::vector<std::string>& args, const std::string& env) {
    return runBinary(FRUGAL_LAB_CLI, dir, args, env);
}

Mesh looseTriangles(const std::vector<glm::vec3>& positions) {
    Mesh mesh;
    mesh.name = "triangles";
    mesh.positions = positions;
    mesh.normals.assign(positions.size(), glm::vec3(0.0f, 0.0f, 1.0f));
    for (std::uint32_t i = 0; i < std::uint32_t(positions.size()); ++i) mesh.indices.push_back(i);
    return mesh;
}

void addAlpha(Scene& scene) {
    for (std::size_t i = 0; i < scene.meshes.size(); ++i) {
        if (i % 3 == 2) continue;
        Mesh& mesh = scene.meshes[i];
        Material material = mesh.material >= 0 ? scene.materials[std::size_t(mesh.material)] : Material{};
        material.name += i % 3 == 0 ? " (blended)" : " (masked)";
        material.alphaMode = i % 3 == 0 ? AlphaMode::Blend : AlphaMode::Mask;
        material.alphaCutoff = 0.5f;
        if (mesh.colors.empty()) mesh.colors.assign(mesh.positions.size(), glm::vec4(1.0f));
        for (std::size_t v = 0; v < mesh.positions.size(); ++v) {
            const glm::vec3 p = mesh.positions[v];
            mesh.colors[v].a *= 0.5f + 0.45f * std::sin(7.0f * p.x + 5.0f * p.y + 3.0f * p.z + float(v));
        }
        mesh.material = int(scene.materials.size());
        scene.materials.push_back(std::move(material));
    }
}

Scene oneMeshScene(Mesh mesh, const Material& material) {
    Scene scene;
    mesh.material = 0;
    scene.meshes.push_back(std::move(mesh));
    scene.materials.push_back(material);
    Node node;
    node.meshes = {0};
    scene.nodes.push_back(node);
    scene.roots = {0};
    scene.buildInstances();
    return scene;
}

int addCameraNode(Scene& scene, SceneCamera camera, const glm::vec3& position) {
    Node node;
    node.translation = position;
    node.camera = int(scene.cameras.size());
    camera.node = int(scene.nodes.size());
    scene.roots.push_back(camera.node);
    scene.nodes.push_back(node);
    scene.cameras.push_back(camera);
    return node.camera;
}

std::string radianceFile(int width, int height, const std::vector<float>& rgb, bool rle) {
    std::string out =
        "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y " + std::to_string(height) + " +X " + std::to_string(width) + "\n";
    std::vector<std::uint8_t> scan(std::size_t(width) * 4);
    for (int y = 0; y < height; ++y) {
        for (int x = 0; x < width; ++x) {
            const float* p = &rgb[(std::size_t(y) * std::size_t(width) + std::size_t(x)) * 3];
            const float m = std::max(p[0], std::max(p[1], p[2]));
            std::uint8_t* e = &scan[std::size_t(x) * 4];
            if (m < 1e-32f) {
                e[0] = e[1] = e[2] = e[3] = 0;
                continue;
            }
            int exponent = 0;
            const float mantissa = std::frexp(m, &exponent);
            const float scale = mantissa * 256.0f / m;
            for (int c = 0; c < 3; ++c) e[c] = std::uint8_t(std::min(255.0f, std::floor(p[c] * scale)));
            e[3] = std::uint8_t(exponent + 128);
        }
        if (!rle) {
            out.append(reinterpret_cast<const char*>(scan.data()), scan.size());
            continue;
        }
        out += char(2);
        out += char(2);
        out += char(width >> 8);
        out += char(width & 255);
        for (int c = 0; c < 4; ++c) {  // runs where 3 or more bytes repeat, literal stretches between
            int x = 0;
            while (x < width) {
                int run = 1;
                while (x + run < width && run < 127 &&
                       scan[std::size_t(x + run) * 4 + c] == scan[std::size_t(x) * 4 + c])
                    ++run;
                if (run >= 3) {
                    out += char(128 + run);
                    out += char(scan[std::size_t(x) * 4 + c]);
                    x += run;
                    continue;
                }
                int literal = 0;
                while (x + literal < width && literal < 128) {
                    const int at = x + literal;
                    if (at + 2 < width && scan[std::size_t(at) * 4 + c] == scan[std::size_t(at + 1) * 4 + c] &&
                        scan[std::size_t(at) * 4 + c] == scan[std::size_t(at + 2) * 4 + c])
                        break;
                    ++literal;
                }
                out += char(literal);
                for (int i = 0; i < literal; ++i) out += char(scan[std::size_t(x + i) * 4 + c]);
                x += literal;
            }
        }
    }
    return out;
}

std::vector<float> testSky(int width, int height) {
    std::vector<float> rgb(std::size_t(width) * std::size_t(height) * 3);
    const glm::vec3 sun = glm::normalize(glm::vec3(0.5f, 0.7f, 0.3f));
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            const float theta = (float(y) + 0.5f) / float(height) * 3.14159265f;
            const float phi = ((float(x) + 0.5f) / float(width) - 0.5f) * 2.0f * 3.14159265f;
            const glm::vec3 d(std::sin(theta) * std::cos(phi), std::cos(theta), std::sin(theta) * std::sin(phi));
            glm::vec3 c =
                d.y > 0.0f ? glm::vec3(0.3f, 0.5f, 1.0f) * (0.4f + 0.6f * d.y) : glm::vec3(0.25f, 0.2f, 0.15f);
            if (glm::dot(d, sun) > 0.995f) c += glm::vec3(40.0f, 38.0f, 30.0f);
            for (int k = 0; k < 3; ++k)
                rgb[(std::size_t(y) * std::size_t(width) + std::size_t(x)) * 3 + std::size_t(k)] = c[k];
        }
    return rgb;
}

Scene morphingScene(std::vector<float> still) {
    Scene scene;
    scene.source = "morphing test scene";
    Material single;
    single.baseColorFactor = {0.9f, 0.6f, 0.3f, 1.0f};
    single.metallicFactor = 0.0f;
    single.roughnessFactor = 0.5f;
    Material both = single;
    both.baseColorFactor = {0.3f, 0.7f, 0.9f, 1.0f};
    both.doubleSided = true;
    scene.materials = {single, both};
    // A UV sphere of radius 1.
    Mesh sphere;
    const int rings = 16, segments = 24;
    for (int i = 0; i <= rings; ++i)
        for (int j = 0; j <= segments; ++j) {
            const float theta = 3.14159265f * float(i) / float(rings), phi = 6.2831853f * float(j) / float(segments);
            const glm::vec3 n(std::sin(theta) * std::cos(phi), std::cos(theta), std::sin(theta) * std::sin(phi));
            sphere.positions.push_back(n);
            sphere.normals.push_back(n);
        }
    for (int i = 0; i < rings; ++i)
        for (int j = 0; j < segments; ++j) {
            const std::uint32_t a = std::uint32_t(i * (segments + 1) + j), b = a + std::uint32_t(segments + 1);
            sphere.indices.insert(sphere.indices.end(), {a, a + 1, b, a + 1, b + 1, b});
        }
    sphere.material = 0;
    Mesh morphing = sphere;
    morphing.material = 1;
    MorphTarget inflate, wave;
    for (std::size_t v = 0; v < sphere.positions.size(); ++v) {
        const glm::vec3 p = sphere.positions[v];
        inflate.positions.push_back(0.4f * p * (0.5f + 0.5f * p.y));
        inflate.normals.push_back(glm::vec3(0.0f, 0.3f * p.y, 0.0f));
        wave.positions.push_back(glm::vec3(0.6f * std::sin(3.0f * p.y), 0.0f, 0.2f * std::cos(2.0f * p.x)));
    }
    morphing.targets = {inflate, wave};
    EXPECT_TRUE(scene.addMesh(sphere));
    EXPECT_TRUE(scene.addMesh(morphing));
    const auto at = [](float x, float y, float z, float s) {
        return glm::scale(glm::translate(glm::mat4(1.0f), glm::vec3(x, y, z)), glm::vec3(s));
    };
    const Result<int> animated = scene.addInstance(1, at(0.0f, 0.0f, 0.0f, 0.5f), "animated");
    const Result<int> fixed = scene.addInstance(1, at(2.2f, 0.5f, -1.0f, 0.4f), "still");
    EXPECT_TRUE(animated && fixed);
    if (fixed) scene.nodes[std::size_t(*fixed)].weights = std::move(still);
    for (const glm::vec3& c :
         {glm::vec3(-2.0f, 0.0f, -2.0f), glm::vec3(0.3f, -0.2f, -3.0f), glm::vec3(1.5f, -1.0f, 1.0f)})
        EXPECT_TRUE(scene.addInstance(0, at(c.x, c.y, c.z, 0.6f)));
    if (animated) {
        AnimChannel channel;
        channel.node = *animated;
        channel.path = AnimPath::Weights;
        channel.interpolation = Interp::Linear;
        channel.times = {0.0f, 1.0f, 2.0f, 3.0f, 4.0f};
        channel.weights = {0.0f, 0.0f, -1.0f, 10.0f, 1.0f, -1.0f, 10.0f, 0.5f, 0.3f, 0.3f};
        channel.weightCount = 2;
        scene.animations.push_back(Animation{"weights", {channel}});
    }
    scene.buildInstances();
    return scene;
}

Scene pointsLinesScene() {
    Scene scene = morphingScene();  // for its spheres: the morphing meshes and instances go
    scene.source = "points and lines test scene";
    scene.animations.clear();
    scene.meshes.resize(1);
    for (Node& node : scene.nodes) std::erase_if(node.meshes, [](int mesh) { return mesh != 0; });
    Material bare;
    bare.baseColorFactor = {0.2f, 0.9f, 0.4f, 1.0f};
    bare.emissiveFactor = {0.3f, 0.0f, 0.2f};
    scene.materials.push_back(bare);
    const int bareMaterial = int(scene.materials.size()) - 1;

    Mesh ring;
    ring.topology = Topology::Lines;
    ring.material = 0;
    constexpr std::uint32_t kSegments = 48;
    for (std::uint32_t i = 0; i < kSegments; ++i) {
        const float a = 6.2831853f * float(i) / float(kSegments);
        ring.positions.push_back({1.6f * std::cos(a), 0.4f * std::sin(3.0f * a), 1.6f * std::sin(a)});
        ring.normals.push_back(glm::normalize(glm::vec3(std::cos(a), 0.5f, std::sin(a))));
        ring.indices.insert(ring.indices.end(), {i, (i + 1) % kSegments});
    }
    Mesh grid;
    grid.topology = Topology::Points;
    grid.material = bareMaterial;
    for (int y = 0; y < 20; ++y)
        for (int x = 0; x < 20; ++x) {
            grid.indices.push_back(std::uint32_t(grid.positions.size()));
            grid.positions.push_back({-3.0f + 0.3f * float(x), -2.0f + 0.22f * float(y), -2.6f});
        }
    Mesh strip;
    strip.topology = Topology::Lines;
    strip.material = bareMaterial;
    for (int i = 0; i < 12; ++i) {
        strip.positions.push_back({-2.5f + 0.45f * float(i), 1.2f * std::sin(1.3f * float(i)), 1.8f});
        if (i % 4 == 1) strip.positions.push_back(strip.positions.back());  // a zero-length segment
    }
    for (std::uint32_t v = 0; v + 1 < strip.positions.size(); ++v)
        strip.indices.insert(strip.indices.end(), {v, v + 1});
    const Result<int> ringMesh = scene.addMesh(ring), gridMesh = scene.addMesh(grid), stripMesh = scene.addMesh(strip);
    EXPECT_TRUE(ringMesh && gridMesh && stripMesh);
    if (!ringMesh || !gridMesh || !stripMesh) return scene;
    const Result<int> turning = scene.addInstance(*ringMesh, glm::mat4(1.0f), "ring");
    EXPECT_TRUE(turning && scene.addInstance(*gridMesh, glm::mat4(1.0f), "grid") &&
                scene.addInstance(*stripMesh, glm::mat4(1.0f), "strip"));
    if (turning) {
        AnimChannel spin;
        spin.node = *turning;
        spin.path = AnimPath::Rotation;
        spin.interpolation = Interp::Linear;
        spin.times = {0.0f, 2.0f, 4.0f};
        for (const float angle : {0.0f, 1.5f, 3.0f}) {
            const glm::quat q = glm::angleAxis(angle, glm::normalize(glm::vec3(0.3f, 1.0f, 0.2f)));
            spin.values.push_back({q.x, q.y, q.z, q.w});
        }
        AnimChannel sweep;
        sweep.node = *turning;
        sweep.path = AnimPath::Translation;
        sweep.times = {0.0f, 2.0f, 4.0f};
        sweep.values = {{-1.0f, 0.0f, -1.5f, 0.0f}, {1.0f, 0.3f, 0.0f, 0.0f}, {0.5f, -0.5f, -2.0f, 0.0f}};
        scene.animations.push_back(Animation{"ring", {spin, sweep}});
    }
    scene.buildInstances();
    return scene;
}

Scene skinnedScene(float topScale, bool affine) {
    Scene scene;
    scene.source = "skinned test scene";
    Material material;
    material.baseColorFactor = {0.8f, 0.5f, 0.4f, 1.0f};
    material.metallicFactor = 0.0f;
    material.roughnessFactor = 0.6f;
    material.doubleSided = true;
    scene.materials = {material};
    Mesh tube;
    const int rings = 24, segments = 16;
    Mesh::Influences influences;
    for (int i = 0; i <= rings; ++i)
        for (int j = 0; j <= segments; ++j) {
            const float h = 2.0f * float(i) / float(rings), phi = 6.2831853f * float(j) / float(segments);
            const glm::vec3 n(std::cos(phi), 0.0f, std::sin(phi));
            tube.positions.push_back(glm::vec3(0.0f, h, 0.0f) + 0.3f * n);
            tube.normals.push_back(n);
            // Root below 1, the middle around 1, the top above 1.
            const float mid = std::max(0.0f, 1.0f - std::abs(h - 1.0f));
            const float scale = affine ? 1.0f : (j % 2 == 0 ? 0.7f : 1.3f);
            influences.joints.push_back(glm::uvec4(0, 1, 2, 0));
            influences.weights.push_back(
                scale * glm::vec4(h < 1.0f ? 1.0f - mid : 0.0f, mid, h >= 1.0f ? 1.0f - mid : 0.0f, 0.0f));
        }
    for (int i = 0; i < rings; ++i)
        for (int j = 0; j < segments; ++j) {
            const std::uint32_t a = std::uint32_t(i * (segments + 1) + j), b = a + std::uint32_t(segments + 1);
            tube.indices.insert(tube.indices.end(), {a, b, a + 1, a + 1, b, b + 1});
        }
    tube.influences = {influences};
    tube.material = 0;
    Mesh ball = morphingScene().meshes[0];  // the unit sphere
    ball.material = 0;
    EXPECT_TRUE(scene.addMesh(tube));
    EXPECT_TRUE(scene.addMesh(ball));
    // The joints: root at the origin, middle 1 above it, top 1 above that.
    Node root, middle, top, skinned;
    root.name = "root";
    middle.name = "middle";
    middle.translation = {0.0f, 1.0f, 0.0f};
    top.name = "top";
    top.translation = {0.0f, 1.0f, 0.0f};
    scene.nodes = {root, middle, top};
    scene.nodes[0].children = {1};
    scene.nodes[1].parent = 0;
    scene.nodes[1].children = {2};
    scene.nodes[2].parent = 1;
    skinned.name = "skinned";
    skinned.translation = {1.5f, -0.5f, 0.0f};  // its own transform: the joints place the tube
    skinned.meshes = {0};
    skinned.skin = 0;
    scene.nodes.push_back(skinned);
    scene.roots = {0, 3};
    Skin skin;
    skin.joints = {0, 1, 2};
    for (float y : {0.0f, 1.0f, 2.0f})
        skin.inverseBindMatrices.push_back(glm::translate(glm::mat4(1.0f), glm::vec3(0.0f, -y, 0.0f)));
    scene.skins = {skin};
    for (const glm::vec3& c : {glm::vec3(-1.5f, 0.0f, -1.0f), glm::vec3(1.0f, 1.5f, -2.0f)}) {
        const glm::mat4 place = glm::scale(glm::translate(glm::mat4(1.0f), c), glm::vec3(0.5f));
        EXPECT_TRUE(scene.addInstance(1, place));
    }
    AnimChannel turn;
    turn.node = 1;
    turn.path = AnimPath::Rotation;
    turn.times = {0.0f, 2.0f, 4.0f};
    turn.values = {{0, 0, 0, 1}, {0, 0, 0.8660254f, 0.5f}, {0, 0, 0, 1}};  // about z: 0, 120, 0 degrees
    AnimChannel grow;
    grow.node = 2;
    grow.path = AnimPath::Scale;
    grow.times = {0.0f, 2.0f, 4.0f};
    grow.values = {{topScale, topScale, topScale, 0}, {1, 1, 1, 0}, {topScale, topScale, topScale, 0}};
    scene.animations.push_back(Animation{"bend", {turn, grow}});
    scene.buildInstances();
    return scene;
}

}  // namespace frugal::test
