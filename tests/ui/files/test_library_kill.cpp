// Saves that never corrupt: processes writing a library killed with SIGKILL at random moments
// leave a file that is one of the versions written, never a mixture (atomic_file.h). Two writers:
// tests/tools/library_writer (saveLibrary in an endless loop) and `mipgloss library add`.
#include "mipgloss/ui/library_file.h"
#include "test_support.h"
#include "tools/library_writer.h"

#include <gtest/gtest.h>

#include <QElapsedTimer>
#include <QFile>
#include <QProcess>
#include <QRegularExpression>
#include <QStringList>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <optional>
#include <random>
#include <set>
#include <string>
#include <thread>
#include <vector>

#include <signal.h>

namespace mipgloss {
namespace {

namespace fs = std::filesystem;

QString q(const fs::path& p) { return QString::fromStdString(p.string()); }

// Files in `dir` other than `keep`; each must be a temporary of the atomic write
// ("<keep>.partial-N", mipgloss/io/atomic_write.h: temporaryBeside), which nothing ever reads as a
// library: readers open the library's own name only.
std::vector<std::string> strayFiles(const fs::path& dir, const std::string& keep) {
    std::vector<std::string> strays;
    const QRegularExpression temporary(QRegularExpression::anchoredPattern(
        QRegularExpression::escape(QString::fromStdString(keep)) + "\\.partial-[0-9]{1,6}"));
    for (const fs::directory_entry& e : fs::directory_iterator(dir)) {
        const std::string name = e.path().filename().string();
        if (name == keep) continue;
        EXPECT_TRUE(temporary.match(QString::fromStdString(name)).hasMatch())
            << "an unexpected file beside the library: " << name;
        strays.push_back(name);
    }
    return strays;
}

void sigkill(QProcess& process) {
    ASSERT_EQ(::kill(static_cast<pid_t>(process.processId()), SIGKILL), 0);
    ASSERT_TRUE(process.waitForFinished(10000));
}

// The writer's loop, killed 200 times (40 under a sanitizer: test::kUnderSanitizer) at a random
// moment 0–30 ms after its writes began. Every time,
// the file must be exactly a version the writer wrote: its first k materials for some k >= 1,
// byte for byte as libraryToJson writes them. The file persists from run to run, so each kill
// also tests that a file being replaced stays the old one or becomes the new one.
TEST(LibraryKill, WriterKilledAtRandomMomentsLeavesAVersionItWrote) {
    test::TempDir dir;
    const fs::path lib = dir / "library.json";
    std::mt19937 random(9);  // seeded: the same moments every run
    std::uniform_int_distribution<int> delayMicroseconds(0, 30000);
    constexpr int kRuns = test::kUnderSanitizer ? 40 : 200;
    std::set<int> lengths;
    int changed = 0, leftTemporary = 0;
    QByteArray previous;
    std::set<std::string> strays;
    for (int run = 0; run < kRuns; ++run) {
        QProcess writer;
        writer.start(QStringLiteral(MIPGLOSS_LIBRARY_WRITER), {q(lib)});
        ASSERT_TRUE(writer.waitForStarted(10000));
        while (!writer.canReadLine()) ASSERT_TRUE(writer.waitForReadyRead(10000)) << "no \"writing\" from the writer";
        ASSERT_EQ(writer.readLine().trimmed(), "writing");
        std::this_thread::sleep_for(std::chrono::microseconds(delayMicroseconds(random)));
        sigkill(writer);
        ASSERT_EQ(writer.exitStatus(), QProcess::CrashExit)
            << "the writer ended by itself: " << writer.readAllStandardError().toStdString();

        if (!fs::exists(lib)) {
            // Only before any save has completed.
            ASSERT_TRUE(previous.isEmpty()) << "run " << run << ": the library vanished";
            continue;
        }
        QFile in(q(lib));
        ASSERT_TRUE(in.open(QIODevice::ReadOnly));
        const QByteArray bytes = in.readAll();
        MaterialLibrary read;
        try {
            read = ui::libraryFromJson(bytes, lib);
        } catch (const ui::LibraryFileError& e) {
            FAIL() << "run " << run << ": " << e.what();
        }
        MaterialLibrary prefix;
        for (int i = 0; i < static_cast<int>(read.entries.size()); ++i)
            prefix.entries.push_back(test::libraryWriterEntry(i));
        ASSERT_GE(read.entries.size(), 1u) << "run " << run;
        ASSERT_EQ(read, prefix) << "run " << run << ": not the first " << read.entries.size() << " materials";
        ASSERT_EQ(bytes, ui::libraryToJson(prefix)) << "run " << run << ": not byte for byte a version written";
        lengths.insert(static_cast<int>(read.entries.size()));
        changed += bytes != previous ? 1 : 0;
        previous = bytes;
        const std::vector<std::string> now = strayFiles(dir.path(), "library.json");
        const std::size_t before = strays.size();
        strays.insert(now.begin(), now.end());
        leftTemporary += strays.size() > before ? 1 : 0;
    }
    ASSERT_FALSE(previous.isEmpty()) << "no save completed in " << kRuns << " runs";
    std::printf("[ LibraryKill ] writer: %d kills; the file changed in %d, %zu distinct lengths (%d to %d "
                "materials), %d kills left a temporary of the atomic write (%zu in all)\n",
                kRuns, changed, lengths.size(), *lengths.begin(), *lengths.rbegin(), leftTemporary, strays.size());
}

// The material `mipgloss library add` gives name i in the test below, and its flags.
Material cliMaterial(int i) {
    Material m;
    m.lambda = static_cast<float>(i % 8);
    m.mode = i % 4 == 3 ? LookupMode::Normal : LookupMode::Reflect;
    return m;
}

QStringList cliFlags(int i) {
    const Material m = cliMaterial(i);
    return {"--lambda", QString::number(static_cast<double>(m.lambda)), "--mode", lookupModeName(m.mode)};
}

// `mipgloss library add` killed at a random moment of its run, 50 times (15 under a sanitizer),
// each adding the next
// name. After each: every add that finished (exit 0) is in the file with its parameters, the
// killed one is there whole or not at all, and nothing else is.
TEST(LibraryKill, CliAddKilledAtRandomMomentsKeepsEveryFinishedAdd) {
    test::TempDir dir;
    const fs::path lib = dir / "library.json";
    const auto add = [&](int i) {
        auto process = std::make_unique<QProcess>();
        process->start(QStringLiteral(MIPGLOSS_CLI),
                       QStringList{"library", "add", q(lib), "--name", QStringLiteral("a%1").arg(i)} + cliFlags(i));
        EXPECT_TRUE(process->waitForStarted(10000));
        return process;
    };
    auto first = add(0);
    ASSERT_TRUE(first->waitForFinished(30000));
    ASSERT_EQ(first->exitCode(), 0) << first->readAllStandardError().toStdString();
    // How long a run takes here, T (the median of three `library list`, which start, read and
    // exit as an add does), to place the kills: most of a run is the program starting (loading
    // its libraries), and the library is read and written in its last milliseconds, so the kills
    // fall uniformly between 0.7 T and 1.1 T, where the reading, the writing and the exit are. A
    // choice of moments, never an assertion.
    std::vector<qint64> runs;
    for (int i = 0; i < 3; ++i) {
        QElapsedTimer timer;
        timer.start();
        QProcess list;
        list.start(QStringLiteral(MIPGLOSS_CLI), {"library", "list", q(lib)});
        ASSERT_TRUE(list.waitForFinished(30000));
        runs.push_back(timer.nsecsElapsed() / 1000);
    }
    std::sort(runs.begin(), runs.end());
    const auto runMicroseconds = static_cast<int>(runs[1]);

    std::mt19937 random(9);
    std::uniform_int_distribution<int> delayMicroseconds(runMicroseconds * 7 / 10, runMicroseconds * 11 / 10);
    constexpr int kKills = test::kUnderSanitizer ? 15 : 50;
    std::vector<int> finished{0};
    int killedBefore = 0, killedAfter = 0, finishedFirst = 0;
    std::set<std::string> strays;
    for (int i = 1; i <= kKills; ++i) {
        auto process = add(i);
        std::this_thread::sleep_for(std::chrono::microseconds(delayMicroseconds(random)));
        bool killed = false;
        if (process->state() != QProcess::NotRunning) {
            ::kill(static_cast<pid_t>(process->processId()), SIGKILL);
            killed = true;
        }
        ASSERT_TRUE(process->waitForFinished(30000));
        // A kill that came as the process was exiting by itself does not count as one.
        killed = killed && process->exitStatus() == QProcess::CrashExit;
        if (!killed) {
            ASSERT_EQ(process->exitCode(), 0) << process->readAllStandardError().toStdString();
            finished.push_back(i);
            ++finishedFirst;
        }

        MaterialLibrary library;
        try {
            library = ui::loadLibrary(lib);
        } catch (const ui::LibraryFileError& e) {
            FAIL() << "after add " << i << ": " << e.what();
        }
        // The names in the order added, each with its parameters; the finished ones all there.
        std::set<int> present;
        int last = -1;
        for (const LibraryMaterial& entry : library.entries) {
            const int n = std::stoi(entry.name.substr(1));
            ASSERT_EQ(entry.name, "a" + std::to_string(n));
            ASSERT_GT(n, last) << "out of order or repeated: " << entry.name;
            ASSERT_LE(n, i) << "a name never added: " << entry.name;
            EXPECT_EQ(entry.material, cliMaterial(n)) << entry.name << " is not as added";
            last = n;
            present.insert(n);
        }
        for (int n : finished) ASSERT_TRUE(present.contains(n)) << "a" << n << " finished but is missing";
        if (killed) (present.contains(i) ? killedAfter : killedBefore) += 1;
        const std::vector<std::string> now = strayFiles(dir.path(), "library.json");
        strays.insert(now.begin(), now.end());
    }
    std::printf("[ LibraryKill ] library add: a run takes %.1f ms here; of %d runs %d finished before the kill, "
                "%d were killed before their save landed and %d after it; %zu temporaries of the atomic write left\n",
                runMicroseconds / 1000.0, kKills, finishedFirst, killedBefore, killedAfter, strays.size());
}

}  // namespace
}  // namespace mipgloss
