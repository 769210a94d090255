// mipgloss-gui: the desktop material previewer. A thin shell over mipgloss::ui::MainWindow.
//
//   mipgloss-gui [FILES...]                 scenes (.mipgloss, or .json from older versions),
//                                           material libraries (.mglib: imported into the user's
//                                           library), meshes, environment images or folders; an
//                                           autosave a crashed session left is offered first
//   mipgloss-gui --help | --version         answered without a display (before QApplication)
//   mipgloss-gui --time-to-first-frame      prints the time from process start to the first frame
//                                           drawn with the environment, then exits
//   mipgloss-gui --screenshot FILE          saves the first complete frame to FILE, then exits
//
// Exit status: 0 done, 1 bad arguments, 2 no usable OpenGL, 3 timed out, 4 screenshot not written.
#include "material_args.h"
#include "process_memory.h"

#include "mipgloss/ui/atomic_file.h"
#include "mipgloss/ui/environment_manager.h"
#include "mipgloss/ui/gl_format.h"
#include "mipgloss/ui/main_window.h"
#include "mipgloss/ui/scene_document.h"
#include "mipgloss/ui/viewport.h"

#include <QApplication>
#include <QIcon>
#include <QCommandLineParser>
#include <QElapsedTimer>
#include <QFileInfo>
#include <QImage>
#include <QTimer>

#include <time.h>
#include <unistd.h>

#include <cstdio>
#include <cstring>
#include <fstream>
#include <iterator>
#include <sstream>
#include <string>

namespace {

// Milliseconds since the kernel started this process (/proc/self/stat field 22, in clock ticks
// since boot, against CLOCK_BOOTTIME): the dynamic loading and static initialisation before
// main. 0 when unavailable. Resolution one clock tick (usually 10 ms).
double processAgeMs() {
    std::ifstream in("/proc/self/stat");
    std::string stat((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    // Field 2, the command name, is in parentheses and may hold spaces: count after the last ')'.
    const std::size_t close = stat.rfind(')');
    if (close == std::string::npos) return 0.0;
    std::istringstream fields(stat.substr(close + 1));
    std::string field;
    unsigned long long startTicks = 0;
    for (int i = 3; i <= 22 && fields >> field; ++i)
        if (i == 22) startTicks = std::stoull(field);
    const long ticksPerSecond = sysconf(_SC_CLK_TCK);
    timespec now{};
    if (startTicks == 0 || ticksPerSecond <= 0 || clock_gettime(CLOCK_BOOTTIME, &now) != 0)
        return 0.0;
    const double nowMs = static_cast<double>(now.tv_sec) * 1e3 + static_cast<double>(now.tv_nsec) * 1e-6;
    const double startMs =
        static_cast<double>(startTicks) * 1e3 / static_cast<double>(ticksPerSecond);
    return nowMs > startMs ? nowMs - startMs : 0.0;
}

// Names QStandardPaths and QSettings place the user's files by: the library, autosaves
// (~/.local/share/mipgloss/mipgloss/) and settings (~/.config/mipgloss/mipgloss.conf); --version.
void setApplicationInfo() {
    QCoreApplication::setOrganizationName(QStringLiteral("mipgloss"));
    QCoreApplication::setApplicationName(QStringLiteral("mipgloss"));
    QCoreApplication::setApplicationVersion(QStringLiteral(MIPGLOSS_VERSION));
}

// The command line, described once: the parser answering --help and --version without a display
// is the one that reads the arguments of a real run.
struct GuiOptions {
    QCommandLineOption time{
        QStringLiteral("time-to-first-frame"),
        QStringLiteral("Print the time from process start to the first frame drawn with the "
                       "environment ready, then exit.")};
    QCommandLineOption screenshot{
        QStringLiteral("screenshot"),
        QStringLiteral("Save the first complete frame (environment built, imports done) to <file>, "
                       "then exit."),
        QStringLiteral("file")};
    QCommandLineOption timeout{
        QStringLiteral("timeout"),
        QStringLiteral("Give up on --time-to-first-frame or --screenshot after <seconds> "
                       "(default 300; at most 86400, a day)."),
        QStringLiteral("seconds"), QStringLiteral("300")};
    QCommandLineOption wholeWindow{
        QStringLiteral("whole-window"),
        QStringLiteral("With --screenshot: the whole window (panels and all), not just the view.")};

    void describe(QCommandLineParser& parser) const {
        parser.setApplicationDescription(
            QStringLiteral("Blurry, glossy and diffuse reflections from one cube-map mip chain"));
        parser.addHelpOption();
        parser.addVersionOption();
        parser.addOptions({time, screenshot, timeout, wholeWindow});
        parser.addPositionalArgument(
            QStringLiteral("files"),
            QStringLiteral("Scene (.mipgloss or .json), material library (.mglib), mesh or "
                           "environment files to open."),
            QStringLiteral("[files...]"));
    }
};

// QApplication needs a display; --help and --version must answer without one (a terminal on a
// server, help2man at package build time), so they are spotted before it is made.
bool asksForHelpOrVersion(int argc, char** argv) {
    for (int i = 1; i < argc; ++i) {
        if (std::strcmp(argv[i], "--") == 0) return false;
        for (const char* flag : {"-h", "-?", "--help", "--help-all", "-v", "--version"})
            if (std::strcmp(argv[i], flag) == 0) return true;
    }
    return false;
}

}  // namespace

int main(int argc, char** argv) {
    QElapsedTimer clock;
    clock.start();
    const double beforeMainMs = processAgeMs();
    auto sinceStartMs = [&] { return beforeMainMs + static_cast<double>(clock.nsecsElapsed()) * 1e-6; };

    const GuiOptions options;
    if (asksForHelpOrVersion(argc, argv)) {
        QCoreApplication core(argc, argv);
        setApplicationInfo();
        // Only here, where no file is placed: --version names this program, not the data folder.
        QCoreApplication::setApplicationName(QStringLiteral("mipgloss-gui"));
        QCommandLineParser parser;
        options.describe(parser);
        parser.process(core);  // prints the help or the version and exits
        return 0;
    }

    mipgloss::ui::setDefaultSurfaceFormat();  // before any widget or context exists
    QApplication app(argc, argv);
    setApplicationInfo();
    QApplication::setWindowIcon(QIcon(QStringLiteral(":/mipgloss/desktop/mipgloss.png")));
    QApplication::setDesktopFileName(QStringLiteral("mipgloss"));

    QCommandLineParser parser;
    options.describe(parser);
    parser.process(app);

    const bool timing = parser.isSet(options.time);
    const QString screenshot = parser.value(options.screenshot);
    // The numbers `mipgloss` reads, read the same way (app/material_args.h); at most a day, so the
    // timer's milliseconds fit an int.
    int timeoutSeconds = 0;
    try {
        timeoutSeconds = mipgloss::app::parseWholeNumber("--timeout", parser.value(options.timeout).toStdString(), 1, 86400);
    } catch (const mipgloss::app::UsageError& e) {
        std::fprintf(stderr, "mipgloss-gui: %s\n", e.what());
        return 1;
    }

    mipgloss::ui::MainWindow window;
    window.show();
    // Measuring or capturing runs unattended: no question about an autosave then.
    const bool unattended = timing || !screenshot.isEmpty();
    if (!unattended) window.offerAutosaveRestore();
    // Meshes given here are the scene (Figure 1 only when nothing is given).
    window.openFiles(parser.positionalArguments(), /*meshesOpen=*/true);
    if (!unattended) return QApplication::exec();

    // Measuring or capturing: wait for a frame drawn with the environment uploaded.
    mipgloss::ui::Viewport* viewport = window.viewport();
    mipgloss::ui::EnvironmentManager* environments = window.environments();
    double environmentReadyMs = -1.0;
    if (environments->current()) environmentReadyMs = sinceStartMs();
    QObject::connect(environments, &mipgloss::ui::EnvironmentManager::environmentReady, &app, [&] {
        if (environmentReadyMs < 0.0) environmentReadyMs = sinceStartMs();
    });
    QObject::connect(viewport, &mipgloss::ui::Viewport::glFailed, &app, [&](const QString& message) {
        std::fprintf(stderr, "mipgloss-gui: OpenGL: %s\n", qPrintable(message));
        QCoreApplication::exit(2);
    });
    bool done = false;
    double firstFrameMs = -1.0;
    QObject::connect(viewport, &mipgloss::ui::Viewport::frameDrawn, &app, [&](quint64) {
        const auto current = environments->current();
        if (done || !current || viewport->counters().baseUploads == 0) return;
        // The environment asked for (a file given on the command line replaces the default).
        if (current->settings.source != window.document()->scene().environment.source) return;
        // The first frame drawn with it: its imported cube, the filtered chain maybe not yet.
        if (firstFrameMs < 0.0) firstFrameMs = sinceStartMs();
        // Then the whole scene: the complete environment, no build or import still under way.
        if (!current->complete() || environments->busy() || window.importing() || viewport->decodingTextures()) return;
        done = true;
        if (timing) {
            std::printf("first frame: %.0f ms (imported cube); complete frame: %.0f ms (environment "
                        "ready at %.0f ms); peak memory %.0f MiB\n",
                        firstFrameMs, sinceStartMs(), environmentReadyMs, mipgloss::app::processStatusMiB("VmHWM"));
            std::fflush(stdout);
        }
        // Outside paintGL: grabbing renders the widget again.
        QTimer::singleShot(0, &app, [&] {
            if (!screenshot.isEmpty()) {
                const QImage image = parser.isSet(options.wholeWindow) ? window.grab().toImage()
                                                                       : viewport->grabFramebuffer();
                QByteArray format = QFileInfo(screenshot).suffix().toUpper().toLatin1();
                if (format.isEmpty()) format = "PNG";
                try {
                    if (image.isNull()) throw mipgloss::FileError(screenshot.toStdString(), "nothing was drawn");
                    mipgloss::ui::writeFileAtomically(screenshot.toStdString(), [&](QIODevice& device) {
                        return image.save(&device, format.constData());
                    });
                } catch (const mipgloss::FileError& e) {
                    std::fprintf(stderr, "mipgloss-gui: could not write the screenshot: %s\n", e.what());
                    QCoreApplication::exit(4);
                    return;
                }
            }
            QCoreApplication::exit(0);
        });
    });
    // The frame after a finished build or import may already have been drawn: ask for another.
    QObject::connect(environments, &mipgloss::ui::EnvironmentManager::busyChanged, viewport,
                     qOverload<>(&QWidget::update));
    QObject::connect(&window, &mipgloss::ui::MainWindow::importFinished, viewport,
                     qOverload<>(&QWidget::update));
    QTimer::singleShot(timeoutSeconds * 1000, &app, [&] {
        std::fprintf(stderr, "mipgloss-gui: no complete frame within %d s\n", timeoutSeconds);
        QCoreApplication::exit(3);
    });
    return QApplication::exec();
}
