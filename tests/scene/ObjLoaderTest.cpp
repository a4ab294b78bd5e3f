// OBJ loader: the Stanford bunny, polygons, materials, vertex attributes, and bad indices.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <numbers>
#include <set>
#include <string>
#include <vector>

#include "TestSupport.h"
#include "scene/Load.h"

namespace frugal {
namespace {

namespace fs = std::filesystem;

Result<Scene> loadText(const std::string& test, const std::string& text, LoadOptions options = {}) {
    const fs::path path = test::freshDir(test) / "model.obj";
    test::writeFile(path, text);
    options.optimizeOrder = false;  // keep the file's triangle order, to compare indices
    return loadObj(path.string(), options);
}

std::string pathOf(const std::string& test) { return (test::outputDir() / test / "model.obj").string(); }

glm::vec3 faceNormal(const Mesh& mesh, std::size_t t) {
    const glm::vec3 a = mesh.positions[mesh.indices[3 * t]], b = mesh.positions[mesh.indices[3 * t + 1]],
                    c = mesh.positions[mesh.indices[3 * t + 2]];
    return glm::cross(b - a, c - a);
}

TEST(ObjLoaderTest, BunnyLoadsWithAllItsVerticesAndTriangles) {
    const Result<Scene> scene = loadObj(FRUGAL_BUNNY_OBJ);
    ASSERT_TRUE(scene.ok()) << scene.error().message;
    ASSERT_EQ(scene->meshes.size(), 1u);
    const Mesh& mesh = scene->meshes[0];
    EXPECT_EQ(mesh.positions.size(), 34835u);
    EXPECT_EQ(mesh.triangleCount(), 69666u);
    EXPECT_EQ(mesh.normals.size(), mesh.positions.size());  // computed: the file has none
    EXPECT_TRUE(mesh.uvs.empty());
    EXPECT_TRUE(mesh.colors.empty());
    EXPECT_EQ(scene->nodes.size(), 1u);
    EXPECT_EQ(scene->roots, (std::vector<int>{0}));
    EXPECT_EQ(scene->instances.size(), 1u);
    EXPECT_EQ(scene->triangleCount(), 69666u);
    EXPECT_TRUE(scene->warnings.empty());
    EXPECT_TRUE(scene->unsupported.empty());
    // One default material, double-sided by default (OBJ has no culling flag).
    ASSERT_EQ(scene->materials.size(), 1u);
    EXPECT_EQ(mesh.material, 0);
    EXPECT_TRUE(scene->materials[0].doubleSided);
    // The file's extent: x in [-1, 1], y in [-0.991233, 0.991233], z in [-0.775047, 0.775047].
    glm::vec3 lo(1e30f), hi(-1e30f);
    for (const glm::vec3& p : mesh.positions) {
        lo = glm::min(lo, p);
        hi = glm::max(hi, p);
    }
    EXPECT_NEAR(lo.x, -1.0f, 1e-5f);
    EXPECT_NEAR(hi.x, 1.0f, 1e-5f);
    EXPECT_NEAR(lo.y, -0.991233f, 1e-5f);
    EXPECT_NEAR(hi.y, 0.991233f, 1e-5f);
    EXPECT_NEAR(lo.z, -0.775047f, 1e-5f);
    EXPECT_NEAR(hi.z, 0.775047f, 1e-5f);
    // Every source triangle id appears exactly once, whatever the optimised order.
    std::vector<std::uint32_t> source = mesh.triangleSource;
    std::sort(source.begin(), source.end());
    for (std::uint32_t t = 0; t < source.size(); ++t) ASSERT_EQ(source[t], t);
}

TEST(ObjLoaderTest, BunnyFollowsObjDoubleSided) {
    LoadOptions options;
    options.objDoubleSided = false;
    options.optimizeOrder = false;
    const Result<Scene> scene = loadObj(FRUGAL_BUNNY_OBJ, options);
    ASSERT_TRUE(scene.ok()) << scene.error().message;
    EXPECT_FALSE(scene->materials[0].doubleSided);
}

// A unit cube of six quads with shared positions, per-face normals and texture coordinates.
const char* kCube = R"(# cube
o cube
v 0 0 0
v 1 0 0
v 1 1 0
v 0 1 0
v 0 0 1
v 1 0 1
v 1 1 1
v 0 1 1
vt 0 0
vt 1 0
vt 1 1
vt 0 1
vn 0 0 -1
vn 0 0 1
vn 0 -1 0
vn 0 1 0
vn -1 0 0
vn 1 0 0
f 1/1/1 4/4/1 3/3/1 2/2/1
f 5/1/2 6/2/2 7/3/2 8/4/2
f 1/1/3 2/2/3 6/3/3 5/4/3
f 4/1/4 8/4/4 7/3/4 3/2/4
f 1/1/5 5/2/5 8/3/5 4/4/5
f 2/1/6 3/4/6 7/3/6 6/2/6
)";

TEST(ObjLoaderTest, QuadsBecomeTwoTrianglesWithFlippedV) {
    const Result<Scene> scene = loadText("ObjCube", kCube);
    ASSERT_TRUE(scene.ok()) << scene.error().message;
    ASSERT_EQ(scene->meshes.size(), 1u);
    const Mesh& mesh = scene->meshes[0];
    EXPECT_EQ(mesh.name, "cube");
    EXPECT_EQ(scene->nodes[0].name, "cube");
    EXPECT_EQ(mesh.triangleCount(), 12u);
    EXPECT_EQ(mesh.positions.size(), 24u);  // 8 positions × 3 normals each
    ASSERT_EQ(mesh.uvs.size(), 24u);
    ASSERT_EQ(mesh.normals.size(), 24u);
    // The first vertex is 1/1/1: position (0,0,0), vt (0,0) → uv (0, 1), normal -z.
    EXPECT_EQ(mesh.positions[0], glm::vec3(0, 0, 0));
    EXPECT_EQ(mesh.uvs[0], glm::vec2(0, 1));
    EXPECT_EQ(mesh.normals[0], glm::vec3(0, 0, -1));
    // 4/4/1 is vertex 1: vt (0,1) → uv (0, 0).
    EXPECT_EQ(mesh.uvs[1], glm::vec2(0, 0));
    // Every triangle faces the way its file normal says (counter-clockwise = front).
    for (std::size_t t = 0; t < mesh.triangleCount(); ++t) {
        const glm::vec3 n = faceNormal(mesh, t);
        EXPECT_GT(glm::dot(n, mesh.normals[mesh.indices[3 * t]]), 0.0f) << "triangle " << t;
    }
}

TEST(ObjLoaderTest, QuadsSplitAlongTheirShorterDiagonalAndPolygonsAsFans) {
    // A kite: diagonal 1-3 (length 1) is shorter than 0-2 (length 3).
    const Result<Scene> kite = loadText("ObjKite", "v 0 0 0\nv 1 -0.5 0\nv 3 0 0\nv 1 0.5 0\nf 1 2 3 4\n");
    ASSERT_TRUE(kite.ok()) << kite.error().message;
    EXPECT_EQ(kite->meshes[0].indices, (std::vector<std::uint32_t>{0, 1, 3, 1, 2, 3}));
    const Result<Scene> pentagon =
        loadText("ObjPentagon", "v 1 0 0\nv 0.3 0.95 0\nv -0.8 0.6 0\nv -0.8 -0.6 0\nv 0.3 -0.95 0\nf 1 2 3 4 5\n");
    ASSERT_TRUE(pentagon.ok()) << pentagon.error().message;
    const Mesh& mesh = pentagon->meshes[0];
    EXPECT_EQ(mesh.indices, (std::vector<std::uint32_t>{0, 1, 2, 0, 2, 3, 0, 3, 4}));
    EXPECT_EQ(mesh.triangleSource, (std::vector<std::uint32_t>{0, 1, 2}));
    for (std::size_t t = 0; t < mesh.triangleCount(); ++t) EXPECT_GT(faceNormal(mesh, t).z, 0.0f);
}

TEST(ObjLoaderTest, RelativeIndicesResolveAgainstTheVerticesReadSoFar) {
    const Result<Scene> scene = loadText("ObjRelative", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf -3 -2 -1\nv 5 5 5\nf 1 -3 -2\n");
    ASSERT_TRUE(scene.ok()) << scene.error().message;
    const Mesh& mesh = scene->meshes[0];
    ASSERT_EQ(mesh.triangleCount(), 2u);
    EXPECT_EQ(mesh.positions[mesh.indices[3]], glm::vec3(0, 0, 0));
    EXPECT_EQ(mesh.positions[mesh.indices[4]], glm::vec3(1, 0, 0));
    EXPECT_EQ(mesh.positions[mesh.indices[5]], glm::vec3(0, 1, 0));
}

TEST(ObjLoaderTest, BadIndicesFailWithTheirNumbers) {
    struct Case {
        const char* name;
        const char* text;
        std::string error;  // after "<path>: "
    };
    const std::vector<Case> cases = {
        {"ObjPositionOutOfRange", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\nf 1 2 9\n",
         "shape 0 face 2: position index 9 out of range, the file has 3 positions"},
        {"ObjTexcoordOutOfRange", "o tri\nv 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nf 1/1 2/2 3/1\n",
         "shape 'tri' face 1: texcoord index 2 out of range, the file has 1 texcoords"},
        {"ObjNormalOutOfRange", "o tri\nv 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 1\nf 1//1 2//1 3//4\n",
         "shape 'tri' face 1: normal index 4 out of range, the file has 1 normals"},
        {"ObjRelativeBeforeFirst", "o tri\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf -1 -2 -5\n",
         "shape 'tri' face 1: a relative position index points before the first position"},
        {"ObjRelativeNormalBeforeFirst", "o tri\nv 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 1\nf 1//-3 2//-1 3//-1\n",
         "shape 'tri' face 1: a relative normal index points before the first normal"},
        {"ObjIndexZero", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 0 1 2\n",
         "Failed parse `f' line(e.g. zero value for face index. line 4.)"},
    };
    for (const Case& c : cases) {
        const Result<Scene> scene = loadText(c.name, c.text);
        ASSERT_FALSE(scene.ok()) << c.name;
        EXPECT_EQ(scene.error().message, pathOf(c.name) + ": " + c.error);
    }
}

TEST(ObjLoaderTest, AFaceOfMoreThan255VerticesFails) {
    std::string text;
    std::string face = "f";
    for (int k = 0; k < 300; ++k) {
        const double angle = 2 * std::numbers::pi * k / 300;
        text += "v " + std::to_string(std::cos(angle)) + " " + std::to_string(std::sin(angle)) + " 0\n";
        face += " " + std::to_string(k + 1);
    }
    const Result<Scene> scene = loadText("ObjHugeFace", text + face + "\n");
    ASSERT_FALSE(scene.ok());
    EXPECT_EQ(scene.error().message, pathOf("ObjHugeFace") +
                                 ": shape 0: a face has more than 255 vertices, which tinyobjloader cannot represent");
}

TEST(ObjLoaderTest, FileProblemsAreReported) {
    const fs::path dir = test::freshDir("ObjFileProblems");
    EXPECT_EQ(loadObj((dir / "missing.obj").string()).error().message, (dir / "missing.obj").string() + ": no such file");
    test::writeFile(dir / "empty.obj", "");
    EXPECT_EQ(loadObj((dir / "empty.obj").string()).error().message, (dir / "empty.obj").string() + ": file is empty");
    EXPECT_EQ(loadObj(dir.string()).error().message, dir.string() + ": is a directory, not a file");
    // Text without faces loads as an empty scene, with a warning.
    test::writeFile(dir / "points.obj", "v 0 0 0\n");
    const Result<Scene> scene = loadObj((dir / "points.obj").string());
    ASSERT_TRUE(scene.ok()) << scene.error().message;
    EXPECT_TRUE(scene->meshes.empty());
    EXPECT_EQ(scene->warnings, (std::vector<std::string>{(dir / "points.obj").string() + ": no faces to draw"}));
}

TEST(ObjLoaderTest, DiffuseColoursBecomeMaterialsOneMeshPerShapeAndMaterial) {
    const fs::path dir = test::freshDir("ObjMaterials");
    test::writeFile(dir / "colours.mtl",
                    "newmtl red\nKd 1 0 0\nd 0.5\nNs 14\nnewmtl green\nKd 0 1 0\nmap_Kd green.png\nNs 1000\n");
    test::writeFile(dir / "model.obj",
                    "mtllib colours.mtl\n"
                    "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\n"
                    "o first\nusemtl red\nf 1 2 3\nusemtl green\nf 2 4 3\nusemtl red\nf 1 2 4\n"
                    "o second\nusemtl nosuchmaterial\nf 1 2 3\n");
    LoadOptions options;
    options.objDoubleSided = false;
    const Result<Scene> scene = loadObj((dir / "model.obj").string(), options);
    ASSERT_TRUE(scene.ok()) << scene.error().message;
    ASSERT_EQ(scene->materials.size(), 3u);  // red, green, and the default for the unknown name
    EXPECT_EQ(scene->materials[0].name, "red");
    EXPECT_EQ(scene->materials[0].baseColorFactor, glm::vec4(1, 0, 0, 1));  // dissolve ignored
    EXPECT_EQ(scene->materials[1].baseColorFactor, glm::vec4(0, 1, 0, 1));
    EXPECT_EQ(scene->materials[2].baseColorFactor, glm::vec4(1, 1, 1, 1));
    // Dielectrics, the Phong exponent as a roughness: (2 / (Ns + 2))^(1/4); no material: Ns 0.
    EXPECT_FLOAT_EQ(scene->materials[0].roughnessFactor, std::pow(2.0f / 16.0f, 0.25f));
    EXPECT_NEAR(scene->materials[1].roughnessFactor, 0.211, 0.001);
    EXPECT_EQ(scene->materials[2].roughnessFactor, 1.0f);
    for (const Material& material : scene->materials) {
        EXPECT_FALSE(material.doubleSided);
        EXPECT_EQ(material.metallicFactor, 0.0f);
    }
    ASSERT_EQ(scene->meshes.size(), 3u);
    EXPECT_EQ(scene->meshes[0].name, "first (red)");
    EXPECT_EQ(scene->meshes[0].material, 0);
    EXPECT_EQ(scene->meshes[0].triangleCount(), 2u);
    EXPECT_EQ(scene->meshes[1].name, "first (green)");
    EXPECT_EQ(scene->meshes[1].material, 1);
    EXPECT_EQ(scene->meshes[2].name, "second");
    EXPECT_EQ(scene->meshes[2].material, 2);
    ASSERT_EQ(scene->nodes.size(), 2u);
    EXPECT_EQ(scene->nodes[0].meshes, (std::vector<int>{0, 1}));
    EXPECT_EQ(scene->nodes[1].meshes, (std::vector<int>{2}));
    EXPECT_EQ(scene->roots, (std::vector<int>{0, 1}));
    EXPECT_EQ(scene->instances.size(), 3u);
    EXPECT_EQ(scene->unsupported, (std::vector<std::string>{"map_Kd textures"}));
    ASSERT_EQ(scene->warnings.size(), 1u);
    EXPECT_NE(scene->warnings[0].find("nosuchmaterial"), std::string::npos) << scene->warnings[0];
}

TEST(ObjLoaderTest, MissingMaterialLibraryIsAWarning) {
    const Result<Scene> scene = loadText("ObjMissingMtl", "mtllib gone.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
    ASSERT_TRUE(scene.ok()) << scene.error().message;
    EXPECT_EQ(scene->meshes.size(), 1u);
    ASSERT_FALSE(scene->warnings.empty());
    EXPECT_EQ(scene->warnings[0], pathOf("ObjMissingMtl") + ": material library 'gone.mtl' not found");
}

TEST(ObjLoaderTest, VertexColoursAreKept) {
    const Result<Scene> scene = loadText("ObjColours", "v 0 0 0 1 0 0\nv 1 0 0 0 1 0\nv 0 1 0 0 0 1\nf 1 2 3\n");
    ASSERT_TRUE(scene.ok()) << scene.error().message;
    const Mesh& mesh = scene->meshes[0];
    ASSERT_EQ(mesh.colors.size(), 3u);
    EXPECT_EQ(mesh.colors[0], glm::vec4(1, 0, 0, 1));
    EXPECT_EQ(mesh.colors[2], glm::vec4(0, 0, 1, 1));
    // Without colours on every vertex there are none.
    const Result<Scene> partial = loadText("ObjPartialColours", "v 0 0 0 1 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
    ASSERT_TRUE(partial.ok()) << partial.error().message;
    EXPECT_TRUE(partial->meshes[0].colors.empty());
}

TEST(ObjLoaderTest, MixedNormalsAreRecomputedAndMissingTexcoordsAreZero) {
    const Result<Scene> scene =
        loadText("ObjMixed", "v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 -1\nvt 0.25 0.25\nf 1/1/1 2//1 3\n");
    ASSERT_TRUE(scene.ok()) << scene.error().message;
    const Mesh& mesh = scene->meshes[0];
    ASSERT_EQ(mesh.normals.size(), 3u);
    EXPECT_EQ(mesh.normals[0], glm::vec3(0, 0, 1));  // computed from the counter-clockwise face
    ASSERT_EQ(mesh.uvs.size(), 3u);
    EXPECT_EQ(mesh.uvs[0], glm::vec2(0.25f, 0.75f));
    EXPECT_EQ(mesh.uvs[1], glm::vec2(0, 0));
}

TEST(ObjLoaderTest, LinesAndPointsAreReportedNotDrawn) {
    const Result<Scene> scene = loadText("ObjLines", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\nl 1 2 3\np 1\n");
    ASSERT_TRUE(scene.ok()) << scene.error().message;
    EXPECT_EQ(scene->triangleCount(), 1u);
    EXPECT_EQ(std::multiset<std::string>(scene->unsupported.begin(), scene->unsupported.end()),
              (std::multiset<std::string>{"OBJ lines (l)", "OBJ points (p)"}));
}

TEST(ObjLoaderTest, VertexLinesMustHoldFiniteFloats) {
    // tinyobjloader reads what it cannot parse as 0 without a word: each of these put a vertex where
    // the file does not say.
    struct Case {
        const char* name;
        const char* text;
        const char* error;  // after "<path>: "
    };
    const Case cases[] = {
        {"ObjVertexNan", "v 0 0 0\nv nan 0 0\nv 0 1 0\nf 1 2 3\n", "line 2: 'nan' in a v line is not finite"},
        {"ObjVertexInf", "v 0 0 0\nv 1 0 0\nv 0 -inf 0\nf 1 2 3\n", "line 3: '-inf' in a v line is not finite"},
        {"ObjVertexWord", "v 0 0 0\r\nv 1 x 0\r\nv 0 1 0\r\nf 1 2 3\r\n", "line 2: 'x' in a v line is not a number"},
        {"ObjVertexTrailing", "v 0 0 0\rv 1 0 0\rv 0 1 0z\rf 1 2 3\r", "line 3: '0z' in a v line is not a number"},
        {"ObjVertexTooFew", "v 0 0 0\nv 1 0\nv 0 1 0\nf 1 2 3\n", "line 2: a v line needs 3 numbers, it has 2"},
        {"ObjVertexOverflow", "o bad\nv 0 0 0\nv 1 0 0\nv 0 1 0\nv 1e39 0 0\nf 1 2 3\nf 1 2 4\n",
         "line 5: '1e39' in a v line does not fit a float (floats end at 3.4e38)"},
        {"ObjVertexOverflowDouble", "v 0 0 0\nv 1 0 0\nv 0 1 -0.0001e400\nf 1 2 3\n",
         "line 3: '-0.0001e400' in a v line does not fit a float (floats end at 3.4e38)"},
        {"ObjVertexColourNan", "v 0 0 0 1 0 0\nv 1 0 0 0 nan 0\nv 0 1 0 0 0 1\nf 1 2 3\n",
         "line 2: 'nan' in a v line is not finite"},
        {"ObjNormalTooFew", "v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 1\nf 1//1 2//1 3//1\n",
         "line 4: a vn line needs 3 numbers, it has 2"},
        {"ObjNormalWord", "v 0 0 0\nv 1 0 0\nv 0 1 0\n  vn\t0 0 one\nf 1//1 2//1 3//1\n",
         "line 4: 'one' in a vn line is not a number"},
        {"ObjTexcoordNone", "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt\nf 1/1 2/1 3/1\n",
         "line 4: a vt line needs 1 number, it has 0"},
        {"ObjTexcoordNotUtf8", "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 \xff\nf 1/1 2/1 3/1\n",
         "line 4: '?' in a vt line is not a number"},
    };
    for (const Case& c : cases) {
        const Result<Scene> scene = loadText(c.name, c.text);
        ASSERT_FALSE(scene.ok()) << c.name;
        EXPECT_EQ(scene.error().message, pathOf(c.name) + ": " + c.error);
    }
}

TEST(ObjLoaderTest, NumbersTinyobjloaderReadsAreAccepted) {
    // Signs, no digits before or after the point, exponents, numbers too small for a double or a float
    // (they read as 0), the largest float as 8 digits print it (a little above it, and rounds to it),
    // a comment after the numbers, and other lines that start with v.
    const std::string tiny = "0." + std::string(60, '0') + "1";
    const Result<Scene> scene =
        loadText("ObjNumbers", "v +1 -0 .5e0\nv 1. 1e-400 " + tiny +
                                   "\nv 0 1E+0 0 # top\nv 3.4028235e38 0 -3.4028235e38\nvp 0.5 nan\nvt .25\n"
                                   "vn 0 0 +1\nf 1/1/1 2/1/1 3/1/1\n");
    ASSERT_TRUE(scene.ok()) << scene.error().message;
    ASSERT_EQ(scene->meshes.size(), 1u);
    const Mesh& mesh = scene->meshes[0];
    ASSERT_EQ(mesh.positions.size(), 3u);
    EXPECT_EQ(mesh.positions[0], glm::vec3(1, 0, 0.5f));
    EXPECT_EQ(mesh.positions[1], glm::vec3(1, 0, 0));
    EXPECT_EQ(mesh.positions[2], glm::vec3(0, 1, 0));
    EXPECT_EQ(mesh.uvs[0], glm::vec2(0.25f, 1.0f));
}

}  // namespace
}  // namespace frugal
