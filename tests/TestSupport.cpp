#include "TestSupport.h"

#include <sys/wait.h>

#include <algorithm>
#include <cstdlib>
#include <fstream>
#include <iterator>
#include <sstream>

namespace frugal::test {

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

std::vector<std::string> CliRun::errLines() const {
    std::vector<std::string> lines;
    std::stringstream in(err);
    for (std::string line; std::getline(in, line);) lines.push_back(line);
    return lines;
}

namespace {

std::string quote(const std::string& s) {
    std::string q = "'";
    for (char c : s) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
    return q + "'";
}

}  // namespace

CliRun runFrugal(const fs::path& dir, const std::vector<std::string>& args, const std::string& env) {
    // (An ostringstream, not string +: GCC 12 -O3 reports a false -Wrestrict on the latter.)
    std::ostringstream line;
    line << "cd " << quote(dir.string()) << " && " << env << " " << quote(FRUGAL_CLI);
    for (const std::string& a : args) line << " " << quote(a);
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

int addCameraNode(Scene& scene, Camera camera, const glm::vec3& position) {
    Node node;
    node.translation = position;
    node.camera = int(scene.cameras.size());
    camera.node = int(scene.nodes.size());
    scene.roots.push_back(camera.node);
    scene.nodes.push_back(node);
    scene.cameras.push_back(camera);
    return node.camera;
}

}  // namespace frugal::test
