// Keeps the scene's environment ready: imports and builds off the UI thread (one worker, newest
// request wins, older ones cancelled), while the previous environment stays current and usable.
// A new import becomes current twice: first early, as soon as its base exists (chain, filter and
// irradiance still null: the renderer draws the base as the mirror and GL's box mips of it for
// λ > 0), then complete. Until the early one arrives the previous environment stays current; a
// request for another file while one is read cancels it, and it never becomes current (a request
// for the same file with other needs lets the import finish and starts from it).
// It watches a SceneDocument and asks for exactly what the scene needs (environment.h): a change
// of λ inside the filtered levels, of mode or of tint builds nothing. Once the scene's λ values
// have rested for kSettleMs, it makes the lobe stack's entries they read (lobes.h, lobesInUse) on
// the same worker, so the settled picture shows each material's exact lobe; then, one per job and
// without counting as busy, the rest of the stack nearest first (lobesNear; 2.3 s at face 128,
// 5.6 s at 256 on 2 cores), so a slider moving anywhere reads exact lobes at once.
#pragma once

#include "mipgloss/scene/environment.h"
#include "mipgloss/ui/background_worker.h"
#include "mipgloss/scene/lobes.h"

#include <QObject>
#include <QString>
#include <QTimer>

#include <cstdint>
#include <map>
#include <memory>
#include <vector>

namespace mipgloss::ui {

class SceneDocument;

// Imports, chains and irradiance maps count the work done, whether or not what it made became
// current (a job that finished although it was cancelled counts); work a cancellation cut short
// does not.
struct EnvironmentCounters {
    std::uint64_t imports = 0;           // files (or the embedded default) read
    std::uint64_t importsCancelled = 0;  // imports a cancellation cut short
    std::uint64_t earlyEnvironments = 0; // early environments made current (a new import, drawn
                                         // before its chain)
    std::uint64_t chainBuilds = 0;       // mip chains built
    std::uint64_t irradianceBuilds = 0;  // irradiance maps computed
    std::uint64_t failures = 0;
    std::uint64_t lobeBuilds = 0;        // lobe stack entries made and kept (of the current environment)
};

class EnvironmentManager : public QObject {
    Q_OBJECT
public:
    explicit EnvironmentManager(QObject* parent = nullptr);
    ~EnvironmentManager() override;  // cancels and waits for the worker

    // Follows the document: environment settings and the scene's needs.
    void watch(SceneDocument* document);

    // Makes sure the environment satisfies (settings, needs); starts a job if it does not.
    void request(const EnvironmentSettings& settings, const ChainNeeds& needs);

    // Before watch(): starts from `environment`, made by another manager (a comparison's shadow
    // scene, viewport.h). It is current at once; a request it satisfies builds nothing, one with
    // the same file and another builder starts from its imported cube instead of reading the file
    // again. Ignored once this manager has an environment of its own.
    void startFrom(std::shared_ptr<const PreparedEnvironment> environment);

    // The environment to draw with; null until the first one is ready. Every new chain or
    // irradiance map comes as a new object, so the renderer uploads only when the pointer changes.
    // May be an early one (complete() false) while its chain is built; stack entries are never made
    // from that (it has no filter).
    std::shared_ptr<const PreparedEnvironment> current() const { return current_; }

    bool busy() const { return busy_ || lobeBusy_; }
    // Whether lobe stack entries are being made (those in use, or quietly those near them).
    bool makingLobes() const { return lobeJob_ != nullptr; }

    // The lobe stack's entries made for the current environment (those in use and near them).
    std::vector<std::shared_ptr<const LobeStackEntry>> lobes() const;
    // How long λ must rest before the stack entries it needs are made.
    static constexpr int kSettleMs = 150;

    // The settings of the last request that failed. The manager does not retry them by itself (a
    // scene change would otherwise re-read a bad file every time); an explicit open calls
    // forgetFailure() first so a file the user has fixed is read again.
    const EnvironmentSettings& lastFailure() const { return failedSettings_; }
    void forgetFailure() { haveFailed_ = false; }
    const EnvironmentCounters& counters() const { return counters_; }

    // Blocks (processing events) until no job runs; for the command line and tests. False on
    // timeout.
    bool waitUntilIdle(int timeoutMs = 120000);

signals:
    void busyChanged(bool busy);
    void progress(const QString& stage, double fraction);  // from the worker, queued to the UI
    // current() changed (for a new import: early, then complete).
    void environmentReady();
    void lobesReady();  // lobes() changed: the entries in use arrived (those near them arrive quietly)
    // A file could not be used; `message` names it. The current environment is kept.
    void failed(const QString& message);

private:
    void startJob();
    void startLobeJob();
    void scheduleLobes();
    void onImported(std::shared_ptr<const PreparedEnvironment> early, const Job* job);
    void onJobFinished(std::shared_ptr<PreparedEnvironment> result, const QString& error, bool cancelled,
                       bool importCutShort);
    // Makes `next`, made by the running job, current.
    void adopt(std::shared_ptr<const PreparedEnvironment> next);

    BackgroundWorker* worker_;
    SceneDocument* document_ = nullptr;
    std::shared_ptr<const PreparedEnvironment> current_;
    EnvironmentSettings wantedSettings_;
    EnvironmentSettings runningSettings_;
    ChainNeeds wantedNeeds_;
    ChainNeeds runningNeeds_;
    bool haveRequest_ = false;
    bool busy_ = false;
    // The running job reads a file and its early environment has not arrived yet.
    bool importing_ = false;
    // What was current when the running job started: drawn again if the job fails after its early
    // environment, or if the scene asks for it again (an undone open) while the job runs.
    std::shared_ptr<const PreparedEnvironment> jobStart_;
    // The running environment job and lobe job (the one worker runs them in turn).
    std::shared_ptr<Job> runningJob_;
    EnvironmentCounters counters_;
    // Last request that failed, so the same bad file is not retried on every scene change.
    EnvironmentSettings failedSettings_;
    bool haveFailed_ = false;
    // Stack entries of current_ by stackKey (lobes.h: each knows its environment's filter; others are dropped).
    std::map<int, std::shared_ptr<const LobeStackEntry>> lobes_;
    bool lobeBusy_ = false;
    bool lobesWanted_ = false;
    std::shared_ptr<Job> lobeJob_;
    QTimer* settle_ = nullptr;
};

}  // namespace mipgloss::ui
