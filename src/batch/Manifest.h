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
//
// A job may read a file an earlier job writes: "settings": "bunny-report/settings.json", whose
// first part is the id of a job of the manifest, names OUT/bunny-report/settings.json (a file
// beside the manifest of that path is named "./bunny-report/settings.json"). The check knows the
// file will be there: the job that writes it exists, comes earlier, and writes it (producedFiles).
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include <frugal/Result.h>

namespace frugal::batch {

enum class Command { Render, CullReport, ReuseBench, Report };
const char* toString(Command command);

// A file a job reads that an earlier job of the manifest writes, found in OUT when the job runs.
struct ProducedInput {
    std::string flag;        // the command's flag that takes it ("--settings")
    std::size_t job = 0;     // the index of the job that writes it, below the reader's
    std::string path;        // "<id>/<name>", relative to OUT
};

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
    std::vector<ProducedInput> reads;     // the files it reads that earlier jobs write, in key order
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

// What a file a job writes is, for a job that reads it: a settings file, or a record no key reads.
enum class FileKind { Settings, Record };
struct ProducedFile {
    std::string name;  // in OUT/<id>/
    FileKind kind;
};
// The files `job` writes under fixed names that another job may read, images aside (no key reads
// an image): a report's settings.json, report.json, ...; a render's render.json, and settings.json
// when its settings are inline; cull-report's and reuse-bench's JSON and CSV.
std::vector<ProducedFile> producedFiles(const Job& job);

// The command line that runs `job` with its outputs in `out`/<id>/ and the files it reads of other
// jobs in `out` (the command's name first).
std::vector<std::string> commandLine(const Job& job, const std::string& out);

}  // namespace frugal::batch
