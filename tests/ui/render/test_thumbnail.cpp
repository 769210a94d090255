// Material thumbnails (thumbnail.h), the pictures: not flat, a mirror unlike a diffuse material,
// the sphere where the camera says it is. (What they show: tests/core/scene/test_thumbnail_scene.cpp.)
#include "mipgloss/ibl/colour.h"
#include "mipgloss/ibl/phong.h"
#include "mipgloss/scene/chain_needs.h"
#include "mipgloss/scene/environment.h"
#include "mipgloss/ui/thumbnail.h"
#include "render_support.h"

#include <gtest/gtest.h>

#include <QImage>

#include <cmath>
#include <cstdio>
#include <string>

namespace mipgloss {
namespace {

// Perceptual luminance of a pixel in [0, 1]: the Rec. 709 luminance of the linear colour,
// sRGB-encoded again, so a step of 1/255 is about one grey level.
double perceptualLuminance(QRgb p) {
    const Rgb linear(static_cast<float>(srgbToLinear(qRed(p) / 255.0)),
                     static_cast<float>(srgbToLinear(qGreen(p) / 255.0)),
                     static_cast<float>(srgbToLinear(qBlue(p) / 255.0)));
    return linearToSrgb(luminance(linear));
}

struct Stats {
    double mean = 0.0, deviation = 0.0;
    int count = 0;
};

// Over the pixels within `radiusFraction` of the thumbnail's half-width from its centre (> 1:
// every pixel).
Stats luminanceStats(const QImage& image, double radiusFraction) {
    const double c = 0.5 * image.width(), r = radiusFraction * c;
    double sum = 0.0, sum2 = 0.0;
    int n = 0;
    for (int y = 0; y < image.height(); ++y)
        for (int x = 0; x < image.width(); ++x) {
            const double dx = x + 0.5 - c, dy = y + 0.5 - c;
            if (radiusFraction <= 1.0 && dx * dx + dy * dy > r * r) continue;
            const double l = perceptualLuminance(image.pixel(x, y));
            sum += l;
            sum2 += l * l;
            ++n;
        }
    Stats s;
    s.count = n;
    s.mean = sum / n;
    s.deviation = std::sqrt(std::max(sum2 / n - s.mean * s.mean, 0.0));
    return s;
}

// Mean |difference| of the perceptual luminance over the same disc.
double meanDifference(const QImage& a, const QImage& b, double radiusFraction) {
    const double c = 0.5 * a.width(), r = radiusFraction * c;
    double sum = 0.0;
    int n = 0;
    for (int y = 0; y < a.height(); ++y)
        for (int x = 0; x < a.width(); ++x) {
            const double dx = x + 0.5 - c, dy = y + 0.5 - c;
            if (dx * dx + dy * dy > r * r) continue;
            sum += std::abs(perceptualLuminance(a.pixel(x, y)) - perceptualLuminance(b.pixel(x, y)));
            ++n;
        }
    return sum / n;
}

std::shared_ptr<const PreparedEnvironment> thumbnailCourtyard() {
    static const auto env = [] {
        EnvironmentSettings settings;
        settings.faceSize = 64;
        return std::make_shared<const PreparedEnvironment>(prepareEnvironment(settings, thumbnailNeeds(64)));
    }();
    return env;
}

Material mirror() { return Material{}; }
Material diffuse() {
    Material m;
    m.lambda = 7.0f;
    m.mode = LookupMode::Normal;
    return m;
}

}  // namespace

TEST(Thumbnail, IsNotFlatAndAMirrorDiffersFromADiffuseMaterial) {
    std::string error;
    ui::OffscreenRenderer* renderer = test::sharedRenderer(&error);
    ASSERT_NE(renderer, nullptr) << error;
    const int size = 96;
    const QImage shiny = ui::renderThumbnail(*renderer, nullptr, mirror(), thumbnailCourtyard(), size);
    const QImage matte = ui::renderThumbnail(*renderer, nullptr, diffuse(), thumbnailCourtyard(), size);
    ASSERT_EQ(shiny.size(), QSize(size, size));
    ASSERT_EQ(matte.size(), QSize(size, size));
    shiny.save(QString::fromStdString((test::outputDir() / "thumbnail_mirror.png").string()));
    matte.save(QString::fromStdString((test::outputDir() / "thumbnail_diffuse.png").string()));

    const Stats shinyAll = luminanceStats(shiny, 2.0), matteAll = luminanceStats(matte, 2.0);
    // The sphere's inner disc: 0.8 of its silhouette, clear of the background at the rim.
    const double disc = 0.8 * 0.84;
    const Stats shinyDisc = luminanceStats(shiny, disc), matteDisc = luminanceStats(matte, disc);
    const double difference = meanDifference(shiny, matte, disc);
    std::printf("mirror: deviation %.4f (disc %.4f)  diffuse: %.4f (disc %.4f)  mean |difference| %.4f\n",
                shinyAll.deviation, shinyDisc.deviation, matteAll.deviation, matteDisc.deviation, difference);
    // Not flat: a flat picture has deviation 0; one grey level is 0.004. Measured 0.29 and 0.28
    // (the sphere against the darker blurred courtyard).
    EXPECT_GT(shinyAll.deviation, 0.1);
    EXPECT_GT(matteAll.deviation, 0.1);
    // The mirror shows the courtyard sharply (walls, windows, sky: disc deviation 0.31), the
    // diffuse sphere its cosine-weighted average, a smooth gradient (0.04): at least 3× apart.
    EXPECT_GT(shinyDisc.deviation, 3.0 * matteDisc.deviation);
    // And they are different pictures: 0.39 apart on average (the diffuse sphere is bright where
    // the mirror shows dark walls), far above a rendering difference of a few grey levels.
    EXPECT_GT(difference, 0.15);
}

}  // namespace mipgloss
