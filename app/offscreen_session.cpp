#include "offscreen_session.h"

#include "cli_args.h"

#include "mipgloss/ui/gl_format.h"

#include <cstdlib>
#include <stdexcept>

namespace mipgloss::app {

namespace {

// Qt aborts when it cannot reach a display; say so first, with the fix.
bool haveDisplay() {
    const char* platform = std::getenv("QT_QPA_PLATFORM");
    if (platform && std::string(platform).rfind("xcb", 0) != 0 && std::string(platform).rfind("wayland", 0) != 0)
        return true;  // some other platform plugin: let Qt decide
    return std::getenv("DISPLAY") || std::getenv("WAYLAND_DISPLAY");
}

}  // namespace

OffscreenSession::OffscreenSession(const char* argv0, const std::string& command) {
    if (!haveDisplay())
        throw std::runtime_error(command + " needs an X display for OpenGL (DISPLAY is not set); run it as: "
                                 "xvfb-run -a mipgloss " + command + " ...");
    argv_[0] = const_cast<char*>(argv0);
    ui::setDefaultSurfaceFormat();
    app_ = std::make_unique<QGuiApplication>(argc_, argv_);
    renderer_ = std::make_unique<ui::OffscreenRenderer>();
    std::string error;
    if (!renderer_->initialize(&error)) throw std::runtime_error(error);
}

// GL teardown while the application exists.
OffscreenSession::~OffscreenSession() { renderer_.reset(); }

void checkRenderSize(const ui::OffscreenRenderer& renderer, const std::string& sizeFlag, int w, int h,
                     std::optional<int> samples) {
    const ui::RenderSizeLimits limits = renderer.maxRenderSize();
    const std::string size = std::to_string(w) + "x" + std::to_string(h);
    if (w > limits.maxWidth)
        throw UsageError(sizeFlag + " " + size + ": the width " + std::to_string(w) + " is beyond this OpenGL's limit of " +
                         std::to_string(limits.maxWidth) + " (" + limits.widthLimit + ")");
    if (h > limits.maxHeight)
        throw UsageError(sizeFlag + " " + size + ": the height " + std::to_string(h) + " is beyond this OpenGL's limit of " +
                         std::to_string(limits.maxHeight) + " (" + limits.heightLimit + ")");
    if (samples && *samples > limits.maxSamples)
        throw UsageError("--samples " + std::to_string(*samples) + " is beyond this OpenGL's limit of " +
                         std::to_string(limits.maxSamples) + " (GL_MAX_SAMPLES)");
}

}  // namespace mipgloss::app
