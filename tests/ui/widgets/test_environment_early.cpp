// Show it early (issue 10, part 3): a new import is current as soon as its base exists and
// complete when its chain is; the old environment stays current until the early one arrives; a
// request for another file while one is read cancels it (it never becomes current); a file that
// fails leaves the previous environment current; the renderer draws the early environment from
// its base and then sends only the chain's levels below it. The manager tests need no display,
// the renderer's need OpenGL (xvfb).
#include "mipgloss/scene/environment.h"
#include "mipgloss/scene/lobes.h"
#include "mipgloss/ui/environment_manager.h"
#include "mipgloss/ui/scene_document.h"

#include "render_support.h"
#include "scene_test_support.h"
#include "test_support.h"

#include <gtest/gtest.h>

#include <QElapsedTimer>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

using namespace mipgloss;
using namespace mipgloss::ui;
namespace fs = std::filesystem;

namespace {

constexpr int kIdleTimeoutMs = 300000;  // sunset at 1024 on a shared 2-core VM
const ChainNeeds kAllLevels{16, false};  // every read level filtered (clamped to the chain)

EnvironmentSettings fileSettings(const std::string& name, int faceSize) {
    EnvironmentSettings s;
    s.source = test::asset("env/" + name).string();
    s.faceSize = faceSize;
    return s;
}

EnvironmentSettings builtinSettings(int faceSize) {
    EnvironmentSettings s;
    s.faceSize = faceSize;
    return s;
}

// What the manager reported, in order, with what was current when each report was handled.
struct Event {
    enum Kind { Progress, Ready, Failed } kind;
    QString text;  // the progress stage or the failure message
    std::shared_ptr<const PreparedEnvironment> current;
    qint64 ms;  // since the recorder was made
};

class Recorder {
public:
    explicit Recorder(EnvironmentManager& m) : m_(m) {
        clock_.start();
        QObject::connect(&m, &EnvironmentManager::progress, &context_, [this](const QString& stage, double) {
            events.push_back({Event::Progress, stage, m_.current(), clock_.elapsed()});
        });
        QObject::connect(&m, &EnvironmentManager::environmentReady, &context_, [this] {
            events.push_back({Event::Ready, {}, m_.current(), clock_.elapsed()});
        });
        QObject::connect(&m, &EnvironmentManager::failed, &context_, [this](const QString& message) {
            events.push_back({Event::Failed, message, m_.current(), clock_.elapsed()});
        });
    }
    std::vector<Event> of(Event::Kind kind) const {
        std::vector<Event> out;
        for (const Event& e : events)
            if (e.kind == kind) out.push_back(e);
        return out;
    }
    std::vector<Event> events;

private:
    EnvironmentManager& m_;
    QObject context_;  // disconnects with the recorder
    QElapsedTimer clock_;
};

// A manager with a small complete environment current: the "previous" one of every test.
std::shared_ptr<const PreparedEnvironment> settle(EnvironmentManager& m, const EnvironmentSettings& settings) {
    m.request(settings, kAllLevels);
    if (!m.waitUntilIdle(kIdleTimeoutMs)) return nullptr;
    return m.current();
}

}  // namespace

// The early environment comes first and holds the import alone; the old one is current until
// then (every import report is handled with it current), the early one while the chain is built
// (every build report). Prints the times from the request to each, for sunset.exr at 1024².
TEST(EnvironmentEarly, ImportIsCurrentBeforeItsChain) {
    EnvironmentManager m;
    const auto previous = settle(m, builtinSettings(64));
    ASSERT_TRUE(previous && previous->complete());
    const EnvironmentCounters before = m.counters();

    Recorder r(m);
    const EnvironmentSettings sunset = fileSettings("sunset.exr", 1024);
    m.request(sunset, kAllLevels);
    ASSERT_TRUE(m.waitUntilIdle(kIdleTimeoutMs));

    const std::vector<Event> ready = r.of(Event::Ready);
    ASSERT_EQ(ready.size(), 2u) << "early, then complete";
    const auto& early = ready[0].current;
    const auto& full = ready[1].current;
    ASSERT_TRUE(early && full);
    EXPECT_FALSE(early->complete());
    EXPECT_EQ(early->settings.source, sunset.source);
    EXPECT_EQ(early->base->size(), 1024);
    EXPECT_NE(early->base, previous->base);
    EXPECT_FALSE(early->filter) << "no stack entry can be made from the early environment";
    EXPECT_FALSE(early->irradiance);
    EXPECT_TRUE(full->complete());
    EXPECT_EQ(full->base, early->base) << "the complete environment keeps the early one's import";
    EXPECT_TRUE(full->filter);
    EXPECT_TRUE(full->satisfies(sunset, kAllLevels));
    EXPECT_EQ(m.current(), full);

    int importReports = 0, buildReports = 0;
    for (const Event& e : r.of(Event::Progress)) {
        if (e.text == QLatin1String("import")) {
            ++importReports;
            EXPECT_EQ(e.current, previous) << "an import report at " << e.ms << " ms saw another environment current";
        } else if (e.text == QLatin1String("build")) {
            ++buildReports;
            EXPECT_EQ(e.current, early) << "a build report at " << e.ms << " ms saw another environment current";
        }
    }
    EXPECT_GT(importReports, 0);
    EXPECT_GT(buildReports, 0);

    const EnvironmentCounters after = m.counters();
    EXPECT_EQ(after.imports, before.imports + 1);
    EXPECT_EQ(after.earlyEnvironments, before.earlyEnvironments + 1);
    EXPECT_EQ(after.chainBuilds, before.chainBuilds + 1);
    EXPECT_EQ(after.failures, before.failures);

    std::printf("sunset.exr at 1024²: request -> early %lld ms, -> complete %lld ms "
                "(on the worker: import %.2f s, chain %.2f s, the filter's pyramid most of the rest)\n",
                static_cast<long long>(ready[0].ms), static_cast<long long>(ready[1].ms), full->importSeconds,
                full->buildSeconds);
}

// A second file asked for while the first is read: the first is cancelled and never current,
// not even early; the previous environment stays current until the second one's early one.
TEST(EnvironmentEarly, SecondFileWhileImportingCancelsTheFirst) {
    EnvironmentManager m;
    const auto previous = settle(m, builtinSettings(64));
    ASSERT_TRUE(previous);
    const EnvironmentCounters before = m.counters();

    const EnvironmentSettings first = fileSettings("sunset.exr", 1024);
    const EnvironmentSettings second = fileSettings("forest.exr", 64);
    Recorder r(m);
    bool asked = false;
    std::shared_ptr<const PreparedEnvironment> currentWhenAsked;
    QObject context;
    QObject::connect(&m, &EnvironmentManager::progress, &context, [&](const QString& stage, double) {
        if (asked || stage != QLatin1String("import")) return;
        asked = true;  // the first file is being read
        currentWhenAsked = m.current();
        m.request(second, kAllLevels);
    });
    m.request(first, kAllLevels);
    ASSERT_TRUE(m.waitUntilIdle(kIdleTimeoutMs));
    ASSERT_TRUE(asked);
    EXPECT_EQ(currentWhenAsked, previous);

    for (const Event& e : r.events) {
        if (e.current) {
            EXPECT_NE(e.current->settings.source, first.source) << "the cancelled file was current at " << e.ms << " ms";
        }
    }
    const std::vector<Event> ready = r.of(Event::Ready);
    ASSERT_EQ(ready.size(), 2u) << "the second file's early and complete environments only";
    EXPECT_FALSE(ready[0].current->complete());
    ASSERT_TRUE(m.current());
    EXPECT_EQ(m.current()->settings.source, second.source);
    EXPECT_TRUE(m.current()->complete());

    const EnvironmentCounters after = m.counters();
    EXPECT_EQ(after.earlyEnvironments, before.earlyEnvironments + 1);
    // The first job stops at its next report once cancelled: its chain is never built (it would
    // need the worker to import and filter a 1024² cube before the UI handles one queued report).
    EXPECT_EQ(after.chainBuilds, before.chainBuilds + 1);
    EXPECT_EQ(after.failures, before.failures);
    // Both files were read or cut short, each once: the first is normally cut short.
    EXPECT_EQ(after.imports + after.importsCancelled, before.imports + before.importsCancelled + 2);
    std::printf("cancelled sunset at 1024² for forest at 64²: imports read %llu, cut short %llu; complete "
                "after %lld ms\n",
                static_cast<unsigned long long>(after.imports - before.imports),
                static_cast<unsigned long long>(after.importsCancelled - before.importsCancelled),
                static_cast<long long>(ready[1].ms));
}

// The same file asked for with other needs while it is read (a λ drag during an import) does
// not read it again: the import goes on, and the next build starts from its early environment.
TEST(EnvironmentEarly, SameFileWithOtherNeedsWhileImportingReadsItOnce) {
    EnvironmentManager m;
    ASSERT_TRUE(settle(m, builtinSettings(64)));
    const EnvironmentCounters before = m.counters();

    const EnvironmentSettings file = fileSettings("city.exr", 512);
    Recorder r(m);
    bool asked = false;
    QObject context;
    QObject::connect(&m, &EnvironmentManager::progress, &context, [&](const QString& stage, double) {
        if (asked || stage != QLatin1String("import")) return;
        asked = true;
        m.request(file, kAllLevels);
    });
    m.request(file, ChainNeeds{0, false});  // mirrors only, at first
    ASSERT_TRUE(m.waitUntilIdle(kIdleTimeoutMs));
    ASSERT_TRUE(asked);

    ASSERT_TRUE(m.current());
    EXPECT_TRUE(m.current()->satisfies(file, kAllLevels));
    const EnvironmentCounters after = m.counters();
    EXPECT_EQ(after.imports, before.imports + 1) << "the file is read once";
    EXPECT_EQ(after.importsCancelled, before.importsCancelled) << "and its reading never cut short";
    EXPECT_EQ(after.earlyEnvironments, before.earlyEnvironments + 1);
    // The one asked for, and the mirrors-only chain if that job finished before it saw its cancel.
    EXPECT_GE(after.chainBuilds, before.chainBuilds + 1);
    EXPECT_LE(after.chainBuilds, before.chainBuilds + 2);
    const std::vector<Event> ready = r.of(Event::Ready);
    ASSERT_FALSE(ready.empty());
    for (const Event& e : ready) EXPECT_EQ(e.current->base, ready.front().current->base) << "one import";
}

// The previous environment asked for again while the new one's chain is built (an open undone
// once the new file shows): it is current again at once, not read again, and the new job stops.
TEST(EnvironmentEarly, PreviousAskedForAgainIsDrawnAgainAtOnce) {
    EnvironmentManager m;
    const auto previous = settle(m, builtinSettings(64));
    ASSERT_TRUE(previous);
    const EnvironmentCounters before = m.counters();

    Recorder r(m);
    bool undone = false;
    std::shared_ptr<const PreparedEnvironment> currentAfterUndo;
    QObject context;
    QObject::connect(&m, &EnvironmentManager::environmentReady, &context, [&] {
        if (undone || !m.current() || m.current()->complete()) return;
        undone = true;  // the new file's early environment is drawn and its chain is being built
        m.request(previous->settings, kAllLevels);
        currentAfterUndo = m.current();
    });
    m.request(fileSettings("sunset.exr", 512), kAllLevels);
    ASSERT_TRUE(m.waitUntilIdle(kIdleTimeoutMs));
    ASSERT_TRUE(undone);
    EXPECT_EQ(currentAfterUndo, previous) << "drawn again within the request";
    EXPECT_EQ(m.current(), previous);
    const EnvironmentCounters after = m.counters();
    EXPECT_EQ(after.imports, before.imports + 1) << "only the new file was read";
    // The job stops at its next report (it would have to make a 512² pyramid and chain before
    // the UI handles one queued event to get past it).
    EXPECT_EQ(after.chainBuilds, before.chainBuilds) << "the new file's chain was cancelled";
    const std::vector<Event> ready = r.of(Event::Ready);
    ASSERT_EQ(ready.size(), 2u) << "the new file early, then the previous again";
    EXPECT_EQ(ready[1].current, previous);
}

// A file that cannot be read leaves the previous environment current: it is never replaced, not
// even early, and the failure names the file.
TEST(EnvironmentEarly, FailingFileLeavesThePreviousCurrent) {
    test::TempDir dir;
    const fs::path text = dir / "not_an_image.exr";
    test::writeBytes(text, "this is not an image\n");
    // A real EXR cut in the middle of its pixels: the header reads, the pixels do not.
    const std::string bytes = test::readText(test::asset("env/night.exr"));
    const fs::path truncated = dir / "truncated.exr";
    test::writeBytes(truncated, bytes.substr(0, bytes.size() / 2));

    EnvironmentManager m;
    const auto previous = settle(m, fileSettings("studio.exr", 128));
    ASSERT_TRUE(previous);
    for (const fs::path& bad : {text, truncated}) {
        SCOPED_TRACE(bad.filename().string());
        const EnvironmentCounters before = m.counters();
        Recorder r(m);
        EnvironmentSettings settings = previous->settings;
        settings.source = bad.string();
        m.request(settings, kAllLevels);
        ASSERT_TRUE(m.waitUntilIdle(kIdleTimeoutMs));
        EXPECT_EQ(m.current(), previous);
        EXPECT_TRUE(r.of(Event::Ready).empty()) << "nothing else was ever current";
        const std::vector<Event> failed = r.of(Event::Failed);
        ASSERT_EQ(failed.size(), 1u);
        EXPECT_TRUE(failed[0].text.contains(QString::fromStdString(bad.filename().string())))
            << failed[0].text.toStdString();
        EXPECT_EQ(failed[0].current, previous) << "the failure is reported with the previous environment current";
        EXPECT_EQ(m.counters().failures, before.failures + 1);
        EXPECT_EQ(m.counters().earlyEnvironments, before.earlyEnvironments);
    }
}

// Stack entries (lobes.h) are made from the complete environment only: the early one has no filter,
// and none is made while it is current.
TEST(EnvironmentEarly, LobeStackEntriesComeFromTheCompleteEnvironmentOnly) {
    Scene scene;
    Material glossy;
    glossy.lambda = 3.0f;
    const MaterialId id = scene.addMaterial("glossy", glossy);
    SceneObject object = test::sphereObject("sphere", 0.0f);
    object.material = id;
    scene.objects.push_back(object);
    scene.environment = builtinSettings(64);
    SceneDocument doc;
    doc.resetScene(scene);

    EnvironmentManager m;
    m.watch(&doc);
    ASSERT_TRUE(m.waitUntilIdle(kIdleTimeoutMs));
    ASSERT_TRUE(m.current() && m.current()->complete());
    const std::uint64_t lobesBefore = m.counters().lobeBuilds;

    std::vector<std::uint64_t> lobeBuildsWhileEarly;
    QObject context;
    QObject::connect(&m, &EnvironmentManager::lobesReady, &context, [&] {
        if (m.current() && !m.current()->complete()) lobeBuildsWhileEarly.push_back(m.counters().lobeBuilds);
    });
    Recorder r(m);
    doc.setEnvironment(fileSettings("interior.exr", 256));
    ASSERT_TRUE(m.waitUntilIdle(kIdleTimeoutMs));

    const std::vector<Event> ready = r.of(Event::Ready);
    ASSERT_EQ(ready.size(), 2u);
    ASSERT_FALSE(ready[0].current->complete());
    EXPECT_TRUE(lobeBuildsWhileEarly.empty()) << "lobes changed while the early environment was current";
    const auto full = m.current();
    ASSERT_TRUE(full && full->complete() && full->filter);
    // The lobe stack's entries one lobe reads (its neighbours and the wider ones its footprint
    // may reach), and perhaps some near them already: all from the complete environment.
    const auto lobes = m.lobes();
    const std::size_t inUse = lobesInUse(doc.scene(), full->filter->baseSize()).size();
    ASSERT_GE(lobes.size(), inUse) << "the entries one lobe reads";
    for (const auto& lobe : lobes) EXPECT_EQ(lobe->filter, full->filter);
    EXPECT_GE(m.counters().lobeBuilds, lobesBefore + inUse);
}

// prepareEnvironment hands on the early environment once per new import, before the chain, and
// not when the import is reused (a builder change): the previous environment is the better
// picture then.
TEST(EnvironmentEarly, PrepareHandsOnEachNewImportOnce) {
    const EnvironmentSettings settings = fileSettings("courtyard.exr", 64);
    std::vector<std::shared_ptr<const PreparedEnvironment>> early;
    auto collect = [&](const std::shared_ptr<const PreparedEnvironment>& e) { early.push_back(e); };
    const PreparedEnvironment first = prepareEnvironment(settings, kAllLevels, nullptr, {}, collect);
    ASSERT_EQ(early.size(), 1u);
    EXPECT_EQ(early[0]->base, first.base);
    EXPECT_FALSE(early[0]->complete());
    EXPECT_EQ(early[0]->settings.faceSize, 64);
    EXPECT_TRUE(early[0]->sameImport(settings));
    EXPECT_FALSE(early[0]->satisfies(settings, ChainNeeds{0, false})) << "an early environment satisfies nothing";

    EnvironmentSettings box = settings;
    box.builder = Builder::Box;
    const PreparedEnvironment boxed = prepareEnvironment(box, kAllLevels, &first, {}, collect);
    EXPECT_EQ(early.size(), 1u) << "the import was reused";
    EXPECT_EQ(boxed.base, first.base);
    // From an early environment, the import is reused as from a complete one.
    const PreparedEnvironment fromEarly = prepareEnvironment(settings, kAllLevels, early[0].get(), {}, collect);
    EXPECT_EQ(early.size(), 1u);
    EXPECT_EQ(fromEarly.base, first.base);
    EXPECT_TRUE(fromEarly.complete());
}

// The renderer draws an early environment from its base (mirrors exactly as they will be, λ > 0
// from GL's box mips: the `box` builder's picture), then sends only the chain's levels below the
// base. Counted: one base upload and one chain upload for the two.
TEST(EnvironmentEarly, RendererSendsTheBaseOnce) {
    std::string error;
    OffscreenRenderer* renderer = test::sharedRenderer(&error);
    ASSERT_NE(renderer, nullptr) << error;

    const EnvironmentSettings settings = fileSettings("sunrise.exr", 128);
    std::shared_ptr<const PreparedEnvironment> early;
    const auto full = std::make_shared<const PreparedEnvironment>(prepareEnvironment(
        settings, kAllLevels, nullptr, {}, [&](const std::shared_ptr<const PreparedEnvironment>& e) { early = e; }));
    ASSERT_TRUE(early);
    EnvironmentSettings boxSettings = settings;
    boxSettings.builder = Builder::Box;
    const auto box = std::make_shared<const PreparedEnvironment>(prepareEnvironment(boxSettings, kAllLevels, full.get()));

    OrbitCamera camera;
    camera.frame(Bounds{glm::vec3(-1.0f), glm::vec3(1.0f)}, 1.0f, 1.05f);
    const int size = 96;
    Material mirror;
    mirror.lambda = 0.0f;
    Material glossy;
    glossy.lambda = 3.0f;
    auto hdr = [&](const Material& material, const std::shared_ptr<const PreparedEnvironment>& env) {
        renderer->render(test::sphereScene(material), camera, env, size, size);
        int w = 0, h = 0;
        return renderer->lastHdr(w, h);
    };
    // Mean |a − b| over the pixels the sphere covers (`aov`, made last: the AOV's exponent is 0
    // elsewhere), relative to the mean of b there.
    AovImage aov;
    auto relative = [&](const std::vector<glm::vec4>& a, const std::vector<glm::vec4>& b) {
        double diff = 0.0, sum = 0.0;
        for (std::size_t i = 0; i < a.size(); ++i) {
            if (aov.exponent[i] == 0.0f) continue;
            for (int c = 0; c < 3; ++c) {
                diff += std::abs(static_cast<double>(a[i][c]) - b[i][c]);
                sum += std::abs(static_cast<double>(b[i][c]));
            }
        }
        return sum > 0.0 ? diff / sum : 0.0;
    };

    const RenderCounters c0 = renderer->counters();
    const auto earlyMirror = hdr(mirror, early);
    const auto earlyGlossy = hdr(glossy, early);
    const RenderCounters c1 = renderer->counters();
    EXPECT_EQ(c1.baseUploads, c0.baseUploads + 1);
    EXPECT_EQ(c1.chainUploads, c0.chainUploads) << "an early environment has no chain to send";
    const auto fullMirror = hdr(mirror, full);
    const auto fullGlossy = hdr(glossy, full);
    const RenderCounters c2 = renderer->counters();
    EXPECT_EQ(c2.baseUploads, c1.baseUploads) << "the complete environment's base is already there";
    EXPECT_EQ(c2.chainUploads, c1.chainUploads + 1);
    const auto boxGlossy = hdr(glossy, box);
    const RenderCounters c3 = renderer->counters();
    EXPECT_EQ(c3.baseUploads, c2.baseUploads) << "another builder, the same import";
    EXPECT_EQ(c3.chainUploads, c2.chainUploads + 1);

    // A complete environment arriving without its early one sends the base and the chain once.
    const auto other = std::make_shared<const PreparedEnvironment>(
        prepareEnvironment(fileSettings("night.exr", 64), kAllLevels));
    hdr(glossy, other);
    const RenderCounters c4 = renderer->counters();
    EXPECT_EQ(c4.baseUploads, c3.baseUploads + 1);
    EXPECT_EQ(c4.chainUploads, c3.chainUploads + 1);

    aov = renderer->renderAov(test::sphereScene(glossy), camera, full, size, size);
    ASSERT_EQ(aov.exponent.size(), earlyMirror.size());
    const double mirrorDiff = relative(earlyMirror, fullMirror);
    const double boxDiff = relative(earlyGlossy, boxGlossy);
    const double phongDiff = relative(earlyGlossy, fullGlossy);
    std::printf("early vs complete, mean relative |Δ|: mirror %.2e; λ 3 against the box chain %.2e, "
                "against the phong chain %.2e\n", mirrorDiff, boxDiff, phongDiff);
    EXPECT_EQ(mirrorDiff, 0.0) << "mirrors read the same base from the same texture";
    EXPECT_LT(boxDiff, 0.01) << "GL's box mips are the box builder's levels, up to half-float rounding";
    EXPECT_GT(phongDiff, 10.0 * boxDiff) << "the phong chain's lobes are wider than the box mips'";
}
