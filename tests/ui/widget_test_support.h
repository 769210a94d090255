// Helpers for the widget tests: real key input and waiting on the event loop.
#pragma once

#include <QAbstractSpinBox>
#include <QElapsedTimer>
#include <QString>
#include <QTest>

#include <functional>

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

}  // namespace mipgloss::test
