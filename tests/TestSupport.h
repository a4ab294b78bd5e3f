// Helpers shared by the test suites.
#pragma once

#include <cstring>
#include <filesystem>
#include <initializer_list>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include <frugal/Scene.h>

namespace frugal::test {

// Folder for images and other files a test writes (actual/expected/diff on failure).
std::filesystem::path outputDir();
// A fresh empty folder under outputDir() for one test.
std::filesystem::path freshDir(const std::string& name);
// Writes `text` to `path` (creating folders).
void writeFile(const std::filesystem::path& path, const std::string& text);
// The whole file, or "" when it cannot be read.
std::string readAll(const std::filesystem::path& path);
// The names of the entries of `dir`, sorted.
std::vector<std::string> filesIn(const std::filesystem::path& dir);

// Values as the bytes a glTF buffer holds them in (little-endian host, like glTF).
template <class T>
std::string bytesOf(const T* values, std::size_t count) {
    std::string out(count * sizeof(T), '\0');
    if (count > 0) std::memcpy(out.data(), values, out.size());
    return out;
}
template <class T>
std::string bytesOf(std::initializer_list<T> values) { return bytesOf(values.begin(), values.size()); }
template <class T>
std::string bytesOf(const std::vector<T>& values) { return bytesOf(values.data(), values.size()); }
// `bytes` in base64 with padding, as a data URI holds them.
std::string base64(const std::string& bytes);

// `text` split at line breaks (no empty last line for a final break).
std::vector<std::string> lines(const std::string& text);
// The fields of a CSV line with no quoted field; a final comma gives an empty last field.
std::vector<std::string> csvFields(const std::string& line);
// `args` joined by spaces, for a trace of a command line.
std::string joined(const std::vector<std::string>& args);

// `text` in the shell's single quotes.
std::string shellQuoted(const std::string& text);
// Whether gnuplot is on PATH.
bool haveGnuplot();

// Skipping. A test skips only for what it cannot change: no GL backend on this machine (frugal's
// exit status 3, ErrorKind::BackendUnavailable), or a dependency that is not installed (gnuplot,
// glmark2-data's bunny, assimp-testmodels). Under FRUGAL_TEST_STRICT=1, which scripts/test sets
// (CI always has llvmpipe and installs every dependency), such a skip is a failure instead, so a
// regression cannot hide behind one. A skip for anything else (not built, a sanitizer, no cgroup)
// is GTEST_SKIP.
bool strictSkips();
// Skips the test (GTEST_SKIP) with "<what>: <message>", or under strictness fails it (GTEST_FAIL).
void skipOrFail(const char* what, const std::string& message);
#define FRUGAL_SKIP_IF_NO_GL(message) \
    return ::frugal::test::skipOrFail("no GL backend", (::testing::Message() << message).GetString())
#define FRUGAL_SKIP_IF_MISSING(message) \
    return ::frugal::test::skipOrFail("not installed", (::testing::Message() << message).GetString())
// Runs gnuplot on `script`; returns its exit status, with its messages in `messages`.
int runGnuplot(const std::filesystem::path& script, std::string& messages);

// The `frugal` binary run in a child process: exit status, stdout and stderr.
struct CliRun {
    int status = -1;  // the exit status, or 128 + signal number
    std::string out, err;
    std::vector<std::string> errLines() const;
};

// frugal-lab's own commands (the research tree's), which frugal does not have.
inline const std::vector<std::string> kLabCommands = {"bench",     "reuse-bench", "order-bench",
                                                      "hsr-bench", "span-bench",  "state-sim",
                                                      "soak",      "write-bench", "shading-bench",
                                                      "pose-bench"};
// The binary that runs `args`: frugal-lab (FRUGAL_LAB_CLI) for its own commands (and their help),
// else frugal (FRUGAL_CLI).
const char* binaryFor(const std::vector<std::string>& args);

// Runs the binary of `args` (binaryFor) with `args` in `dir`, with an optional environment prefix
// such as "GALLIUM_DRIVER=x". Its stdout/stderr go through files in `dir` that are removed after.
CliRun runFrugal(const std::filesystem::path& dir, const std::vector<std::string>& args, const std::string& env = "");
// The same with frugal-lab, whatever the command (a batch of research jobs).
CliRun runLab(const std::filesystem::path& dir, const std::vector<std::string>& args, const std::string& env = "");

// A mesh of separate triangles, three positions each (normals +z): tests that draw triangles alone.
Mesh looseTriangles(const std::vector<glm::vec3>& positions);
// A scene with one root node drawing `mesh` with `material` (the mesh gets material 0).
Scene oneMeshScene(Mesh mesh, const Material& material = {});

// A scene with morph targets and large deformations: a sphere of 2 targets (an inflation with its
// normals, and a wave that moves vertices sideways by up to 0.6) drawn by an animated node whose
// weights run through (0, 0), (−1, 10), (1, −1), (10, 0.5) and (0.3, 0.3) (not summing to 1) over
// 4 s, linearly, and by a node of its own fixed weights `still`; beside them three static spheres,
// single- and double-sided. Built in memory (buildInstances called).
Scene morphingScene(std::vector<float> still = {0.5f, -0.5f});

// A scene with a skin: a tube along y, skinned to three joints in a chain (root, middle, top) whose
// weights blend by height, drawn by a node placed apart from the joints; the middle joint turns by
// up to 120 degrees and back over 4 s, and the top one is scaled by `topScale` at 0 and 4 s and by
// 1 at 2 s (a scale of 0 and of 10⁴ are the extremes); with `affine` false the weights sum to 0.7
// or 1.3 instead of 1. Beside it two static spheres. Built in memory (buildInstances called).
Scene skinnedScene(float topScale = 2.0f, bool affine = true);

// A scene of points and line segments among triangles: three static spheres; a ring of 48
// segments (a closed loop, lit: it has normals) that turns and sweeps through them over 4 s; a
// static grid of 400 points (no normals) partly behind the spheres; and a static strip of
// segments in front of them whose vertices include repeated ones (zero-length segments). Built in
// memory (buildInstances called).
Scene pointsLinesScene();

// Gives a third of the scene's meshes a blended material and a third a masked one (each a copy of
// its material), with vertex alphas that vary across every mesh (from its positions): masked
// triangles get holes at the cutoff of 0.5, blended ones a range of coverage. For checking that a
// method stays exact with alpha; call it before anything reorders or uploads the meshes.
void addAlpha(Scene& scene);
// Adds a root node at `position`, looking down -z, that carries `camera`; returns the camera's index.
int addCameraNode(Scene& scene, SceneCamera camera, const glm::vec3& position);

// A Radiance .hdr file of `width` × `height` linear rgb pixels (rows top first), each written as
// RGBE (exact for values m · 2^e with m < 256 of 8 bits), its scan lines run-length encoded (the
// new scheme) or flat.
std::string radianceFile(int width, int height, const std::vector<float>& rgb, bool rle = true);
// The sky the environment tests light with: blue above (brighter toward the zenith), brown below,
// and a small sun of radiance 40 toward (0.5, 0.7, 0.3).
std::vector<float> testSky(int width, int height);

}  // namespace frugal::test
