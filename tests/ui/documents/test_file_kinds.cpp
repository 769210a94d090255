// fileKindOf (file_kinds.h): every extension the window opens, in any case, a folder, and names
// that are none of these; sortByKind's first scene and last environment; the dialogs' patterns
// and Save As's suffix.
#include "mipgloss/ui/file_kinds.h"

#include <gtest/gtest.h>

#include <QDir>
#include <QTemporaryDir>

#include <string>

using namespace mipgloss::ui;

namespace {

std::string kindName(FileKind kind) {
    switch (kind) {
        case FileKind::Unknown: return "Unknown";
        case FileKind::Scene: return "Scene";
        case FileKind::Library: return "Library";
        case FileKind::Mesh: return "Mesh";
        case FileKind::Environment: return "Environment";
    }
    return "?";
}

// Each name as given, upper case and capitalised, in a folder that does not exist (only the name
// counts for a file).
void expectKind(const char* name, FileKind expected) {
    const QString lower = QStringLiteral("/no/such/folder/") + QLatin1String(name);
    const QString upper = QStringLiteral("/no/such/folder/") + QString::fromLatin1(name).toUpper();
    QString capitalised = QString::fromLatin1(name);
    capitalised[0] = capitalised[0].toUpper();
    capitalised = QStringLiteral("/no/such/folder/") + capitalised;
    for (const QString& path : {lower, upper, capitalised})
        EXPECT_EQ(kindName(fileKindOf(path)), kindName(expected)) << path.toStdString();
}

}  // namespace

TEST(FileKinds, ScenesAreMipglossAndOlderJsonFiles) {
    expectKind("gold.mipgloss", FileKind::Scene);
    expectKind("old.json", FileKind::Scene);
}

TEST(FileKinds, LibrariesAreMglibFiles) { expectKind("materials.mglib", FileKind::Library); }

TEST(FileKinds, MeshesAndAssetsAreEveryImportExtension) {
    for (const char* name : {"bunny.obj", "bunny.off", "bunny.ply", "bunny.stl", "bunny.om", "car.gltf", "car.glb"})
        expectKind(name, FileKind::Mesh);
}

TEST(FileKinds, EnvironmentsAreTheImageFormatsTheImportReads) {
    for (const char* name : {"sky.exr", "sky.hdr", "sky.png", "sky.jpg", "sky.jpeg", "sky.tif", "sky.tiff", "sky.pfm"})
        expectKind(name, FileKind::Environment);
}

TEST(FileKinds, AFolderIsAnEnvironmentWhateverItsName) {
    QTemporaryDir dir;
    ASSERT_TRUE(dir.isValid());
    ASSERT_TRUE(QDir(dir.path()).mkdir(QStringLiteral("faces.json")));
    EXPECT_EQ(kindName(fileKindOf(dir.path())), "Environment");
    EXPECT_EQ(kindName(fileKindOf(dir.filePath(QStringLiteral("faces.json")))), "Environment");
    // A folder that does not exist has only its name: none here.
    EXPECT_EQ(kindName(fileKindOf(dir.filePath(QStringLiteral("gone")))), "Unknown");
}

TEST(FileKinds, OtherNamesAreUnknown) {
    for (const char* name : {"notes.txt", "README", "archive.tar.gz", "scene.mipgloss.bak", "sky.exr~", ".obj.swp",
                             "mesh.fbx", "image.webp"})
        expectKind(name, FileKind::Unknown);
    EXPECT_EQ(kindName(fileKindOf(QString())), "Unknown");
}

TEST(FileKinds, SortByKindKeepsTheFirstSceneAndTheLastEnvironment) {
    const FilesByKind files = sortByKind({QStringLiteral("/a/one.mipgloss"), QStringLiteral("/a/sky.exr"),
                                          QStringLiteral("/a/bunny.obj"), QStringLiteral("/a/two.json"),
                                          QStringLiteral("/a/lib.mglib"), QStringLiteral("/a/studio.HDR"),
                                          QStringLiteral("/a/car.glb"), QStringLiteral("/a/notes.txt")});
    EXPECT_EQ(files.scene, QStringLiteral("/a/one.mipgloss"));
    EXPECT_EQ(files.environment, QStringLiteral("/a/studio.HDR"));
    EXPECT_EQ(files.meshes, (QStringList{QStringLiteral("/a/bunny.obj"), QStringLiteral("/a/car.glb")}));
    EXPECT_EQ(files.libraries, QStringList{QStringLiteral("/a/lib.mglib")});
    EXPECT_EQ(files.unknown, QStringList{QStringLiteral("/a/notes.txt")});

    const FilesByKind none = sortByKind({});
    EXPECT_TRUE(none.scene.isEmpty() && none.environment.isEmpty() && none.meshes.isEmpty() &&
                none.libraries.isEmpty() && none.unknown.isEmpty());
}

TEST(FileKinds, DialogPatternsListEachSuffixOnce) {
    EXPECT_EQ(dialogPatternsOf(FileKind::Scene), QStringLiteral("*.mipgloss *.json"));
    EXPECT_EQ(dialogPatternsOf(FileKind::Library), QStringLiteral("*.mglib"));
    EXPECT_EQ(dialogPatternsOf(FileKind::Mesh), QStringLiteral("*.obj *.off *.ply *.stl *.om *.gltf *.glb"));
    EXPECT_EQ(dialogPatternsOf(FileKind::Environment),
              QStringLiteral("*.exr *.hdr *.png *.jpg *.jpeg *.tif *.tiff *.pfm"));
    EXPECT_TRUE(dialogPatternsOf(FileKind::Unknown).isEmpty());
}

TEST(FileKinds, WithSuffixAddsOnlyWhenTheNameHasNone) {
    EXPECT_EQ(withSuffix(QStringLiteral("/shots/gold"), QStringLiteral("mipgloss")), QStringLiteral("/shots/gold.mipgloss"));
    EXPECT_EQ(withSuffix(QStringLiteral("/shots/gold.json"), QStringLiteral("mipgloss")), QStringLiteral("/shots/gold.json"));
    // A dot in a folder's name is not the file's suffix.
    EXPECT_EQ(withSuffix(QStringLiteral("/v1.2/gold"), QStringLiteral("png")), QStringLiteral("/v1.2/gold.png"));
    EXPECT_TRUE(withSuffix(QString(), QStringLiteral("mipgloss")).isEmpty()) << "a cancelled dialog stays cancelled";
}
