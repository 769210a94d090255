// Helpers for the widget tests: real key input and waiting on the event loop.
#pragma once

#include "mipgloss/scene/scene.h"
#include "mipgloss/ui/main_window.h"

#include <gtest/gtest.h>

#include <QAbstractSpinBox>
#include <QElapsedTimer>
#include <QSize>
#include <QStandardPaths>
#include <QString>
#include <QTest>

#include <functional>
#include <memory>
#include <string>

namespace mipgloss::test {

// Replaces a spin box's text the way a user does: select all, type, press Enter (the panel's
// spin boxes commit on Enter, not per keystroke).
inline void typeInto(QAbstractSpinBox* spin, const QString& text) {
    spin->setFocus();
    spin->selectAll();
    QTest::keyClicks(spin, text);
    QTest::keyClick(spin, Qt::Key_Return);
}

// Processes events until `done` holds; false after `timeoutMs`.
inline bool waitUntil(const std::function<bool()>& done, int timeoutMs) {
    QElapsedTimer timer;
    timer.start();
    while (!done()) {
        if (timer.elapsed() > timeoutMs) return false;
        QTest::qWait(10);
    }
    return true;
}

// The embedded courtyard (or `source`) at a face of 32, so an environment manager's builds and
// the thumbnails' environment are quick to make.
inline EnvironmentSettings smallEnvironment(const std::string& source = kBuiltinEnvironment) {
    EnvironmentSettings settings;
    settings.source = source;
    settings.faceSize = 32;
    return settings;
}

// A window that keeps to the test's folders (QStandardPaths test mode: autosaves, settings) and
// discards unsaved changes without a dialog when a test opens or makes a new scene over them;
// shown at `size`, not maximised (as the window opens the first time), whatever the screen.
inline std::unique_ptr<ui::MainWindow> openWindow(QSize size = QSize(1200, 760)) {
    QStandardPaths::setTestModeEnabled(true);
    auto w = std::make_unique<ui::MainWindow>();
    w->prompts().saveChanges = [](const QString&) { return ui::MainWindow::SaveChoice::Discard; };
    w->setWindowState(Qt::WindowNoState);
    w->resize(size);
    w->show();
    EXPECT_TRUE(QTest::qWaitForWindowExposed(w.get()));
    return w;
}

}  // namespace mipgloss::test
