// The values every command reads the same way (cli_args.h, material_args.h): one wording for a
// choice, sizes, numbers with limits.
#include "cli_args.h"
#include "material_args.h"

#include "mipgloss/ibl/builders.h"

#include "usage_error.h"

#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace mipgloss::app {
namespace {

enum class Fruit { Apple, Pear, Plum };

TEST(ParseChoice, ReturnsTheNamedEnumerator) {
    const std::vector<std::pair<std::string, Fruit>> fruit{{"apple", Fruit::Apple}, {"pear", Fruit::Pear}, {"plum", Fruit::Plum}};
    EXPECT_EQ(parseChoice("--fruit", "pear", fruit), Fruit::Pear);
    EXPECT_EQ(parseChoice("--fruit", "plum", fruit), Fruit::Plum);
}

TEST(ParseChoice, UnknownValueListsTheValidOnesInOneWording) {
    const std::vector<std::pair<std::string, Fruit>> fruit{{"apple", Fruit::Apple}, {"pear", Fruit::Pear}, {"plum", Fruit::Plum}};
    EXPECT_EQ(usageError([&] { parseChoice("--fruit", "Pear", fruit); }), "--fruit is apple, pear or plum, got 'Pear'");
    const std::vector<Builder> builders(kAllBuilders.begin(), kAllBuilders.end());
    EXPECT_EQ(usageError([&] { parseChoice("--builder", "sideways", builders, builderName); }),
              "--builder is phong, box, paper or reference, got 'sideways'");
}

TEST(ChoiceList, JoinsWithCommasAndOr) {
    EXPECT_EQ(choiceList({"a"}), "a");
    EXPECT_EQ(choiceList({"a", "b"}), "a or b");
    EXPECT_EQ(choiceList({"a", "b", "c"}), "a, b or c");
}

TEST(Args, AFlagWithoutItsValueIsAUsageError) {
    Args args(std::vector<std::string>{"--out"});
    const std::string flag = args.next();
    EXPECT_EQ(usageError([&] { args.value(flag); }), "--out needs a value");
}

TEST(ParseSize, ReadsWidthAndHeight) {
    int w = 0, h = 0;
    parseSize("--size", "800x600", w, h);
    EXPECT_EQ(w, 800);
    EXPECT_EQ(h, 600);
}

TEST(ParseSize, RefusesZeroNegativeHugeAndMalformedNamingTheValue) {
    int w = 0, h = 0;
    EXPECT_EQ(usageError([&] { parseSize("--size", "0x120", w, h); }), "--size 0x120: the width 0 must be at least 1");
    EXPECT_EQ(usageError([&] { parseSize("--size", "160x-5", w, h); }), "--size 160x-5: the height -5 must be at least 1");
    EXPECT_EQ(usageError([&] { parseSize("--size", "99999999999x1", w, h); }),
              "--size needs WxH, two whole numbers such as 800x600, got '99999999999x1'");
    EXPECT_EQ(usageError([&] { parseSize("--size", "big", w, h); }),
              "--size needs WxH, two whole numbers such as 800x600, got 'big'");
    EXPECT_EQ(usageError([&] { parseSize("--size", "12x", w, h); }),
              "--size needs WxH, two whole numbers such as 800x600, got '12x'");
}

TEST(ParseWholeNumber, AcceptsTheLimitsAndRefusesFractionsSignsBeyondAndEmpty) {
    EXPECT_EQ(parseWholeNumber("--repeat", "1", 1, 16384), 1);
    EXPECT_EQ(parseWholeNumber("--repeat", "16384", 1, 16384), 16384);
    for (const char* bad : {"0", "16385", "2.5", "", "x", "99999999999999999999"})
        EXPECT_EQ(usageError([&] { parseWholeNumber("--repeat", bad, 1, 16384); }),
                  std::string("--repeat needs a whole number from 1 to 16384, got '") + bad + "'");
}

TEST(ParseFloat, AcceptsTheLimitsAndRefusesBeyondThem) {
    EXPECT_EQ(parseFloat("--yaw", "-360", -360.0f, 360.0f), -360.0f);
    EXPECT_EQ(parseFloat("--yaw", "12.5", -360.0f, 360.0f), 12.5f);
    EXPECT_NE(usageError([&] { parseFloat("--yaw", "361", -360.0f, 360.0f); }).find("--yaw needs a number from"),
              std::string::npos);
    EXPECT_NE(usageError([&] { parseFloat("--yaw", "nan", -360.0f, 360.0f); }).find("got 'nan'"), std::string::npos);
}

TEST(LowerExtension, IsTheExtensionInLowerCase) {
    EXPECT_EQ(lowerExtension("a/B.EXR"), ".exr");
    EXPECT_EQ(lowerExtension("picture.Png"), ".png");
    EXPECT_EQ(lowerExtension("noextension"), "");
}

}  // namespace
}  // namespace mipgloss::app
