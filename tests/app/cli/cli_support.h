// The `mipgloss` command line as a user runs it, for the tests that drive it (MIPGLOSS_CLI): its
// exit status (-1 when it did not exit normally: a crash) and what it printed.
#pragma once

#include <QProcess>
#include <QString>
#include <QStringList>

#include <filesystem>
#include <string>

namespace mipgloss::test {

// A path as one argument of the command line.
inline QString q(const std::filesystem::path& p) { return QString::fromStdString(p.string()); }

struct CliResult {
    int exitCode = -1;
    std::string out, err;
};

inline CliResult runCli(const QStringList& args, int timeoutMs = 180000) {
    QProcess process;
    process.start(QStringLiteral(MIPGLOSS_CLI), args);
    process.waitForFinished(timeoutMs);
    return {process.exitStatus() == QProcess::NormalExit ? process.exitCode() : -1,
            process.readAllStandardOutput().toStdString(), process.readAllStandardError().toStdString()};
}

}  // namespace mipgloss::test
