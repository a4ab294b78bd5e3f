// `frugal-lab write-bench`'s measurement: what writing a frame's files costs, and whether a sequence
// runs at the speed of rendering.
//
// Part one, the encoder table: each scene's frame is rendered once (colour, depth, ids) and each
// plane encoded `repeat` times per libdeflate level and PNG filter, beside the baseline: the
// encoder frugal had before (no filter, zlib's compress2 at level 6, single-threaded), kept here
// for that purpose. Per row the median time, the bytes, size and speed against the baseline, and
// whether the decoded pixels equal the baseline's. The choice per plane is the fastest level and
// filter (the fastest of each row's repeats, summed over the scenes: noise only ever adds time)
// whose files are at most `sizeLimit` times the baseline's on every scene.
//
// Part two, the sequence: `frames` frames of the first scene per variant, the variants taking turns
// for `rounds` rounds (the machine's noise hits all alike), wall time per frame:
//   render    render and read back only, no file: the floor
//   async     FrameWriter (frugal/Files.h): files encoded and written while the next frame renders
//   async level 1  the same at --png-level 1 (the run-length encoder for every image)
//   sync      writeFrame after each frame, same encoder, one thread
//   baseline  the baseline encoder after each frame: what `frugal render` did before
// once with the colour file alone and once with colour, depth and ids; and one frame at a time
// ("one frame": a writer made, one frame written, finished), async against baseline.
//
// Part three, the read-back (GL backends; a scene the minimal frame draws, lab/MinimalFrame.h):
// the first scene's frame drawn by the fewest GL calls, `readbackFrames` frames per variant, in
// turns for `rounds` rounds, with the colour alone and with colour and depth:
//   draw        drawn and finished, nothing read: the floor
//   readpixels  glFinish, then glReadPixels into memory: what the GL backend does
//   pbo         glReadPixels into a pixel buffer object, then copied out of it
//   pbo, a frame late  frame N read into one of two buffers while frame N-1 is copied out of the
//               other: what a renderer handing frames over one frame late would do
// Each variant's last images are checked equal to glReadPixels'.
#pragma once

#include <functional>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <frugal/Result.h>
#include <frugal/Scene.h>
#include <frugal/Settings.h>

namespace frugal {

struct WriteBenchSettings {
    Settings render;                            // size, backend, threads (ids are turned on)
    std::vector<int> levels{1, 2, 3, 4, 6, 9};  // libdeflate levels in the table
    int repeat = 5;                             // encodings per row (the median is reported)
    double sizeLimit = 1.1;                     // the choice's largest file ÷ the baseline's
    int frames = 30;                            // part two: frames per variant and round; 0 skips it
    int rounds = 3;                             // parts two and three
    int readbackFrames = 30;                    // part three: frames per variant and round; 0 skips it
    std::string dir;  // where part two writes its files, removed after; "": a new folder in the temporary one
};

struct EncodeRow {
    std::string scene, plane;  // plane: "color", "depth", "ids"
    std::string encoder;       // "baseline", "run-length" (level 1) or "libdeflate"
    int level = 0;
    std::string filter;                  // "none", "sub", "up", "paeth"
    double medianMs = 0.0, minMs = 0.0;  // of the repeats
    std::size_t bytes = 0;
    double sizeRatio = 0.0;    // bytes ÷ the baseline's
    double speedup = 0.0;      // the baseline's median ÷ this one's
    bool pixelsEqual = false;  // decoded, the same pixels as the baseline's file
};

struct EncodeChoice {
    std::string plane, filter;
    int level = 0;
    double worstSizeRatio = 0.0, totalMs = 0.0, baselineTotalMs = 0.0;  // ms: the rows' fastest, summed
    bool found = false;                                                 // some level and filter met the size limit
};

struct SequenceRow {
    std::string planes;              // "color" or "color+depth+ids"
    std::string variant;             // "render", "async", "async level 1", "sync", "baseline", "one-frame async"
    std::vector<double> msPerFrame;  // one per round
    double medianMs = 0.0;
    double cpuMs = 0.0;         // the process's CPU time per frame (every thread: llvmpipe's, the writer's), median
    double overRender = 0.0;    // medianMs ÷ the render row's of the same planes
    double overBaseline = 0.0;  // medianMs ÷ the baseline row's of the same planes
    double renderMs = 0.0, readbackMs = 0.0;  // the frames' own medians (render row)
};

struct ReadBackRow {
    std::string planes;              // "color" or "color+depth"
    std::string variant;             // "draw", "readpixels", "pbo", "pbo, a frame late"
    std::vector<double> msPerFrame;  // one per round
    double medianMs = 0.0;
    double overDraw = 0.0;              // medianMs ÷ the draw row's of the same planes
    double overReadPixels = 0.0;        // medianMs ÷ the readpixels row's
    std::optional<bool> pixelsEqual;    // the last frame's images equal glReadPixels' (not for draw)
};

struct WriteBench {
    WriteBenchSettings settings;
    std::vector<std::string> scenes;
    std::vector<EncodeRow> encodes;
    std::vector<EncodeChoice> choices;
    std::string sequenceScene;
    std::vector<SequenceRow> sequence;
    std::string readbackScene, readbackSkipped;  // skipped: why part three did not run
    std::vector<ReadBackRow> readback;
};

// Scenes by name, loaded. `progress` gets a line per scene and variant. Errors: the renderer's,
// an encoder's, a file's (part two).
Result<WriteBench> measureWriteBench(const std::vector<std::pair<std::string, Scene>>& scenes,
                                     const WriteBenchSettings& settings,
                                     const std::function<void(const std::string&)>& progress);

std::string writeBenchJson(const WriteBench& bench);
std::string writeBenchCsv(const WriteBench& bench);  // the encoder table
std::string writeBenchGnuplot(const WriteBench& bench, const std::string& csvPath, const std::string& svgPath);
std::string writeBenchText(const WriteBench& bench);  // the choices and the sequence, for a terminal

}  // namespace frugal
