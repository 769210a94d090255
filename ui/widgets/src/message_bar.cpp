#include "mipgloss/ui/message_bar.h"

#include "elided_label.h"

#include <QColor>
#include <QHBoxLayout>
#include <QPalette>
#include <QStatusBar>
#include <QTimer>
#include <QToolButton>

#include <iostream>

namespace mipgloss::ui {

MessageBar::MessageBar(QStatusBar* statusBar, QWidget* parent) : QWidget(parent) {
    setObjectName(QStringLiteral("messageBanner"));
    setAutoFillBackground(true);
    QPalette bannerPalette = palette();
    bannerPalette.setColor(QPalette::Window, QColor(0xf8, 0xd7, 0xda));
    bannerPalette.setColor(QPalette::WindowText, QColor(0x58, 0x15, 0x1c));
    setPalette(bannerPalette);
    auto* layout = new QHBoxLayout(this);
    layout->setContentsMargins(8, 4, 4, 4);
    text_ = new QLabel(this);
    text_->setObjectName(QStringLiteral("messageText"));
    text_->setWordWrap(true);
    text_->setTextInteractionFlags(Qt::TextSelectableByMouse);
    auto* dismiss = new QToolButton(this);
    dismiss->setObjectName(QStringLiteral("dismissMessage"));
    dismiss->setText(QStringLiteral("✕"));
    dismiss->setToolTip(tr("Dismiss"));
    dismiss->setAutoRaise(true);
    connect(dismiss, &QToolButton::clicked, this, &QWidget::hide);
    layout->addWidget(text_, 1);
    layout->addWidget(dismiss, 0, Qt::AlignTop);
    hide();

    // The message takes the room the status bar's permanent widgets leave (they get theirs first).
    statusLine_ = new ElidedLabel(QStringLiteral("statusMessage"), statusBar);
    statusLine_->setSizePolicy(QSizePolicy::Ignored, QSizePolicy::Preferred);
    statusBar->addWidget(statusLine_, 1);
    statusTimer_ = new QTimer(this);
    statusTimer_->setSingleShot(true);
    connect(statusTimer_, &QTimer::timeout, this, [this] {
        statusLine_->setWholeText(QString());
        statusText_.clear();
    });
}

void MessageBar::showMessage(const QString& message, bool error, bool log) {
    lastMessage_ = message;
    lastMessageIsError_ = error;
    if (error) {
        text_->setText(message);
        show();
        bannerKind_ = Kind::Other;  // showMessageOf names the kind
        showStatus(message, 30000);
        if (log) std::cerr << "mipgloss: " << message.toStdString() << '\n';
    } else {
        showStatus(message, 8000);
    }
    emit messageShown(message, error);
}

void MessageBar::showMessageOf(Kind kind, const QString& message, bool error, bool log) {
    showMessage(message, error, log);
    noteOutcome(kind, error);
}

void MessageBar::noteOutcome(Kind kind, bool error) {
    if (error)
        bannerKind_ = kind;
    else if (kind != Kind::Other && bannerKind_ == kind)
        hide();  // what failed has been done since (message_bar.h: Kind)
}

void MessageBar::showUntilNextMessage(const QString& message) {
    showMessage(message, false);
    statusTimer_->stop();
}

void MessageBar::clearStatus() { showStatus(QString(), 0); }

void MessageBar::showStatus(const QString& message, int timeoutMs) {
    // One line: an error's first (the banner has the rest), a message's lines joined.
    const QString line = message.contains(QLatin1Char('\n')) && lastMessageIsError_
                             ? message.section(QLatin1Char('\n'), 0, 0)
                             : QString(message).replace(QLatin1Char('\n'), QLatin1Char(' '));
    statusLine_->setWholeText(line);
    statusLine_->setToolTip(message);
    statusText_ = message;
    if (timeoutMs > 0 && !message.isEmpty())
        statusTimer_->start(timeoutMs);
    else
        statusTimer_->stop();
}

}  // namespace mipgloss::ui
