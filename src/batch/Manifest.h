// A batch manifest (`frugal batch`, docs/batch.md): the jobs of a dataset or a sweep, each a command
// of the command line on one scene, read and checked in full before any job runs.
//
//   {"frugal_batch": 1,
//    "defaults": {"size": "320x240"},                       // merged under every job's keys
//    "jobs": [{"id": "bunny-orbit", "command": "render", "scene": "bunny.obj",
//              "camera_path": "orbit.json", "frames": "0:99", "settings": {"cull": "conservative"},
//              "outputs": ["color", "depth", "json"]}, ...]}
//
// Paths (scene, camera_path, a settings file) are relative to the manifest's folder. Each job's
// outputs go to OUT/<id>/ under names batch chooses, so two jobs never write one file. Errors name
// the manifest, the line and the field: "m.json line 7: job 2 'bunny': frames: 'x' is not A:B".
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include <frugal/Result.h>

namespace frugal::batch {

enum class Command { Render, CullReport, ReuseBench, Report };
const char* toString(Command command);

struct Job {
    std::string id;           // [A-Za-z0-9._-], 1 to 100, not starting with '.'; default "job-<index>"
    Command command = Command::Render;
    int line = 0;             // of the job's object in the manifest
    // The command's arguments but its outputs: the scene, then flags (paths joined to the manifest's
    // folder, so that they name the same files from where frugal runs).
    std::vector<std::string> args;
    // An inline settings object, as the settings file written beside the job's outputs (render only).
    std::string settingsText;
    // Render's images and records: any of "color", "depth", "ids", "json" (default color and json).
    std::vector<std::string> outputs;
    std::vector<std::string> inputFiles;  // the files it reads: scene, camera path, settings file
    std::string canonical;                // the job's keys after the defaults, as compact JSON
    // For the cost estimate: frames (or views) it renders, and pixels a frame.
    std::int64_t frames = 1;
    std::int64_t pixels = 800 * 600;
    std::string scene;  // the scene argument, for the estimate's triangle count
};

struct Manifest {
    std::string path;  // as given
    std::vector<Job> jobs;
};

// Reads and checks the manifest at `path`: JSON, schema version 1, known keys of the right kinds,
// unique ids, scenes and other input files that exist. Errors: one line, as above.
Result<Manifest> readManifest(const std::string& path);
// The same on text; `path` names it in messages and locates relative paths.
Result<Manifest> parseManifest(std::string_view text, const std::string& path);

// The command line that runs `job` with its outputs in `jobDir` (the command's name first).
std::vector<std::string> commandLine(const Job& job, const std::string& jobDir);

}  // namespace frugal::batch
