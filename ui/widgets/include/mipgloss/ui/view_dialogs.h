// The view's dialogs: File → Export image (a size not tied to the window, PNG or linear EXR) and
// Help → Keyboard and mouse shortcuts (made from the window's actions, so it never goes stale).
#pragma once

#include <QDialog>
#include <QList>
#include <QSize>

class QAction;
class QComboBox;
class QSpinBox;

namespace mipgloss::ui {

class ExportImageDialog : public QDialog {
    Q_OBJECT
public:
    enum class Format { Png, Exr };
    // `viewSize` is offered as "the view's size"; `maxSize` is the largest side OpenGL draws.
    ExportImageDialog(QSize viewSize, int maxSize, QWidget* parent = nullptr);
    QSize imageSize() const;
    Format format() const;
    QSpinBox* widthSpin() const { return width_; }
    QSpinBox* heightSpin() const { return height_; }

private:
    QSpinBox* width_ = nullptr;
    QSpinBox* height_ = nullptr;
    QComboBox* format_ = nullptr;
};

class ShortcutsDialog : public QDialog {
    Q_OBJECT
public:
    ShortcutsDialog(const QList<QAction*>& actions, QWidget* parent = nullptr);
    // The rows shown: what, and the keys or mouse gesture.
    const QList<QPair<QString, QString>>& rows() const { return rows_; }

private:
    QList<QPair<QString, QString>> rows_;
};

}  // namespace mipgloss::ui
