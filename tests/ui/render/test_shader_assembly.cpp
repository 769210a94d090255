// Shader assembly (ui/render/src/shaders.h): each file's own #include lines resolved, each file
// once however often it is included, and the compiler's line numbers those of the file each line
// comes from (so a GLSL error names the right line of shading_plan.glsl or lobe_stack.glsl).
#include "shaders.h"

#include <gtest/gtest.h>

#include <QFile>

#include <string>

namespace {

// The line number (1-based) the compiler gives the first line of `assembled` containing `text`,
// following its #line directives (a #line N makes the next line N).
int compilerLineOf(const QByteArray& assembled, const QByteArray& text) {
    int line = 1;
    for (const QByteArray& l : assembled.split('\n')) {
        if (l.contains(text) && !l.startsWith("#line")) return line;
        line = l.startsWith("#line ") ? l.mid(6).trimmed().toInt() : line + 1;
    }
    return -1;
}

// The line number of the first line of shader resource `file` containing `text`.
int fileLineOf(const QString& file, const QByteArray& text) {
    QFile f(":/mipgloss/shaders/" + file);
    if (!f.open(QIODevice::ReadOnly)) return -2;
    const QList<QByteArray> lines = f.readAll().split('\n');
    for (qsizetype i = 0; i < lines.size(); ++i)
        if (lines[i].contains(text)) return static_cast<int>(i) + 1;
    return -3;
}

}  // namespace

TEST(ShaderAssembly, IncludesEachFileOnceWithTheLinesOfTheFileEachLineIsIn) {
    std::string error;
    const QByteArray object = mipgloss::ui::assembleShader("object.frag", "", &error);
    ASSERT_FALSE(object.isEmpty()) << error;
    EXPECT_FALSE(object.contains("#include")) << "every include resolved";
    // Each included file's functions are defined once.
    EXPECT_EQ(object.count("vec3 stackRead(vec3 d, float n) {"), 1);
    EXPECT_EQ(object.count("FragmentPlan planFragment()"), 1);
    EXPECT_EQ(object.count("vec3 ggxAlbedo(float roughness, float cosView) {"), 1);
    // A line of each level: the main file after its include, an included file after its own four
    // includes, its first and its last include.
    const struct {
        const char* file;
        QByteArray text;
    } probes[] = {{"object.frag", "layout(location = 0) out vec4 fragColour;"},
                  {"shading_plan.glsl", "FragmentPlan planFragment()"},
                  {"lobe_stack.glsl", "vec3 stackRead(vec3 d, float n) {"},
                  {"layered.glsl", "vec3 ggxAlbedo(float roughness, float cosView) {"},
                  {"cube_lod.glsl", "float cubeLevelOfDetail(vec3 r, float size) {"}};
    for (const auto& p : probes)
        EXPECT_EQ(compilerLineOf(object, p.text), fileLineOf(p.file, p.text)) << p.file << ": " << p.text.toStdString();
}

TEST(ShaderAssembly, AMissingFileIsAnErrorNamingIt) {
    std::string error;
    EXPECT_TRUE(mipgloss::ui::assembleShader("no_such.frag", "", &error).isEmpty());
    EXPECT_NE(error.find("no_such.frag"), std::string::npos) << error;
}
