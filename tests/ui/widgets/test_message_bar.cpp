// The message rule (message_bar.h): an error shows whole in the banner and its first line in the
// status line; information only in the status line, its lines joined; a later success of the
// same kind takes an error's banner down, another kind's leaves it. And the window shows a message
// made while it is being built (an unreadable library), before its status bar had its label.
#include "mipgloss/ui/library_file.h"
#include "mipgloss/ui/main_window.h"
#include "mipgloss/ui/message_bar.h"

#include "widget_test_support.h"

#include <gtest/gtest.h>

#include <QFile>
#include <QLabel>
#include <QSignalSpy>
#include <QStatusBar>
#include <QToolButton>

#include <filesystem>
#include <system_error>

using namespace mipgloss;
using namespace mipgloss::ui;

namespace {

struct Bar {
    QWidget window;
    QStatusBar* statusBar = new QStatusBar(&window);
    MessageBar* bar = new MessageBar(statusBar, &window);

    bool bannerShown() const { return !bar->isHidden(); }
    QString bannerText() const { return bar->findChild<QLabel*>(QStringLiteral("messageText"))->text(); }
    QString statusLine() const { return statusBar->findChild<QLabel*>(QStringLiteral("statusMessage"))->toolTip(); }
};

}  // namespace

TEST(MessageBar, AnErrorIsInTheBannerWholeAndItsFirstLineInTheStatusLine) {
    Bar b;
    EXPECT_FALSE(b.bannerShown());
    QSignalSpy shown(b.bar, &MessageBar::messageShown);
    const QString error = QStringLiteral("bunny.obj: line 12: a face with 1 vertex\nand more detail");
    b.bar->showMessage(error, true, /*log=*/false);
    EXPECT_TRUE(b.bannerShown());
    EXPECT_EQ(b.bannerText(), error);
    EXPECT_EQ(b.bar->statusText(), error);
    const auto* label = b.statusBar->findChild<QLabel*>(QStringLiteral("statusMessage"));
    ASSERT_NE(label, nullptr) << "the status line is in the status bar";
    EXPECT_EQ(label->toolTip(), error) << "the whole message in the tooltip";
    EXPECT_FALSE(label->text().contains(QStringLiteral("more detail"))) << "one line: the first";
    EXPECT_EQ(b.bar->lastMessage(), error);
    EXPECT_TRUE(b.bar->lastMessageIsError());
    ASSERT_EQ(shown.count(), 1);
    EXPECT_TRUE(shown.front().at(1).toBool());

    // Information: the status line only, lines joined; the banner stays until dismissed.
    b.bar->showMessage(QStringLiteral("Imported a\nwith a warning"), false);
    EXPECT_TRUE(b.bannerShown());
    EXPECT_EQ(b.bannerText(), error);
    EXPECT_FALSE(b.bar->lastMessageIsError());
    EXPECT_TRUE(b.statusBar->findChild<QLabel*>(QStringLiteral("statusMessage"))->toolTip().contains(QLatin1Char('\n')));
    auto* dismiss = b.bar->findChild<QToolButton*>(QStringLiteral("dismissMessage"));
    ASSERT_NE(dismiss, nullptr);
    dismiss->click();
    EXPECT_FALSE(b.bannerShown());
    b.bar->clearStatus();
    EXPECT_TRUE(b.bar->statusText().isEmpty());
}

TEST(MessageBar, ALaterSuccessOfTheSameKindTakesTheBannerDown) {
    Bar b;
    b.bar->showMessageOf(MessageBar::Kind::Meshes, QStringLiteral("no_faces.obj: no faces"), true, false);
    ASSERT_TRUE(b.bannerShown());
    b.bar->showMessageOf(MessageBar::Kind::Scene, QStringLiteral("Opened good.mipgloss"), false);
    EXPECT_TRUE(b.bannerShown()) << "a scene opened says nothing about the mesh that failed";
    b.bar->showMessage(QStringLiteral("Saved good.mipgloss"), false);
    EXPECT_TRUE(b.bannerShown()) << "a message of no kind says nothing either";
    b.bar->showMessageOf(MessageBar::Kind::Meshes, QStringLiteral("Imported tetra.obj"), false);
    EXPECT_FALSE(b.bannerShown()) << "the mesh import succeeded";

    // An error of no kind (saving, exporting) stays until dismissed, whatever succeeds after.
    b.bar->showMessage(QStringLiteral("shot.png: its folder is not writable"), true, false);
    for (MessageBar::Kind kind : {MessageBar::Kind::Scene, MessageBar::Kind::Environment, MessageBar::Kind::Meshes,
                                  MessageBar::Kind::Library, MessageBar::Kind::Other})
        b.bar->showMessageOf(kind, QStringLiteral("done"), false);
    EXPECT_TRUE(b.bannerShown());

    // The rule alone, for a message shown elsewhere (the library dock's).
    b.bar->showMessageOf(MessageBar::Kind::Library, QStringLiteral("absent.mglib: not found"), true, false);
    b.bar->noteOutcome(MessageBar::Kind::Library, false);
    EXPECT_FALSE(b.bannerShown());
}

TEST(MessageBar, AMessageUntilTheNextOneIsReplacedByIt) {
    Bar b;
    b.bar->showUntilNextMessage(QStringLiteral("Opening environment sky.exr…"));
    EXPECT_EQ(b.bar->statusText(), QStringLiteral("Opening environment sky.exr…"));
    EXPECT_FALSE(b.bannerShown());
    b.bar->showMessageOf(MessageBar::Kind::Environment, QStringLiteral("Loaded sky.exr"), false);
    EXPECT_EQ(b.bar->statusText(), QStringLiteral("Loaded sky.exr"));
}

// Bug, found moving the rule out of the window: the library is opened while the window builds its
// docks, before the status bar had its message label, so an unreadable library's message was
// shown into no label, and the window crashed.
TEST(MainWindow, AnUnreadableLibraryAtStartIsAnErrorInTheBanner) {
    QStandardPaths::setTestModeEnabled(true);
    const std::filesystem::path library = defaultLibraryPath();
    std::filesystem::create_directories(library.parent_path());
    const std::filesystem::path kept = library.string() + ".kept";
    std::error_code none;
    std::filesystem::rename(library, kept, none);  // an earlier test's library, put back below
    {
        QFile f(QString::fromStdString(library.string()));
        ASSERT_TRUE(f.open(QIODevice::WriteOnly));
        f.write("{ not a library");
    }
    {
        MainWindow w;
        EXPECT_TRUE(w.lastMessageIsError());
        EXPECT_TRUE(w.lastMessage().contains(QStringLiteral("could not be read"))) << w.lastMessage().toStdString();
        EXPECT_FALSE(w.findChild<QWidget*>(QStringLiteral("messageBanner"))->isHidden());
    }
    std::filesystem::remove(library);
    std::filesystem::rename(kept, library, none);
}
