// The material library value: names, lookups, file-safe thumbnail names.
#include "mipgloss/scene/library.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cctype>
#include <set>
#include <vector>
#include <string>

namespace mipgloss {
namespace {

MaterialLibrary libraryNamed(std::initializer_list<const char*> names) {
    MaterialLibrary library;
    for (const char* name : names) library.entries.push_back({name, Material{}});
    return library;
}

TEST(MaterialName, AcceptsWhatAnArtistTypes) {
    for (const char* name : {"Gold", "brushed steel 2", "  padded  ", "Café au lait", "金属", "a"})
        EXPECT_EQ(materialNameProblem(name), "") << name;
    EXPECT_EQ(materialNameProblem(std::string(kMaxMaterialNameBytes, 'x')), "");
}

TEST(MaterialName, RefusesEmptyBlankControlAndTooLong) {
    EXPECT_NE(materialNameProblem("").find("empty"), std::string::npos);
    for (const char* blank : {" ", "   ", "\u00a0\u3000"})
        EXPECT_NE(materialNameProblem(blank).find("white space"), std::string::npos) << '"' << blank << '"';
    for (const char* control : {"a\tb", "line\nbreak", "cr\r", "\x7f", "bell\x07", "c1\u0085", "sep\u2028"})
        EXPECT_NE(materialNameProblem(control).find("control"), std::string::npos) << control;
    // A name whose only other character is a tab is refused for the tab.
    EXPECT_NE(materialNameProblem(" \t ").find("control"), std::string::npos);
    const std::string tooLong(kMaxMaterialNameBytes + 1, 'x');
    const std::string problem = materialNameProblem(tooLong);
    EXPECT_NE(problem.find("200"), std::string::npos) << problem;
    EXPECT_NE(problem.find("201"), std::string::npos) << problem;
    // Bytes, not characters: 67 three-byte characters are 201 bytes.
    std::string wide;
    for (int i = 0; i < 67; ++i) wide += "金";
    EXPECT_NE(materialNameProblem(wide), "");
}

TEST(MaterialName, RefusesBytesThatAreNotUtf8) {
    for (const std::string& bad : {std::string("\xff"), std::string("a\x80"), std::string("\xc3"),
                                  std::string("\xc0\xaf"), std::string("\xed\xa0\x80")})
        EXPECT_NE(materialNameProblem(bad).find("UTF-8"), std::string::npos);
}

TEST(MaterialLibrary, FindsByExactName) {
    MaterialLibrary library = libraryNamed({"Gold", "gold", "Steel"});
    EXPECT_EQ(library.indexOf("gold"), 1);
    EXPECT_EQ(library.indexOf("Gold"), 0);
    EXPECT_EQ(library.indexOf("GOLD"), -1);
    EXPECT_EQ(library.indexOf("Gold "), -1);
    EXPECT_TRUE(library.contains("Steel"));
    ASSERT_NE(library.find("Steel"), nullptr);
    library.find("Steel")->material.lambda = 3.0f;
    EXPECT_EQ(std::as_const(library).find("Steel")->material.lambda, 3.0f);
    EXPECT_EQ(library.find("Copper"), nullptr);
}

TEST(MaterialLibrary, UniqueNameCountsUpFromTwo) {
    const MaterialLibrary library = libraryNamed({"Gold", "Gold 2", "Material"});
    EXPECT_EQ(library.uniqueName("Steel"), "Steel");
    EXPECT_EQ(library.uniqueName("Gold"), "Gold 3");
    EXPECT_EQ(library.uniqueName(""), "Material 2");
    EXPECT_EQ(MaterialLibrary{}.uniqueName("Gold"), "Gold");
}

TEST(FileSafeName, KeepsSafeNamesAndReplacesTheRest) {
    EXPECT_EQ(fileSafeName("Brushed steel-2_b.v1"), "Brushed steel-2_b.v1");
    EXPECT_EQ(fileSafeName("/"), "_");
    EXPECT_EQ(fileSafeName("a/b\\c"), "a_b_c");
    EXPECT_EQ(fileSafeName("a:b"), "a_b");
    EXPECT_EQ(fileSafeName("what?*<>|\""), "what______");
    // One '_' per character, however many bytes it takes; a stray byte is one '_' too.
    EXPECT_EQ(fileSafeName("Café"), "Caf_");
    EXPECT_EQ(fileSafeName("金属"), "__");
    EXPECT_EQ(fileSafeName("a\xff" "b"), "a_b");
}

TEST(FileSafeName, NeverAFolderAHiddenFileOrEmpty) {
    EXPECT_EQ(fileSafeName(".."), "material");
    EXPECT_EQ(fileSafeName("."), "material");
    EXPECT_EQ(fileSafeName(""), "material");
    EXPECT_EQ(fileSafeName(" . "), "material");
    EXPECT_EQ(fileSafeName(".hidden"), "hidden");
    EXPECT_EQ(fileSafeName("../etc/passwd"), "_etc_passwd");
    EXPECT_EQ(fileSafeName("name. . "), "name");
}

TEST(FileSafeName, AvoidsWindowsDeviceNames) {
    EXPECT_EQ(fileSafeName("CON"), "CON_");
    EXPECT_EQ(fileSafeName("con"), "con_");
    EXPECT_EQ(fileSafeName("Nul"), "Nul_");
    EXPECT_EQ(fileSafeName("COM1"), "COM1_");
    EXPECT_EQ(fileSafeName("lpt9"), "lpt9_");
    EXPECT_EQ(fileSafeName("aux.gold"), "aux_.gold");
    // Only the whole stem: these are ordinary names.
    EXPECT_EQ(fileSafeName("CONSOLE"), "CONSOLE");
    EXPECT_EQ(fileSafeName("COM10"), "COM10");
    EXPECT_EQ(fileSafeName("my con"), "my con");
}

TEST(FileSafeName, AtMostOneHundredBytes) {
    const std::string longName(300, 'x');
    EXPECT_EQ(fileSafeName(longName), std::string(100, 'x'));
    // Cut where a trailing space would be left, the space goes too.
    EXPECT_EQ(fileSafeName(std::string(99, 'a') + " bcd"), std::string(99, 'a'));
    // 300 characters of two bytes each: one '_' apiece, then cut.
    std::string accents;
    for (int i = 0; i < 300; ++i) accents += "é";
    EXPECT_EQ(fileSafeName(accents), std::string(100, '_'));
    // A device name with a long extension stays within the limit.
    EXPECT_EQ(fileSafeName("CON." + std::string(200, 'y')).size(), 100u);
    EXPECT_TRUE(fileSafeName("CON." + std::string(200, 'y')).starts_with("CON_."));
}

TEST(ThumbnailFileNames, UniqueWithoutRegardToCase) {
    const MaterialLibrary library = libraryNamed({"a", "A", "A-2", "a/b", "a:b", "Gold", "gold", "GOLD"});
    const std::vector<std::string> names = thumbnailFileNames(library);
    const std::vector<std::string> expected{"a", "A-2", "A-2-2", "a_b", "a_b-2", "Gold", "gold-2", "GOLD-3"};
    EXPECT_EQ(names, expected);
    std::set<std::string> lower;
    for (std::string name : names) {
        std::transform(name.begin(), name.end(), name.begin(),
                       [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
        lower.insert(name);
    }
    EXPECT_EQ(lower.size(), names.size());
}

TEST(ThumbnailFileNames, SuffixKeepsTheLengthLimit) {
    const std::string longName(150, 'z');
    const MaterialLibrary library = libraryNamed({longName.c_str(), (longName + "!").c_str()});
    const std::vector<std::string> names = thumbnailFileNames(library);
    ASSERT_EQ(names.size(), 2u);
    EXPECT_EQ(names[0], std::string(100, 'z'));
    EXPECT_EQ(names[1], std::string(98, 'z') + "-2");
    EXPECT_TRUE(thumbnailFileNames(MaterialLibrary{}).empty());
}

}  // namespace
}  // namespace mipgloss

// The starter library a new user gets: a dozen layered materials artists make and the paper's two,
// every one valid, under unique valid names, dielectrics with a colourless F0 and metals with none
// of a matte base.
TEST(StarterLibrary, HoldsADozenValidLayeredMaterialsArtistsMake) {
    const mipgloss::MaterialLibrary library = mipgloss::starterLibrary();
    int layeredCount = 0;
    std::set<std::string> names;
    for (const mipgloss::LibraryMaterial& entry : library.entries) {
        EXPECT_TRUE(mipgloss::materialNameProblem(entry.name).empty()) << entry.name;
        EXPECT_TRUE(names.insert(entry.name).second) << entry.name << " twice";
        EXPECT_TRUE(mipgloss::isValidMaterial(entry.material)) << entry.name;
        if (entry.material.layered) ++layeredCount;
    }
    EXPECT_GE(layeredCount, 12);
    for (const char* wanted : {"Chrome", "Gold", "Copper", "Red plastic", "Black rubber", "Clay", "Glazed ceramic",
                               "Blue car paint", "Satin fabric"})
        EXPECT_TRUE(library.contains(wanted)) << wanted;
    EXPECT_EQ(library.find("Gold")->material.layers.metallic, 1.0f);
    EXPECT_GT(library.find("Blue car paint")->material.layers.coat, 0.0f);
}

namespace mipgloss {
namespace {

// UniqueNames gives what uniqueName gives name after name (the smallest free suffix), in linear
// time: alike names, names that already carry a suffix, names reserved beforehand, the empty name.
TEST(UniqueNames, NamesAsUniqueNameDoesOneAfterAnother) {
    const std::vector<std::string> asked = {"Paint", "Paint", "Paint 2", "Paint", "", "", "Material", "Paint 3",
                                            "Paint", "Wood", "Paint 2", "Wood 2", "Wood"};
    UniqueNames fast;
    std::set<std::string> taken{"Wood"};
    fast.reserve("Wood");
    for (const std::string& base : asked) {
        const std::string expected = uniqueName(base, [&](const std::string& n) { return taken.count(n) > 0; });
        taken.insert(expected);
        EXPECT_EQ(fast.take(base), expected) << "asked \"" << base << "\"";
    }
    EXPECT_EQ(taken.size(), asked.size() + 1) << "every name distinct";
}

}  // namespace
}  // namespace mipgloss
