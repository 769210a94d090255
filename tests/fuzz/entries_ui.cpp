// Fuzz entries for the files the previewer reads through Qt's JSON parser: scenes and material
// libraries. Neither needs an application object or a display.
#include "entries.h"

#include "mipgloss/ui/library_file.h"
#include "mipgloss/ui/scene_file.h"

namespace mipgloss::fuzz {
namespace {

// Relative mesh and environment paths resolve into a folder that does not exist, so a fuzzed
// scene reads no file of the machine it runs on (only builtin: meshes load).
const char* const kSceneFile = "/nonexistent-mipgloss-fuzz/fuzz-scene.mipgloss";
const char* const kLibraryFile = "/nonexistent-mipgloss-fuzz/fuzz-library.mglib";

std::string namesFile(const std::string& what, const std::string& name, const char* kind) {
    if (what.find(name) != std::string::npos) return {};
    return std::string(kind) + " does not name the file '" + name + "': " + what;
}

QByteArray toQByteArray(Bytes data) {
    return QByteArray(reinterpret_cast<const char*>(data.data()), static_cast<qsizetype>(data.size()));
}

}  // namespace

std::string sceneFile(Bytes data) {
    Scene scene;
    try {
        ui::SceneFileReport report;
        scene = ui::sceneFromJson(toQByteArray(data), kSceneFile, &report);
        for (const std::string& w : report.warnings)
            if (std::string p = namesFile(w, kSceneFile, "a warning"); !p.empty()) return p;
    } catch (const ui::SceneFileError& e) {
        return namesFile(e.what(), kSceneFile, "a SceneFileError");
    }
    // What loaded saves, and what is saved loads again (the file's writer and reader agree).
    try {
        const Scene again = ui::sceneFromJson(ui::sceneToJson(scene, kSceneFile), kSceneFile);
        if (again.objects.size() != scene.objects.size())
            return "a loaded scene, saved and loaded again, has another number of objects";
    } catch (const ui::SceneFileError& e) {
        return std::string("a loaded scene, saved, does not load again: ") + e.what();
    }
    return {};
}

std::string libraryFile(Bytes data) {
    MaterialLibrary library;
    try {
        ui::LibraryFileReport report;
        library = ui::libraryFromJson(toQByteArray(data), kLibraryFile, &report);
        for (const std::string& w : report.warnings)
            if (std::string p = namesFile(w, kLibraryFile, "a warning"); !p.empty()) return p;
    } catch (const ui::LibraryFileError& e) {
        return namesFile(e.what(), kLibraryFile, "a LibraryFileError");
    }
    try {
        const MaterialLibrary again = ui::libraryFromJson(ui::libraryToJson(library), kLibraryFile);
        if (!(again == library)) return "a loaded library, saved and loaded again, differs";
    } catch (const ui::LibraryFileError& e) {
        return std::string("a loaded library, saved, does not load again: ") + e.what();
    }
    return {};
}

}  // namespace mipgloss::fuzz
