// Built-in procedural scenes. They use the same model as loaded files (nodes, TRS animation,
// materials), so every later module treats them exactly like a glTF scene.
//
//   builtin:dominoes?polygons=804&static=0.5544&floor=0
//       A serpentine field of dominoes that fall one after another. One domino is a box of 6 quads
//       (12 triangles), so polygons/6 dominoes. At every frame after the first, exactly
//       k = round((1 − static) · dominoes) dominoes change pose (each falls over k frames and the next
//       one starts a frame later), which makes the share of static polygons per frame a parameter:
//       paper 000 uses 804 polygons / 55.44 % static and 1,404 / 98.66 %.
//   builtin:cubes?count=28&seconds=10&seed=1
//       N cubes spinning about random axes at random speeds (paper 003: 28 cubes = 168 quads).
//   builtin:copies?count=3&of=SCENE
//       COUNT copies of another scene side by side along x (paper 002's "Bunny ×3"); every copy is
//       its own set of instances with its own ids, the meshes are shared. SCENE's cameras are
//       dropped (the view is fitted to the row). `of` comes last and may be any file or built-in.
//   builtin:orbit?count=8&seconds=4&duty=1&of=SCENE
//       SCENE as it is, with COUNT small cubes circling in front of it (one turn in SECONDS, in 8
//       hops; with DUTY < 1 a cube moves for that share of each hop and rests, the cubes staggered,
//       so cubes start and stop on most frames), seen by a fixed camera: a large static model crossed by a few moving objects, the case where the
//       granularity of temporal reuse's extents matters. SCENE's cameras are dropped; `of` comes last.
//   builtin:materials?draws=1000&meshes=40&shapes=6&materials=24&textures=8&seed=1
//       DRAWS boxes on a grid, a state-ordering test scene (paper 004, issue 10): SHAPES box
//       proportions, MATERIALS materials (colours; one in three double-sided; the first TEXTURES
//       of them each with a checker texture of its own), and MESHES (shape, material) pairs, a
//       glTF primitive each. Each box draws one of the meshes at random, and the boxes are
//       submitted in a random order, so that consecutive draws rarely share any state.
//   builtin:default
//       The dominoes with a checkered floor: what `frugal render` draws with no scene.
#include <algorithm>
#include <charconv>
#include <cmath>
#include <map>
#include <random>

#include <glm/gtc/constants.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include "base/Format.h"
#include "scene/Load.h"
#include "scene/MeshBuild.h"

namespace frugal {

namespace {

using Params = std::map<std::string, std::string>;

// What one spec may make frugal build. A built-in scene grows with its parameters, some as products
// (every domino has a key per frame of its fall; copies repeat a whole scene), so that a few
// characters can ask for more memory than a machine has, or for minutes of work; the counts are
// checked before anything is built.
// - 2^26 animation keys (20 bytes each, 1.3 GB): 1.5x the 44.6 million of
//   builtin:dominoes?polygons=60000, the largest scene the docs use;
// - 2^17 nodes and meshes (a cube is one of each, and as many draws): 13x the 10,000 dominoes of
//   that scene.
// (What such scenes take to build: docs/gl/README.md, "Outside the GL backend".)
constexpr double kMaxKeys = 67108864.0;
constexpr double kMaxObjects = 131072.0;

// Animation keys of a scene (built-ins that wrap another scene add theirs to its own).
double animationKeys(const Scene& scene) {
    double keys = 0.0;
    for (const Animation& animation : scene.animations)
        for (const AnimChannel& channel : animation.channels) keys += double(channel.times.size());
    return keys;
}

// Messages quote the spec and its parameters through oneLine: a spec is the user's text.
struct ParamReader {
    std::string scene;  // the spec, as messages quote it
    Params params;
    std::string error;

    double number(const std::string& key, double fallback, double lo, double hi) {
        auto it = params.find(key);
        if (it == params.end()) return fallback;
        const std::string text = it->second;
        params.erase(it);
        double value = 0.0;
        auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
        // A rejected value gives way to the fallback: callers convert before they check `error`.
        if (ec != std::errc() || end != text.data() + text.size() || !std::isfinite(value)) {
            fail(oneLine(key + "=" + text, 80) + " is not a number");
            return fallback;
        }
        if (value < lo || value > hi) {
            fail(oneLine(key + "=" + text, 80) + " is out of range [" + trim(lo) + ", " + trim(hi) + "]");
            return fallback;
        }
        return value;
    }
    std::string text(const std::string& key) {
        auto it = params.find(key);
        if (it == params.end()) return {};
        std::string value = it->second;
        params.erase(it);
        return value;
    }
    void fail(const std::string& why) {
        if (error.empty()) error = scene + ": " + why;
    }
    // Fails when the scene asked for is over the budget below; `what` says what makes it that large.
    void budget(double keys, double objects, const std::string& what) {
        if (keys > kMaxKeys)
            fail(what + " need " + fmt(keys) + " animation keys, more than frugal's limit of " +
                 std::to_string(std::uint64_t(kMaxKeys)));
        else if (objects > kMaxObjects)
            fail(what + " need " + fmt(objects) + " nodes and meshes, more than frugal's limit of " +
                 std::to_string(std::uint64_t(kMaxObjects)));
    }
    static std::string trim(double v) {
        char buf[32];
        auto [end, ec] = std::to_chars(buf, buf + sizeof buf, v);
        return std::string(buf, end);
    }
};

// Box with flat faces: 24 vertices, 12 triangles, counter-clockwise outside.
Mesh makeBox(const glm::vec3& lo, const glm::vec3& hi, int material, const std::string& name) {
    Mesh mesh;
    mesh.name = name;
    mesh.material = material;
    const glm::vec3 normals[6] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
    for (const glm::vec3& n : normals) {
        // Two axes spanning the face, chosen so that u × v = n (counter-clockwise seen from outside).
        const glm::vec3 u = std::abs(n.y) > 0.5f ? glm::vec3(0, 0, n.y) : glm::vec3(-n.z, 0, n.x);
        const glm::vec3 v = glm::cross(n, u);
        const std::uint32_t base = std::uint32_t(mesh.positions.size());
        const glm::vec2 corners[4] = {{-1, -1}, {1, -1}, {1, 1}, {-1, 1}};
        for (const glm::vec2& c : corners) {
            const glm::vec3 unit = n + c.x * u + c.y * v;  // in [-1,1]^3
            mesh.positions.push_back(glm::mix(lo, hi, (unit + 1.0f) * 0.5f));
            mesh.normals.push_back(n);
            mesh.uvs.push_back((c + 1.0f) * 0.5f);
        }
        for (std::uint32_t i : {0u, 1u, 2u, 0u, 2u, 3u}) mesh.indices.push_back(base + i);
    }
    return mesh;
}

Mesh makeQuad(float halfX, float halfZ, float uvRepeat, int material) {
    Mesh mesh;
    mesh.name = "floor";
    mesh.material = material;
    const glm::vec2 corners[4] = {{-1, -1}, {-1, 1}, {1, 1}, {1, -1}};  // y-up quad, CCW seen from above
    for (const glm::vec2& c : corners) {
        mesh.positions.push_back({c.x * halfX, 0.0f, c.y * halfZ});
        mesh.normals.push_back({0, 1, 0});
        mesh.uvs.push_back((c + 1.0f) * 0.5f * uvRepeat);
    }
    mesh.indices = {0, 1, 2, 0, 2, 3};
    return mesh;
}

Texture makeChecker(int size, int cells) {
    Texture texture;
    texture.name = "checker";
    texture.width = texture.height = size;
    texture.filter = texture.minFilter = Filter::Nearest;  // no mipmaps (the default)
    texture.rgba.resize(std::size_t(size) * size * 4);
    for (int y = 0; y < size; ++y)
        for (int x = 0; x < size; ++x) {
            const bool dark = ((x * cells / size) + (y * cells / size)) % 2 != 0;
            std::uint8_t* p = &texture.rgba[(std::size_t(y) * size + x) * 4];
            p[0] = dark ? 70 : 200;
            p[1] = dark ? 80 : 205;
            p[2] = dark ? 90 : 210;
            p[3] = 255;
        }
    return texture;
}

// The built-in scenes' materials are dielectrics of medium roughness (plastic): a diffuse colour
// with a soft highlight.
Material builtinMaterial() {
    Material material;
    material.metallicFactor = 0.0f;
    material.roughnessFactor = 0.5f;
    return material;
}

glm::vec4 hueColor(float hue) {
    const glm::vec3 k = glm::abs(glm::fract(glm::vec3(hue) + glm::vec3(0.0f, 2.0f / 3.0f, 1.0f / 3.0f)) * 6.0f - 3.0f);
    return glm::vec4(glm::mix(glm::vec3(1.0f), glm::clamp(k - 1.0f, 0.0f, 1.0f), 0.7f), 1.0f);
}

int addCamera(Scene& scene, const glm::vec3& eye, const glm::vec3& target, float znear, float zfar) {
    Node node;
    node.name = "camera";
    node.hasMatrix = true;
    node.matrix = glm::inverse(glm::lookAt(eye, target, glm::vec3(0, 1, 0)));
    node.camera = int(scene.cameras.size());
    SceneCamera camera;
    camera.name = "camera";
    camera.node = int(scene.nodes.size());
    camera.yfov = glm::radians(40.0f);
    camera.znear = znear;
    camera.zfar = zfar;
    scene.cameras.push_back(camera);
    scene.nodes.push_back(node);
    scene.roots.push_back(camera.node);
    return camera.node;
}

int addNode(Scene& scene, Node node, int parent) {
    const int index = int(scene.nodes.size());
    node.parent = parent;
    scene.nodes.push_back(std::move(node));
    if (parent >= 0) scene.nodes[parent].children.push_back(index);
    else scene.roots.push_back(index);
    return index;
}

Result<Scene> makeDominoes(ParamReader& in, bool defaultFloor) {
    const double polygons = in.number("polygons", 804, 6, 6e6);
    const double staticShare = in.number("static", 0.5544, 0.0, 1.0);
    const bool floor = in.number("floor", defaultFloor ? 1 : 0, 0, 1) != 0.0;
    if (!in.error.empty()) return Error{in.error};
    const int count = std::max(1, int(std::lround(polygons / 6.0)));
    const int moving = std::clamp(int(std::lround((1.0 - staticShare) * count)), 1, count);
    in.budget(double(count) * (moving + 1), count + 9.0,
              std::to_string(count) + " dominoes falling over " + std::to_string(moving) + " frames each");
    if (!in.error.empty()) return Error{in.error};

    Scene scene;
    scene.fps = 30.0;
    const float height = 2.0f, thickness = 0.3f, width = 1.0f, spacing = 1.2f, rowGap = 3.2f;
    const int perRow = std::max(1, int(std::ceil(std::sqrt(count * 2.5))));
    const int rows = (count + perRow - 1) / perRow;
    const float rowLength = float(perRow - 1) * spacing;

    const int kColours = 6;
    for (int c = 0; c < kColours; ++c) {
        Material material = builtinMaterial();
        material.name = "domino" + std::to_string(c);
        material.baseColorFactor = hueColor(float(c) / kColours);
        scene.materials.push_back(material);
        // The box sits behind its pivot (the front-bottom edge, at the origin), falling towards +z.
        scene.meshes.push_back(makeBox({-width / 2, 0, -thickness}, {width / 2, height, 0}, c, "domino" + std::to_string(c)));
    }

    // A leaning domino rests on the next one: its top touches where the next one stands.
    const float restAngle = std::asin(std::min(1.0f, spacing / height));
    // Domino i falls during frames [i, i + moving]: one key per frame, accelerating (angle ∝ u²),
    // so that between any two consecutive frames exactly `moving` dominoes change pose. There are
    // only four falls (two directions, to rest or flat), each computed once: large fields have
    // tens of millions of keys.
    std::vector<glm::vec4> falls[2][2];  // [forward][flat]
    const auto fall = [&](bool forward, bool flat) -> const std::vector<glm::vec4>& {
        std::vector<glm::vec4>& values = falls[forward][flat];
        if (!values.empty()) return values;
        const glm::quat facing =
            glm::angleAxis(forward ? glm::half_pi<float>() : -glm::half_pi<float>(), glm::vec3(0, 1, 0));
        const float finalAngle = flat ? glm::half_pi<float>() : restAngle;
        for (int k = 0; k <= moving; ++k) {
            const float u = float(k) / float(moving);
            const glm::quat q = facing * glm::angleAxis(finalAngle * u * u, glm::vec3(1, 0, 0));
            values.push_back({q.x, q.y, q.z, q.w});
        }
        return values;
    };
    for (int i = 0; i < count; ++i) {
        const int row = i / perRow, col = i % perRow;
        const bool forward = row % 2 == 0;  // serpentine: odd rows run back
        const float x = (forward ? float(col) : float(perRow - 1 - col)) * spacing - rowLength / 2;
        const float z = (float(row) - float(rows - 1) / 2) * rowGap;
        Node pivot;
        pivot.name = "domino" + std::to_string(i);
        pivot.translation = {x, 0.0f, z};
        // Travel along ±x; the box falls towards its local +z, so turn local +z onto the travel direction.
        const glm::quat facing = glm::angleAxis(forward ? glm::half_pi<float>() : -glm::half_pi<float>(), glm::vec3(0, 1, 0));
        pivot.rotation = facing;
        pivot.meshes.push_back(i % kColours);
        const int node = addNode(scene, pivot, -1);

        AnimChannel channel;
        channel.node = node;
        channel.path = AnimPath::Rotation;
        channel.interpolation = Interp::Linear;
        channel.values = fall(forward, i == count - 1 || col == perRow - 1);
        channel.times.resize(channel.values.size());
        // The same arithmetic as the frame times (frame / fps, in double, then float) so keys fall on frames exactly.
        for (int k = 0; k <= moving; ++k) channel.times[std::size_t(k)] = float(double(i + k) / scene.fps);
        Animation animation;
        animation.name = pivot.name;
        animation.channels.push_back(std::move(channel));
        scene.animations.push_back(std::move(animation));
    }

    const float halfX = rowLength / 2 + 3.0f, halfZ = float(rows) * rowGap / 2 + 2.0f;
    if (floor) {
        Material material = builtinMaterial();
        material.name = "floor";
        material.baseColorTexture = 0;
        scene.materials.push_back(material);
        scene.textures.push_back(makeChecker(64, 8));
        scene.meshes.push_back(makeQuad(halfX, halfZ, std::max(halfX, halfZ) / 4.0f, int(scene.materials.size()) - 1));
        Node node;
        node.name = "floor";
        node.meshes.push_back(int(scene.meshes.size()) - 1);
        addNode(scene, node, -1);
    }
    const float extent = std::max(halfX, halfZ);
    addCamera(scene, {0.0f, extent * 1.1f, extent * 1.5f}, {0.0f, 0.0f, 0.0f}, 0.1f, extent * 6.0f);
    return scene;
}

Result<Scene> makeCubes(ParamReader& in) {
    const double count = in.number("count", 28, 1, 1e6);
    const double seconds = in.number("seconds", 10, 0.1, 3600);
    const double seed = in.number("seed", 1, 0, 4294967295.0);
    if (!in.error.empty()) return Error{in.error};
    const int n = int(count);
    // The fastest cube turns 0.5 times a second, 16 keys a turn.
    in.budget(n * std::max(2.0, std::ceil(seconds * 0.5 * 16.0) + 1.0), 2.0 * n + 1.0,
              std::to_string(n) + " cubes turning for " + fmt(seconds) + " s");
    if (!in.error.empty()) return Error{in.error};

    Scene scene;
    scene.fps = 30.0;
    std::mt19937 rng{static_cast<std::uint32_t>(seed)};
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    const float side = 1.0f;
    const float spread = 2.2f * std::cbrt(float(n)) * side;  // cubes overlap in screen space, by design
    scene.meshes.reserve(n);
    for (int i = 0; i < n; ++i) {
        Material material = builtinMaterial();
        material.name = "cube" + std::to_string(i);
        material.baseColorFactor = hueColor(unit(rng));
        scene.materials.push_back(material);
        scene.meshes.push_back(makeBox(glm::vec3(-side / 2), glm::vec3(side / 2), i, material.name));

        Node node;
        node.name = material.name;
        node.translation = (glm::vec3(unit(rng), unit(rng), unit(rng)) - 0.5f) * spread;
        node.meshes.push_back(i);
        const int index = addNode(scene, node, -1);

        // Uniform rotation about a random axis: slerp between keys 1/16 turn apart is exact.
        glm::vec3 axis(unit(rng) - 0.5f, unit(rng) - 0.5f, unit(rng) - 0.5f);
        axis = glm::length(axis) > 1e-3f ? glm::normalize(axis) : glm::vec3(0, 1, 0);
        const float turnsPerSecond = 0.1f + 0.4f * unit(rng);
        const float phase = unit(rng) * glm::two_pi<float>();
        AnimChannel channel;
        channel.node = index;
        channel.path = AnimPath::Rotation;
        const int keys = std::max(2, int(std::ceil(seconds * turnsPerSecond * 16.0)) + 1);
        for (int k = 0; k < keys; ++k) {
            const float t = float(seconds) * float(k) / float(keys - 1);
            const glm::quat q = glm::angleAxis(phase + glm::two_pi<float>() * turnsPerSecond * t, axis);
            channel.times.push_back(t);
            channel.values.push_back({q.x, q.y, q.z, q.w});
        }
        Animation animation;
        animation.name = node.name;
        animation.channels.push_back(std::move(channel));
        scene.animations.push_back(std::move(animation));
    }
    const float r = spread * 0.9f + side;
    addCamera(scene, {0.0f, r * 0.6f, r * 2.2f}, glm::vec3(0.0f), 0.1f, r * 6.0f);
    return scene;
}

Result<Scene> makeCopies(ParamReader& in, const LoadOptions& options) {
    const double count = in.number("count", 3, 1, 1000);
    const std::string of = in.text("of");
    if (!in.error.empty()) return Error{in.error};
    if (of.empty()) return Error{in.scene + ": parameter 'of' (the scene to copy) is missing"};
    if (of.rfind("builtin:copies", 0) == 0) return Error{in.scene + ": copies of copies are not supported"};
    Result<Scene> loaded = loadScene(of, options);
    if (!loaded) return loaded;
    const Scene& one = *loaded;
    in.budget(count * animationKeys(one), count * (double(one.nodes.size()) + 1.0) + double(one.meshes.size()),
              fmt(count) + " copies of a scene of " + std::to_string(one.nodes.size()) + " nodes");
    if (!in.error.empty()) return Error{in.error};

    Scene scene;
    scene.meshes = one.meshes;
    scene.materials = one.materials;
    scene.textures = one.textures;
    scene.unsupported = one.unsupported;
    scene.warnings = one.warnings;
    scene.fps = one.fps;
    const Bounds bounds = one.bounds(0.0);
    const float step = bounds.empty() ? 1.0f : (bounds.max.x - bounds.min.x) * 1.1f;
    const int n = int(count);
    for (int k = 0; k < n; ++k) {
        Node root;
        root.name = "copy" + std::to_string(k);
        root.translation = {(float(k) - float(n - 1) / 2.0f) * step, 0.0f, 0.0f};
        const int rootIndex = addNode(scene, root, -1);
        const int offset = int(scene.nodes.size());
        for (const Node& source : one.nodes) {
            Node node = source;
            node.camera = -1;
            node.parent = source.parent >= 0 ? source.parent + offset : rootIndex;
            for (int& child : node.children) child += offset;
            scene.nodes.push_back(std::move(node));
        }
        for (int r : one.roots) scene.nodes[rootIndex].children.push_back(r + offset);
        for (const Animation& source : one.animations) {
            Animation animation = source;
            for (AnimChannel& channel : animation.channels) channel.node += offset;
            scene.animations.push_back(std::move(animation));
        }
    }
    return scene;
}

Result<Scene> makeOrbit(ParamReader& in, const LoadOptions& options) {
    const double count = in.number("count", 8, 1, 10000);
    const double seconds = in.number("seconds", 4, 0.1, 3600);
    const double duty = in.number("duty", 1, 0.05, 1);
    const std::string of = in.text("of");
    if (!in.error.empty()) return Error{in.error};
    if (of.empty()) return Error{in.scene + ": parameter 'of' (the scene to circle) is missing"};
    Result<Scene> loaded = loadScene(of, options);
    if (!loaded) return loaded;
    Scene scene = std::move(*loaded);
    // A cube has 8 hops of 9 keys, and one more to start when staggered.
    in.budget(animationKeys(scene) + count * 73.0, double(scene.nodes.size() + scene.meshes.size()) + count + 2.0,
              "a scene of " + std::to_string(scene.nodes.size()) + " nodes and " + fmt(count) + " orbiting cubes");
    if (!in.error.empty()) return Error{in.error};
    const Bounds bounds = scene.bounds(0.0);
    const glm::vec3 centre = bounds.empty() ? glm::vec3(0.0f) : bounds.center();
    const float radius = bounds.empty() || bounds.radius() <= 0.0f ? 1.0f : bounds.radius();
    scene.cameras.clear();
    for (Node& node : scene.nodes) node.camera = -1;

    const float side = 0.08f * radius, ring = 0.6f * radius;
    const int n = int(count);
    Material material = builtinMaterial();
    material.name = "orbiter";
    material.baseColorFactor = {0.95f, 0.85f, 0.2f, 1.0f};
    scene.materials.push_back(material);
    scene.meshes.push_back(makeBox(glm::vec3(-side / 2), glm::vec3(side / 2), int(scene.materials.size()) - 1, "orbiter"));
    const int mesh = int(scene.meshes.size()) - 1;
    // A turn is 8 hops; a cube moves for `duty` of each hop's time and rests for the rest, the
    // cubes staggered, so that with duty < 1 some start and some stop on most frames.
    constexpr int kHops = 8, kKeysPerHop = 8;
    const float hopTime = float(seconds) / kHops, hopAngle = glm::two_pi<float>() / kHops;
    for (int i = 0; i < n; ++i) {
        Node node;
        node.name = "orbiter" + std::to_string(i);
        node.meshes.push_back(mesh);
        const int index = addNode(scene, node, -1);
        AnimChannel channel;
        channel.node = index;
        channel.path = AnimPath::Translation;
        const float phase = glm::two_pi<float>() * float(i) / float(n);
        const float depth = centre.z + radius * (0.4f + 0.2f * float(i % 3));  // in front of the model
        const float stagger = duty < 1.0 ? hopTime * float(i) / float(n) : 0.0f;
        const auto key = [&](float time, float angle) {
            channel.times.push_back(time);
            channel.values.push_back({centre.x + ring * std::cos(angle), centre.y + ring * std::sin(angle), depth, 0.0f});
        };
        if (stagger > 0.0f) key(0.0f, phase);
        for (int h = 0; h < kHops; ++h)
            for (int k = 0; k <= kKeysPerHop; ++k) {
                if (h > 0 && k == 0 && duty >= 1.0) continue;  // continuous: hops share their end keys
                const float u = float(k) / kKeysPerHop;
                key(stagger + hopTime * (float(h) + float(duty) * u), phase + hopAngle * (float(h) + u));
            }
        Animation animation;
        animation.name = node.name;
        animation.channels.push_back(std::move(channel));
        scene.animations.push_back(std::move(animation));
    }
    addCamera(scene, centre + glm::vec3(0.0f, 0.3f * radius, 3.2f * radius), centre, 0.05f * radius, 8.0f * radius);
    return scene;
}

Result<Scene> makeMaterials(ParamReader& in) {
    const int draws = int(in.number("draws", 1000, 1, 1e6));
    const int meshCount = int(in.number("meshes", 40, 1, 1e5));
    const int shapes = int(in.number("shapes", 6, 1, 1e4));
    const int materials = int(in.number("materials", 24, 1, 1e5));
    const int textures = int(in.number("textures", 8, 0, 1e4));
    const double seed = in.number("seed", 1, 0, 4294967295.0);
    if (in.error.empty() && textures > materials)
        in.fail("textures=" + std::to_string(textures) + " exceeds materials=" + std::to_string(materials) +
                " (one texture a material at most)");
    in.budget(0.0, draws + meshCount + 1.0,
              std::to_string(draws) + " draws of " + std::to_string(meshCount) + " meshes");
    if (!in.error.empty()) return Error{in.error};

    Scene scene;
    std::mt19937 rng{static_cast<std::uint32_t>(seed)};
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    for (int t = 0; t < textures; ++t) {
        scene.textures.push_back(makeChecker(32, 2 + t % 6));
        scene.textures.back().name = "checker" + std::to_string(t);
    }
    for (int m = 0; m < materials; ++m) {
        Material material = builtinMaterial();
        material.name = "material" + std::to_string(m);
        material.baseColorFactor = hueColor(float(m) / float(materials));
        material.baseColorTexture = m < textures ? m : -1;
        material.doubleSided = m % 3 == 2;
        scene.materials.push_back(material);
    }
    std::vector<glm::vec3> extents;
    for (int s = 0; s < shapes; ++s) extents.push_back(glm::vec3(0.3f + 0.6f * unit(rng), 0.3f + 0.6f * unit(rng), 0.3f + 0.6f * unit(rng)));
    for (int k = 0; k < meshCount; ++k) {
        const int shape = k % shapes, material = int(unit(rng) * float(materials)) % materials;
        scene.meshes.push_back(makeBox(-extents[std::size_t(shape)] / 2.0f, extents[std::size_t(shape)] / 2.0f, material,
                                       "shape" + std::to_string(shape) + "-material" + std::to_string(material)));
    }
    // Grid cells in a random order: the submission order.
    const int side = int(std::ceil(std::sqrt(double(draws))));
    std::vector<int> cells;
    for (int i = 0; i < draws; ++i) cells.push_back(i);
    std::shuffle(cells.begin(), cells.end(), rng);
    for (int cell : cells) {
        Node node;
        node.name = "box" + std::to_string(cell);
        node.translation = {float(cell % side) - 0.5f * float(side - 1), 0.0f, float(cell / side) - 0.5f * float(side - 1)};
        node.rotation = glm::angleAxis(unit(rng) * glm::two_pi<float>(), glm::vec3(0, 1, 0));
        node.meshes.push_back(int(unit(rng) * float(meshCount)) % meshCount);
        addNode(scene, node, -1);
    }
    const float extent = 0.5f * float(side) + 1.0f;
    addCamera(scene, {0.0f, extent * 1.2f, extent * 1.4f}, {0.0f, 0.0f, 0.0f}, 0.1f, extent * 6.0f);
    return scene;
}

}  // namespace

std::vector<std::pair<std::string, std::string>> builtinScenes() {
    return {
        {"builtin:default", "the dominoes on a checkered floor (what `frugal render` draws with no scene)"},
        {"builtin:dominoes", "falling dominoes; ?polygons=804&static=0.5544&floor=0 (6 polygons a domino)"},
        {"builtin:cubes", "spinning cubes; ?count=28&seconds=10&seed=1"},
        {"builtin:copies", "copies of a scene side by side; ?count=3&of=SCENE (of last)"},
        {"builtin:orbit", "a static scene circled by moving cubes; ?count=8&seconds=4&duty=1&of=SCENE (of last)"},
        {"builtin:materials", "boxes over many meshes, materials and textures, in a random order (state ordering); "
                              "?draws=1000&meshes=40&shapes=6&materials=24&textures=8&seed=1"},
    };
}

Result<Scene> makeBuiltin(const std::string& spec, const LoadOptions& options) {
    const std::string prefix = "builtin:";
    std::string rest = spec.substr(spec.rfind(prefix, 0) == 0 ? prefix.size() : 0);
    std::string name = rest.substr(0, rest.find('?'));
    ParamReader in{oneLine(spec), {}, {}};
    if (rest.size() > name.size()) {
        std::string query = rest.substr(name.size() + 1);
        std::size_t at = 0;
        while (at <= query.size()) {
            if (query.compare(at, 3, "of=") == 0) {  // the copied scene's spec: the rest, '&' and all
                in.params["of"] = query.substr(at + 3);
                break;
            }
            const std::size_t end = std::min(query.find('&', at), query.size());
            const std::string pair = query.substr(at, end - at);
            const std::size_t eq = pair.find('=');
            if (pair.empty() || eq == std::string::npos || eq == 0)
                return Error{in.scene + ": parameter '" + oneLine(pair, 80) + "' is not key=value"};
            in.params[pair.substr(0, eq)] = pair.substr(eq + 1);
            at = end + 1;
        }
    }

    Result<Scene> made = Error{""};
    if (name == "default") made = makeDominoes(in, true);
    else if (name == "dominoes") made = makeDominoes(in, false);
    else if (name == "cubes") made = makeCubes(in);
    else if (name == "copies") made = makeCopies(in, options);
    else if (name == "orbit") made = makeOrbit(in, options);
    else if (name == "materials") made = makeMaterials(in);
    else {
        std::string known;
        for (const auto& [n, _] : builtinScenes()) known += (known.empty() ? "" : ", ") + n;
        return Error{in.scene + ": no such built-in scene (there are " + known + ")"};
    }
    if (!made) return made;
    if (!in.params.empty())
        return Error{in.scene + ": unknown parameter '" + oneLine(in.params.begin()->first, 80) + "'"};

    Scene& scene = *made;
    scene.source = spec;
    if (name != "copies" && name != "orbit")  // the loaded scene's meshes are finalised already
        for (Mesh& mesh : scene.meshes) finalizeMesh(mesh, options.optimizeOrder);
    else if (name == "orbit")
        finalizeMesh(scene.meshes.back(), options.optimizeOrder);
    scene.buildInstances();
    return made;
}

}  // namespace frugal
