// A user's program: a three-frame sequence of builtin:dominoes with culling, temporal reuse and a
// draw order, through the installed library's public API alone, its files written by a
// FrameWriter; they are compared with the installed command line's (CMakeLists.txt). Usage:
// consumer FOLDER.
#include <cstdio>
#include <string>

#include <frugal/frugal.h>

int main(int argc, char** argv) {
    if (argc != 2) return std::fprintf(stderr, "usage: consumer FOLDER\n"), 2;
    const std::string folder = argv[1];
    frugal::Result<frugal::Scene> scene = frugal::loadScene("builtin:dominoes");
    if (!scene) return std::fprintf(stderr, "error: %s\n", scene.error().message.c_str()), 1;
    frugal::Result<frugal::Renderer> renderer =
        frugal::Renderer::create(std::move(*scene), {.width = 160,
                                                     .height = 120,
                                                     .cull = frugal::Cull::Conservative,
                                                     .order = frugal::Order::Key,
                                                     .reuse = true,
                                                     .ids = true});
    if (!renderer) return std::fprintf(stderr, "error: %s\n", renderer.error().message.c_str()), 3;
    // The files are written by a FrameWriter while the next frame renders, as the command line
    // writes them; the frame's memory comes back from write() for the next render.
    frugal::FrameWriter writer;
    frugal::Frame frame;
    for (int i = 0; i < 3; ++i) {
        frugal::Result<bool> rendered =
            renderer->render(frugal::Camera::fromScene(0), i / renderer->scene().fps, frame);
        if (!rendered) return std::fprintf(stderr, "error: %s\n", rendered.error().message.c_str()), 1;
        std::printf("frame %d: %.2f ms (%s)\n", i, frame.stats.renderMs,
                    frame.stats.reuse ? frugal::toString(frame.stats.reuse->mode) : "-");
        const std::string n = std::to_string(i);
        frugal::Result<bool> queued = writer.write(
            {folder + "/api_" + n + ".png", folder + "/api_depth_" + n + ".pfm", folder + "/api_ids_" + n + ".png"},
            frame);
        if (!queued) return std::fprintf(stderr, "error: %s\n", queued.error().message.c_str()), 1;
    }
    if (frugal::Result<bool> written = writer.finish(); !written)
        return std::fprintf(stderr, "error: %s\n", written.error().message.c_str()), 1;
    return 0;
}
