// Image files, top row first as every viewer expects, written all or nothing: to a temporary file in
// the same folder, then renamed (an interrupted program never leaves a half-written image).
//   colour: 8-bit RGBA PNG;
//   depth:  16-bit grey PNG, 0 near, 65535 far (d24: the top 16 of its 24 bits; d32f: (1 − window z)
//           · 65535 rounded), with the format and the planes it was drawn with in tEXt chunks
//           (depth_format, depth_znear, depth_zfar, depth_projection, depth_encoding); or PFM, the
//           window z as float32, exact (d32f: reversed, 1 near, 0 far);
//   ids:    8-bit RGBA PNG whose bytes are the 32-bit id, little-endian (R = bits 0-7); 0 is the
//           background;
//   linear colour (Settings::linear): PFM ("PF": rgb as float32, exact, alpha left out), or 16-bit
//           RGBA PNG, each channel clamped to [0, 1] and rounded to 65535 steps, with a gAMA chunk of
//           1.0 (the values are linear light).
// Errors (ErrorKind::Io): "<path>: <why>", e.g. "out.png: write failed after 4096 of 9120 bytes:
// File too large", with nothing left behind.
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include <frugal/Image.h>
#include <frugal/Result.h>

namespace frugal {

// PNG compression level, 0 to 12: 0 stores the pixels uncompressed (fastest to write, largest);
// 1 is frugal's run-length deflate (src/io/RunDeflate.h: matches that repeat the pixel to the
// left only, several times faster than a general deflate, files somewhat larger); 2 to 12 are
// libdeflate's levels (smaller files, slower; 12 the smallest). kAutoPngLevel, the default, gives
// each kind of image the fastest level whose files stayed within 1.1 times those of frugal's old
// zlib encoder on every scene measured (docs/writing.md, at 1080p): colour 3, depth 1, ids 6.
inline constexpr int kMaxPngLevel = 12;
inline constexpr int kRunLengthPngLevel = 1;
inline constexpr int kAutoPngLevel = -1;
inline constexpr int kDefaultPngLevel = kAutoPngLevel;

// Error for a level out of range: "PNG encoder: the level must be 0 to 12 (or -1: auto), got 13" (BadInput).
Result<bool> writePng(const std::string& path, const ColorImage& image, int level = kDefaultPngLevel);
Result<bool> writePng(const std::string& path, const DepthImage& image, int level = kDefaultPngLevel);
Result<bool> writePfm(const std::string& path, const DepthImage& image);
Result<bool> writePng(const std::string& path, const IdImage& image, int level = kDefaultPngLevel);
Result<bool> writePfm(const std::string& path, const LinearImage& image);
Result<bool> writePng(const std::string& path, const LinearImage& image, int level = kDefaultPngLevel);

// A frame's files as `frugal render` writes them, as one set: each to a temporary name, then all
// renamed together (a set is never half renamed, and on an error none of it is left). An empty path
// is not written; depth and linear colour are PFM when their path ends in .pfm (any case), else
// 16-bit PNG. Error for ids asked of a frame without them: "ids <path>: the frame has no ids
// (Settings::ids)", and the like for linear colour (Settings::linear) (BadInput).
struct FramePaths {
    std::string color, depth, ids, linear;
};
struct Frame;
Result<bool> writeFrame(const FramePaths& paths, const Frame& frame, int pngLevel = kDefaultPngLevel);

// Writes frames' files on threads of its own while the caller renders the next frame: the PNG
// encoder, not the renderer, would otherwise set the pace of a sequence (a 1080p colour PNG takes
// about as long to encode as the frame takes to draw).
//
//   FrameWriter writer;
//   Frame frame;
//   for (int i = 0; i < 100; ++i) {
//       renderer.render(Camera::orbit(...), 0.0, frame);
//       if (Result<bool> queued = writer.write({"out_" + std::to_string(i) + ".png"}, frame); !queued) ...
//   }
//   if (Result<bool> done = writer.finish(); !done) ...
//
// Each frame's files are written as writeFrame() writes them (a set, all or nothing), and frames
// reach the disk in the order they were given: when frame N's files exist, so do those of every
// frame before it. At most `queue` frames are held at once (write() waits for room), so memory
// stays flat however long the sequence. The first error (a full disk, a folder that is not there)
// stops the writer: the frames after it are not written, and write() and finish() return it. The
// destructor waits for the frames given (their errors unreported: call finish() to see them).
// A FrameWriter is used from one thread at a time.
class FrameWriter {
public:
    struct Options {
        int threads = 0;  // encoding threads; 0: one per core, at most 4
        int queue = 0;    // frames held at once, rendered but not yet written; 0: threads + 1
        int pngLevel = kDefaultPngLevel;
    };
    // Errors (BadInput): "png-level 13: must be 0 (fastest, largest) to 12 (smallest, slowest), or
    // auto (-1)", "writer threads 65: ...", "writer queue 0: ...".
    static Result<FrameWriter> create(const Options& options);
    FrameWriter();  // the default options
    FrameWriter(FrameWriter&& other) noexcept;
    FrameWriter& operator=(FrameWriter&& other) noexcept;
    FrameWriter(const FrameWriter&) = delete;
    FrameWriter& operator=(const FrameWriter&) = delete;
    ~FrameWriter();

    // Queues `frame`'s files for `paths`, taking its images; `frame` is left holding the images of
    // a frame already written (or none), memory to render the next frame into, so that a loop of
    // render() and write() allocates nothing a frame. Waits while `queue` frames are held. Errors:
    // writeFrame's for a frame without ids asked for ids; an earlier frame's write error.
    Result<bool> write(const FramePaths& paths, Frame& frame);
    // Waits until every frame given is written; the first error, if any.
    Result<bool> finish();

    // The frames written since the last call, in the order given: the how-manieth write() each
    // came from (0 first) and what encoding and writing its files took, in milliseconds.
    struct Written {
        std::size_t index = 0;
        double encodeMs = 0.0, writeMs = 0.0;
    };
    std::vector<Written> takeWritten();
    int threads() const;

private:
    struct Impl;
    explicit FrameWriter(std::unique_ptr<Impl> impl);
    std::unique_ptr<Impl> impl_;
};

// Other files, written as the images are: all or nothing. Error (Io): "<path>: <why>".
Result<bool> writeFile(const std::string& path, std::string_view bytes);
// A whole file, such as a settings file or a manifest; nothing when it cannot be read.
std::optional<std::string> readFile(const std::string& path);
// Whether `path` ends in `extension` (".pfm"), in any case: how writeFrame tells a PFM depth file
// from a PNG one.
bool hasExtension(const std::string& path, const std::string& extension);
// Why `path` cannot name a linear colour file (FramePaths::linear): "name it .pfm (float32) or .png
// (16-bit)"; "" when it ends in either. The command line and Python refuse such a name up front.
std::string linearPathProblem(const std::string& path);

// Several files that appear together or not at all (a report's JSON, CSV and script; a frame's
// images). commit() writes each to a temporary name in its folder, created exclusively, and only
// when every write succeeded renames them into place; if a rename fails, the files already renamed
// are taken back (a file that existed before gets its old contents back). A file given as an
// encoder's error fails the commit before anything is written. SIGINT, SIGTERM and SIGHUP wait
// while it runs. A link is followed (its file replaced, the link kept); a device or a pipe
// (/dev/null, a terminal) is written in place.
class FileSet {
public:
    void add(std::string path, Result<std::vector<std::uint8_t>> bytes);
    void add(std::string path, std::string_view text);
    Result<bool> commit();
    bool empty() const { return files_.empty(); }

private:
    std::vector<std::pair<std::string, Result<std::vector<std::uint8_t>>>> files_;
};

}  // namespace frugal
