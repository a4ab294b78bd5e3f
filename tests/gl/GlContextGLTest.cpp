// GL contexts and backend selection: each kind creates a current 3.3+ core context, `auto` logs
// one line per attempt, bad choices and a bad GALLIUM_DRIVER give one-line errors and never crash.
//
// GALLIUM_DRIVER is read by Mesa when it first makes a screen (OSMesa keeps one per process), so
// those tests re-run this binary in a fresh process with the variable set: a hook that runs before
// main() sees FRUGAL_GL_TEST_CHILD, does the one thing asked, prints the outcome and exits. The
// parent's contexts and environment are untouched, and a crash in the child shows as a signal.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

#include "gl/GlApi.h"
#include "gl/GlBackend.h"
#include "gl/GlContext.h"

namespace frugal {
namespace {

bool built(ContextKind kind) {
    for (ContextKind k : availableContextKinds())
        if (k == kind) return true;
    return false;
}

// The child's side: "ok <renderer>" or "error <message>" on stdout, exit 0.
std::string childAction(const std::string& action) {
    Result<std::unique_ptr<Backend>> backend = Error{"unknown child action " + action};
    if (action == "osmesa-context") {
        Result<std::unique_ptr<GlContext>> context = createOsMesaContext();
        return context ? "ok context" : "error " + context.error().message;
    }
    std::vector<std::string> log;
    if (action == "osmesa") backend = createGlBackend(BackendChoice::OsMesa, &log);
    if (action == "egl") backend = createGlBackend(BackendChoice::Egl, &log);
    if (!backend) return "error " + backend.error().message;
    return "ok " + (*backend)->renderer();
}

[[maybe_unused]] const int kChildHook = [] {
    const char* action = std::getenv("FRUGAL_GL_TEST_CHILD");
    if (action == nullptr) return 0;
    const std::string outcome = childAction(action);
    std::fwrite(outcome.data(), 1, outcome.size(), stdout);
    std::fflush(stdout);
    _exit(0);  // no gtest, no atexit handlers
}();

// Runs `action` in a fresh copy of this binary with GALLIUM_DRIVER=`driver`. Returns what the child
// printed, or "killed by signal N" / "exit N" when it did not finish normally.
std::string inChild(const char* action, const char* driver) {
    int fds[2];
    if (pipe(fds) != 0) return "pipe failed";
    const pid_t pid = fork();
    if (pid == 0) {
        dup2(fds[1], STDOUT_FILENO);
        close(fds[0]);
        close(fds[1]);
        setenv("GALLIUM_DRIVER", driver, 1);
        setenv("FRUGAL_GL_TEST_CHILD", action, 1);
        execl("/proc/self/exe", "frugal_gl_tests", static_cast<char*>(nullptr));
        _exit(127);
    }
    close(fds[1]);
    std::string output;
    char buffer[512];
    for (ssize_t n; (n = read(fds[0], buffer, sizeof buffer)) > 0;) output.append(buffer, std::size_t(n));
    close(fds[0]);
    int status = 0;
    waitpid(pid, &status, 0);
    if (WIFSIGNALED(status)) return "killed by signal " + std::to_string(WTERMSIG(status));
    if (WEXITSTATUS(status) != 0) return "exit " + std::to_string(WEXITSTATUS(status)) + ": " + output;
    return output;
}

TEST(GlContextGLTest, KindNamesAndOrder) {
    EXPECT_STREQ(contextKindName(ContextKind::EglDevice), "egl-device");
    EXPECT_STREQ(contextKindName(ContextKind::EglSurfaceless), "egl-surfaceless");
    EXPECT_STREQ(contextKindName(ContextKind::OsMesa), "osmesa");
    const std::vector<ContextKind> kinds = availableContextKinds();
    ASSERT_FALSE(kinds.empty());
    // The order `auto` tries them in.
    for (std::size_t i = 1; i < kinds.size(); ++i) EXPECT_LT(int(kinds[i - 1]), int(kinds[i]));
}

TEST(GlContextGLTest, EachKindGivesACurrentCoreContext) {
    for (ContextKind kind : availableContextKinds()) {
        SCOPED_TRACE(contextKindName(kind));
        Result<std::unique_ptr<GlContext>> context = kind == ContextKind::EglDevice ? createEglDeviceContext(true)
                                                     : kind == ContextKind::OsMesa  ? createOsMesaContext()
                                                                                    : createEglSurfacelessContext();
        ASSERT_TRUE(context) << context.error().message;
        EXPECT_EQ((*context)->kind(), kind);
        EXPECT_FALSE((*context)->description().empty());
        EXPECT_NE((*context)->getProcAddress("glBlitFramebuffer"), nullptr);
        EXPECT_NE((*context)->getProcAddress("glClear"), nullptr);  // a GL 1.0 entry point too
        EXPECT_TRUE((*context)->makeCurrent());
        // The context is current right away: glGetIntegerv answers.
        using GetIntegerv = void (*)(unsigned, int*);
        auto getIntegerv = reinterpret_cast<GetIntegerv>((*context)->getProcAddress("glGetIntegerv"));
        ASSERT_NE(getIntegerv, nullptr);
        int major = 0, minor = 0, profile = 0;
        getIntegerv(0x821B /*GL_MAJOR_VERSION*/, &major);
        getIntegerv(0x821C /*GL_MINOR_VERSION*/, &minor);
        getIntegerv(0x9126 /*GL_CONTEXT_PROFILE_MASK*/, &profile);
        EXPECT_GE(major * 10 + minor, 33);
        EXPECT_EQ(profile & 1 /*GL_CONTEXT_CORE_PROFILE_BIT*/, 1);
    }
}

// Contexts of different platforms on one thread: each makeCurrent must reach its own context.
// (Mesa 22 + libglvnd: without releasing the EGL context first, eglMakeCurrent after an
// OSMesaMakeCurrent is a no-op and GL calls land in the OSMesa context.)
TEST(GlContextGLTest, ContextsOfDifferentKindsTakeTurns) {
    std::vector<std::unique_ptr<GlContext>> contexts;
    for (ContextKind kind : availableContextKinds()) {
        Result<std::unique_ptr<GlContext>> context = kind == ContextKind::EglDevice ? createEglDeviceContext(true)
                                                     : kind == ContextKind::OsMesa  ? createOsMesaContext()
                                                                                    : createEglSurfacelessContext();
        ASSERT_TRUE(context) << context.error().message;
        contexts.push_back(std::move(*context));
    }
    if (contexts.size() < 2) GTEST_SKIP() << "one context kind only";
    using ClearColor = void (*)(float, float, float, float);
    using GetFloatv = void (*)(unsigned, float*);
    const auto red = [&](GlContext& c) {
        float value[4] = {-1, -1, -1, -1};
        reinterpret_cast<GetFloatv>(c.getProcAddress("glGetFloatv"))(0x0C22 /*GL_COLOR_CLEAR_VALUE*/, value);
        return value[0];
    };
    for (std::size_t i = 0; i < contexts.size(); ++i) {
        ASSERT_TRUE(contexts[i]->makeCurrent());
        reinterpret_cast<ClearColor>(contexts[i]->getProcAddress("glClearColor"))(0.125f * float(i + 1), 0, 0, 0);
    }
    for (int round = 0; round < 2; ++round) {
        for (std::size_t i = 0; i < contexts.size(); ++i) {
            ASSERT_TRUE(contexts[i]->makeCurrent());
            EXPECT_EQ(red(*contexts[i]), 0.125f * float(i + 1)) << contextKindName(contexts[i]->kind());
        }
        std::reverse(contexts.begin(), contexts.end());
        for (std::size_t i = 0; i < contexts.size(); ++i) {
            ASSERT_TRUE(contexts[i]->makeCurrent());
            EXPECT_EQ(red(*contexts[i]), 0.125f * float(contexts.size() - i)) << contextKindName(contexts[i]->kind());
        }
        std::reverse(contexts.begin(), contexts.end());
    }
    // Destroying the current one leaves the others usable.
    contexts.back().reset();
    ASSERT_TRUE(contexts.front()->makeCurrent());
    EXPECT_EQ(red(*contexts.front()), 0.125f);
}

// A real context whose getProcAddress can hide one entry point or swap in a replacement.
class DoctoredContext final : public GlContext {
public:
    DoctoredContext(std::unique_ptr<GlContext> real, std::string name, void* replacement)
        : real_(std::move(real)), name_(std::move(name)), replacement_(replacement) {}
    ContextKind kind() const override { return real_->kind(); }
    void* getProcAddress(const char* name) const override {
        return name_ == name ? replacement_ : real_->getProcAddress(name);
    }
    bool makeCurrent() override { return real_->makeCurrent(); }
    std::string description() const override { return real_->description(); }
    GlContext& real() { return *real_; }

private:
    std::unique_ptr<GlContext> real_;
    std::string name_;
    void* replacement_;
};

std::unique_ptr<GlContext> anyContext() {
    for (ContextKind kind : availableContextKinds()) {
        Result<std::unique_ptr<GlContext>> context = kind == ContextKind::OsMesa      ? createOsMesaContext()
                                                     : kind == ContextKind::EglDevice ? createEglDeviceContext(true)
                                                                                      : createEglSurfacelessContext();
        if (context) return std::move(*context);
    }
    return nullptr;
}

TEST(GlContextGLTest, AMissingEntryPointIsNamed) {
    std::unique_ptr<GlContext> real = anyContext();
    ASSERT_NE(real, nullptr);
    const std::string kind = contextKindName(real->kind());
    DoctoredContext doctored(std::move(real), "glMultiDrawArrays", nullptr);
    GlApi api;
    EXPECT_EQ(api.load(doctored), "GL entry point glMultiDrawArrays not found (" + kind + ")");
    EXPECT_EQ(api.load(doctored.real()), "");
    EXPECT_NE(api.MultiDrawArrays, nullptr);
    // And no backend is made on such a context.
    std::unique_ptr<GlContext> again = anyContext();
    ASSERT_NE(again, nullptr);
    EXPECT_EQ(makeGlBackend(std::make_unique<DoctoredContext>(std::move(again), "glBlitFramebuffer", nullptr)).error().message,
              kind + ": GL entry point glBlitFramebuffer not found (" + kind + ")");
}

// glShaderSource replaced by one that hands GL a broken shader: the backend is not made.
PFNGLSHADERSOURCEPROC gRealShaderSource = nullptr;
void APIENTRY brokenShaderSource(GLuint shader, GLsizei, const GLchar* const*, const GLint*) {
    const char* broken = "#version 330 core\nvoid main() { this is not glsl }\n";
    gRealShaderSource(shader, 1, &broken, nullptr);
}

TEST(GlContextGLTest, AShaderThatDoesNotCompileFailsTheBackend) {
    std::unique_ptr<GlContext> real = anyContext();
    ASSERT_NE(real, nullptr);
    gRealShaderSource = reinterpret_cast<PFNGLSHADERSOURCEPROC>(real->getProcAddress("glShaderSource"));
    ASSERT_NE(gRealShaderSource, nullptr);
    Result<std::unique_ptr<Backend>> backend = makeGlBackend(
        std::make_unique<DoctoredContext>(std::move(real), "glShaderSource", reinterpret_cast<void*>(&brokenShaderSource)));
    ASSERT_FALSE(backend);
    EXPECT_NE(backend.error().message.find("mesh"), std::string::npos) << backend.error().message;
    EXPECT_EQ(backend.error().message.find('\n'), std::string::npos) << "one line";
}

TEST(GlContextGLTest, EglDeviceSkipsSoftwareDevicesUnlessAllowed) {
    if (!built(ContextKind::EglDevice)) GTEST_SKIP() << "EGL not built";
    Result<std::unique_ptr<GlContext>> any = createEglDeviceContext(true);
    ASSERT_TRUE(any) << any.error().message;
    Result<std::unique_ptr<GlContext>> hardware = createEglDeviceContext(false);
    if (hardware) {
        EXPECT_EQ(hardware.value()->description().find("(software)"), std::string::npos)
            << hardware.value()->description();
    } else {
        // A machine without a GPU (this project's CI): the one software device is skipped, and said so.
        EXPECT_EQ(hardware.error().message.rfind("egl-device: no hardware EGL device (", 0), 0u) << hardware.error().message;
        EXPECT_NE(hardware.error().message.find("software device"), std::string::npos) << hardware.error().message;
        EXPECT_NE(any.value()->description().find("(software)"), std::string::npos) << any.value()->description();
    }
}

TEST(GlContextGLTest, ParseBackendChoice) {
    const struct {
        const char* text;
        BackendChoice choice;
    } good[] = {{"auto", BackendChoice::Auto},
                {"egl", BackendChoice::Egl},
                {"egl-device", BackendChoice::EglDevice},
                {"egl-surfaceless", BackendChoice::EglSurfaceless},
                {"osmesa", BackendChoice::OsMesa}};
    for (const auto& g : good) {
        Result<BackendChoice> r = parseBackendChoice(g.text);
        ASSERT_TRUE(r) << g.text;
        EXPECT_EQ(*r, g.choice) << g.text;
    }
    for (const char* bad : {"", "EGL", "gl", "osmesa "}) {
        Result<BackendChoice> r = parseBackendChoice(bad);
        EXPECT_FALSE(r) << "'" << bad << "'";
        EXPECT_EQ(r.error().message, std::string("unknown GL backend '") + bad +
                                 "' (expected auto, egl, egl-device, egl-surfaceless or osmesa)");
    }
}

TEST(GlContextGLTest, AutoLogsEveryAttemptAndSaysWhatItChose) {
    std::vector<std::string> log;
    Result<std::unique_ptr<Backend>> backend = createGlBackend(BackendChoice::Auto, &log);
    ASSERT_TRUE(backend) << backend.error().message;
    ASSERT_FALSE(log.empty());
    const std::string& last = log.back();
    EXPECT_EQ(last.rfind((*backend)->name() + ": ok (", 0), 0u) << last;
    EXPECT_NE(last.find((*backend)->renderer()), std::string::npos) << last;
    // Lines before the chosen one are failures, each naming its kind.
    for (std::size_t i = 0; i + 1 < log.size(); ++i) {
        EXPECT_EQ(log[i].find(": ok"), std::string::npos) << log[i];
        EXPECT_TRUE(log[i].rfind("egl-device: ", 0) == 0 || log[i].rfind("egl-surfaceless: ", 0) == 0) << log[i];
    }
}

TEST(GlContextGLTest, EachChoiceCreatesItsKind) {
    const struct {
        BackendChoice choice;
        ContextKind kind;
    } cases[] = {{BackendChoice::EglSurfaceless, ContextKind::EglSurfaceless},
                 {BackendChoice::EglDevice, ContextKind::EglDevice},
                 {BackendChoice::OsMesa, ContextKind::OsMesa}};
    for (const auto& c : cases) {
        if (!built(c.kind)) continue;
        std::vector<std::string> log;
        Result<std::unique_ptr<Backend>> backend = createGlBackend(c.choice, &log);
        ASSERT_TRUE(backend) << backend.error().message;
        EXPECT_EQ((*backend)->name(), contextKindName(c.kind));
        EXPECT_EQ(log.size(), 1u);
    }
}

TEST(GlContextGLTest, OsMesaRefusesAnUnknownGalliumDriverWithoutCrashing) {
    if (!built(ContextKind::OsMesa)) GTEST_SKIP() << "OSMesa not built";
    EXPECT_EQ(inChild("osmesa-context", "nonexistent"),
              "error osmesa: GALLIUM_DRIVER=nonexistent is not a driver OSMesa has (llvmpipe, "
              "softpipe); unset it or pick one");
    // Through createGlBackend: one line, listing the attempt.
    EXPECT_EQ(inChild("osmesa", "nonexistent"),
              "error no usable GL context: osmesa: GALLIUM_DRIVER=nonexistent is not a driver "
              "OSMesa has (llvmpipe, softpipe); unset it or pick one");
    // The same in this process, with the variable restored afterwards: the check comes before
    // OSMesa is touched, so it holds even once OSMesa has a screen.
    const char* saved = std::getenv("GALLIUM_DRIVER");
    const std::string savedValue = saved ? saved : "";
    setenv("GALLIUM_DRIVER", "nonexistent", 1);
    Result<std::unique_ptr<GlContext>> context = createOsMesaContext();
    if (saved)
        setenv("GALLIUM_DRIVER", savedValue.c_str(), 1);
    else
        unsetenv("GALLIUM_DRIVER");
    EXPECT_FALSE(context);
}

TEST(GlContextGLTest, OsMesaAcceptsSoftpipe) {
    if (!built(ContextKind::OsMesa)) GTEST_SKIP() << "OSMesa not built";
    const std::string outcome = inChild("osmesa", "softpipe");
    EXPECT_EQ(outcome.rfind("ok softpipe; ", 0), 0u) << outcome;
}

TEST(GlContextGLTest, EglWithAnUnknownGalliumDriverFailsCleanlyAndSaysWhy) {
    if (!built(ContextKind::EglSurfaceless)) GTEST_SKIP() << "EGL not built";
    const std::string outcome = inChild("egl", "nonexistent");
    EXPECT_EQ(outcome.rfind("error no usable GL context: egl-device: ", 0), 0u) << outcome;
    // Mesa 22 fails in eglInitialize; the message says so and points at the variable.
    const std::string surfaceless =
        "; egl-surfaceless: no EGL display (eglInitialize failed: "
        "EGL_NOT_INITIALIZED) (GALLIUM_DRIVER=nonexistent is set)";
    EXPECT_NE(outcome.find(surfaceless), std::string::npos) << outcome;
    EXPECT_EQ(outcome.find('\n'), std::string::npos);
}

}  // namespace
}  // namespace frugal
