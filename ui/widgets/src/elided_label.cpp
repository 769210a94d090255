#include "elided_label.h"

#include <QFontMetrics>
#include <QResizeEvent>

namespace mipgloss::ui {

ElidedLabel::ElidedLabel(const QString& objectName, QWidget* parent) : QLabel(parent) {
    setObjectName(objectName);
    setTextFormat(Qt::PlainText);
}

void ElidedLabel::setWholeText(const QString& text) {
    whole_ = text;
    setToolTip(text);
    updateGeometry();
    elide();
}

QSize ElidedLabel::sizeHint() const {
    const QMargins m = contentsMargins();
    return {fontMetrics().horizontalAdvance(whole_) + m.left() + m.right() + 2 * margin(), QLabel::sizeHint().height()};
}

QSize ElidedLabel::minimumSizeHint() const { return {0, QLabel::minimumSizeHint().height()}; }

void ElidedLabel::resizeEvent(QResizeEvent* event) {
    QLabel::resizeEvent(event);
    elide();
}

void ElidedLabel::elide() {
    // elidedText cuts some texts that fit their horizontalAdvance (measured here with a glyph
    // from a fallback font, "²"): given exactly its sizeHint, the label shows the whole text.
    const int room = contentsRect().width() - 2 * margin();
    const QFontMetrics metrics = fontMetrics();
    setText(metrics.horizontalAdvance(whole_) <= room ? whole_ : metrics.elidedText(whole_, Qt::ElideRight, room));
}

}  // namespace mipgloss::ui
