// What the commands that draw (render, bench-render, library thumbnails) need for as long as they
// run: a Qt application and an offscreen OpenGL context.
#pragma once

#include "mipgloss/ui/offscreen.h"

#include <QGuiApplication>

#include <memory>
#include <optional>
#include <string>

namespace mipgloss::app {

class OffscreenSession {
public:
    // Throws (a message naming `command` and the fix) when there is no display, where Qt would
    // abort, or no OpenGL 4.1 core context.
    OffscreenSession(const char* argv0, const std::string& command);
    ~OffscreenSession();
    OffscreenSession(const OffscreenSession&) = delete;
    OffscreenSession& operator=(const OffscreenSession&) = delete;

    ui::OffscreenRenderer& renderer() { return *renderer_; }

private:
    int argc_ = 1;
    char* argv_[2] = {nullptr, nullptr};
    std::unique_ptr<QGuiApplication> app_;
    std::unique_ptr<ui::OffscreenRenderer> renderer_;
};

// Refuses, before anything is drawn, a size or a sample count this OpenGL cannot draw
// (RenderSizeLimits), naming the flag, the value and the limit: a UsageError.
void checkRenderSize(const ui::OffscreenRenderer& renderer, const std::string& sizeFlag, int w, int h,
                     std::optional<int> samples);

}  // namespace mipgloss::app
