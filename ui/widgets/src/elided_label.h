// A one-line label for a status bar. QLabel cuts a long text off at its edge (or, in a layout,
// makes its least width the whole text's). This one shows its text cut short (…) to the width it
// has, keeps the whole text in its tooltip, asks for the whole text's width and gets by with none,
// so it never sets the window's least width.
#pragma once

#include <QLabel>
#include <QString>

namespace mipgloss::ui {

class ElidedLabel : public QLabel {
public:
    // Plain text, named `objectName`.
    ElidedLabel(const QString& objectName, QWidget* parent);

    void setWholeText(const QString& text);

    QSize sizeHint() const override;
    QSize minimumSizeHint() const override;

protected:
    void resizeEvent(QResizeEvent* event) override;

private:
    void elide();

    QString whole_;
};

}  // namespace mipgloss::ui
