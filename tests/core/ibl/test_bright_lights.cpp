// The environment split into bright lights and the smooth remainder (bright_lights.h): what the
// layered program shades with the exact BRDF and what its lookups read from the remainder stack.
#include "mipgloss/ibl/bright_lights.h"
#include "mipgloss/ibl/colour.h"
#include "mipgloss/ibl/gltf_brdf.h"

#include <glm/geometric.hpp>
#include <glm/vec2.hpp>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>

namespace mipgloss {
namespace {

// A dim sky with a warm sun of 3 × 3 texels and one lone bright texel on another face.
CubeMap skyWithASun(int size) {
    CubeMap cube(size, Rgb(0.2f, 0.3f, 0.5f));
    for (int y = 0; y < 3; ++y)
        for (int x = 0; x < 3; ++x) cube.at(Face::PY, 10 + x, 12 + y) = Rgb(4000.0f, 3000.0f, 2000.0f);
    cube.at(Face::NZ, 5, 7) = Rgb(50.0f, 80.0f, 60.0f);
    cube.makeSeamless();
    return cube;
}

glm::dvec3 energyOf(const CubeMap& cube) {
    glm::dvec3 sum(0.0);
    for (Face f : kAllFaces)
        for (int y = 0; y < cube.size(); ++y)
            for (int x = 0; x < cube.size(); ++x) sum += glm::dvec3(cube.at(f, x, y)) * texelSolidAngle(x, y, cube.size());
    return sum;
}

TEST(BrightLights, TheRemainderAndTheLightsAddUpToTheEnvironmentPerChannel) {
    const CubeMap base = skyWithASun(32);
    const CubeMap remainder = withoutBrightLights(base);
    // However the lights are merged (one, or every bright texel its own), their energy is what the
    // remainder lost: double sums of float texels, within 1e-6 of the whole.
    for (const int maxLights : {1, 4, 1 << 20}) {
        glm::dvec3 lights(0.0);
        for (const PointLight& light : brightLights(base, kBrightFactor, maxLights)) lights += glm::dvec3(light.energy);
        const glm::dvec3 whole = energyOf(base), split = energyOf(remainder) + lights;
        for (int c = 0; c < 3; ++c) EXPECT_NEAR(split[c] / whole[c], 1.0, 1e-6) << "channel " << c << ", " << maxLights << " lights";
    }
}

TEST(BrightLights, TheRemainderIsTheBaseClampedAtTheThresholdWithItsColour) {
    const CubeMap base = skyWithASun(32);
    const CubeMap remainder = withoutBrightLights(base);
    const double threshold = brightThreshold(base);
    ASSERT_GT(threshold, luminance(Rgb(0.2f, 0.3f, 0.5f)));
    // The sun's texels come down to the threshold's luminance, hue kept; the sky is untouched.
    const Rgb sun = remainder.at(Face::PY, 11, 13);
    EXPECT_NEAR(luminance(sun) / threshold, 1.0, 1e-5);
    EXPECT_NEAR(sun.r / sun.b, 2.0, 1e-5);
    EXPECT_EQ(remainder.at(Face::PX, 3, 3), base.at(Face::PX, 3, 3));
    for (Face f : kAllFaces)
        for (int y = 0; y < 32; ++y)
            for (int x = 0; x < 32; ++x) EXPECT_LE(luminance(remainder.at(f, x, y)), threshold * (1.0 + 1e-6));
}

TEST(BrightLights, AnEnvironmentWithoutBrightTexelsIsItsOwnRemainder) {
    CubeMap uniform(16, Rgb(1.0f, 2.0f, 3.0f));
    uniform.makeSeamless();
    EXPECT_TRUE(brightLights(uniform).empty());
    const CubeMap remainder = withoutBrightLights(uniform);
    EXPECT_EQ(remainder.at(Face::NY, 7, 9), uniform.at(Face::NY, 7, 9));
    EXPECT_EQ(energyOf(remainder), energyOf(uniform));
}


// GGX's D averaged over the half vectors of an elliptic patch about a centre θ0 from N (in the
// x–z plane): radius `along` in the plane of incidence and `across` out of it, uniform in solid
// angle, by a polar rule on the tangent plane's exponential map. The brute force
// discAveragedGgx's closed form stands for.
double patchMeanOfGgx(double alpha, double theta0, double along, double across) {
    const glm::dvec3 h0(std::sin(theta0), 0.0, std::cos(theta0));
    const glm::dvec3 e1(std::cos(theta0), 0.0, -std::sin(theta0)), e2(0.0, 1.0, 0.0);
    double sum = 0.0, weight = 0.0;
    const int rings = 400, spokes = 256;
    for (int i = 0; i < rings; ++i)
        for (int j = 0; j < spokes; ++j) {
            const double s = (i + 0.5) / rings, phi = 2.0 * std::numbers::pi * (j + 0.5) / spokes;
            const double x = s * along * std::cos(phi), y = s * across * std::sin(phi);
            const double t = std::hypot(x, y);
            const glm::dvec3 dir = t > 0.0 ? (x * e1 + y * e2) / t : e1;
            const glm::dvec3 h = std::cos(t) * h0 + std::sin(t) * dir;
            // dω = sin t dt dφ' = (sin t / t)·dx dy; dx dy ∝ s ds dφ.
            const double w = s * (t > 0.0 ? std::sin(t) / t : 1.0);
            sum += w * ggxDistribution(alpha, h.z);
            weight += w;
        }
    return sum / weight;
}

TEST(LightsShape, ADiscAsSmallAsAPointIsGgxItself) {
    for (double alpha : {0.01, 0.09, 0.36})
        for (double cosHalf : {1.0, 0.99, 0.9, 0.6})
            EXPECT_NEAR(discAveragedGgx(alpha, cosHalf, 1e-6) / ggxDistribution(alpha, cosHalf), 1.0, 1e-4)
                << alpha << " " << cosHalf;
}

TEST(LightsShape, ADiscMeansGgxOverItsHalfVectors) {
    // The light's disc of radius ρ is a disc of ρ/2 about h (head-on, v·h = 1): core, edge and
    // tail, lobes narrower and wider than the light, centres from N to 0.6 rad off it. Within
    // 3 % (the slope-space ellipse taken as its equal-area disc, off N).
    for (double alpha : {0.01, 0.04, 0.2})
        for (double radius : {0.02, 0.1})
            for (double theta : {0.0, 0.02, 0.06, 0.2, 0.6}) {
                const double brute = patchMeanOfGgx(alpha, theta, radius / 2, radius / 2);
                const double closed = discAveragedGgx(alpha, std::cos(theta), radius);
                EXPECT_NEAR(closed / brute, 1.0, 0.03) << "α " << alpha << " ρ " << radius << " θ " << theta;
            }
}

TEST(LightsShape, FarFromTheLightTheTailIsGgxsNotAWiderLobes) {
    // The tail of D averaged over a disc is D's: the mean of α²/(π d⁴) over the disc, → 1 as d
    // grows. Widening α to α'² = α² + (ρ/2)² (what the lights used to do) made it (α'/α)² too bright.
    const double alpha = 0.04, radius = 0.05, theta = 0.5;
    const double tail = ggxDistribution(alpha, std::cos(theta));
    EXPECT_NEAR(discAveragedGgx(alpha, std::cos(theta), radius) / tail, 1.0, 0.01);
    const double widened = std::sqrt(alpha * alpha + 0.25 * radius * radius);
    EXPECT_GT(ggxDistribution(widened, std::cos(theta)) / tail, 1.35);
}

TEST(LightsShape, AveragedOverTheHemisphereTheDiscsLobeKeepsItsEnergy) {
    // ∫ D cos θh dω_h = 1 for GGX; averaging over a disc moves energy, it makes none: within 1 %
    // for lights up to 0.1 rad (the maps' widest: 0.01–0.09), 2.5 % for one of 0.3 rad (the
    // equal-area disc, and the disc kept off the horizon).
    for (double alpha : {0.05, 0.3})
        for (double radius : {0.05, 0.1, 0.3}) {
            double sum = 0.0;
            const int steps = 20000;
            for (int i = 0; i < steps; ++i) {
                const double theta = (i + 0.5) / steps * (std::numbers::pi / 2);
                sum += discAveragedGgx(alpha, std::cos(theta), radius) * std::cos(theta) * std::sin(theta) * 2 * std::numbers::pi *
                       (std::numbers::pi / 2) / steps;
            }
            EXPECT_NEAR(sum, 1.0, radius <= 0.1 ? 0.01 : 0.025) << "α " << alpha << " ρ " << radius;
        }
}

TEST(LightsShape, TheHorizonCutsADiscsCosineSmoothly) {
    const double radius = 0.05;
    EXPECT_DOUBLE_EQ(horizonCosine(0.3, radius), 0.3);
    EXPECT_DOUBLE_EQ(horizonCosine(-0.06, radius), 0.0);
    // Against (N·l)⁺ averaged over the disc on the sphere, its centre from below to above the
    // horizon: within 1 % of ρ (the closed form is the small-disc limit).
    for (double e : {-0.045, -0.02, 0.0, 0.01, 0.03, 0.049}) {
        const glm::dvec3 c(std::cos(e), 0.0, std::sin(e)), e1(-std::sin(e), 0.0, std::cos(e)), e2(0.0, 1.0, 0.0);
        double sum = 0.0, weight = 0.0;
        for (int i = 0; i < 300; ++i)
            for (int j = 0; j < 256; ++j) {
                const double t = (i + 0.5) / 300 * radius, phi = 2 * std::numbers::pi * (j + 0.5) / 256;
                const glm::dvec3 l = std::cos(t) * c + std::sin(t) * (std::cos(phi) * e1 + std::sin(phi) * e2);
                sum += std::sin(t) * std::max(l.z, 0.0);
                weight += std::sin(t);
            }
        EXPECT_NEAR(horizonCosine(std::sin(e), radius), sum / weight, 0.01 * radius) << "elevation " << e;
    }
}

// GGX's D at the half vector of each direction of a light's disc (radius ρ about l, uniform in
// solid angle), averaged: what lightAveragedGgx stands for, by a polar rule about l.
double lightMeanOfGgx(double alpha, const glm::dvec3& n, const glm::dvec3& v, const glm::dvec3& l, double radius) {
    const glm::dvec3 e1 = glm::normalize(glm::cross(l, std::abs(l.x) < 0.9 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 1, 0)));
    const glm::dvec3 e2 = glm::cross(l, e1);
    double sum = 0.0, weight = 0.0;
    const int rings = 300, spokes = 300;
    for (int i = 0; i < rings; ++i)
        for (int j = 0; j < spokes; ++j) {
            const double t = (i + 0.5) / rings * radius, phi = 2.0 * std::numbers::pi * (j + 0.5) / spokes;
            const glm::dvec3 d = std::cos(t) * l + std::sin(t) * (std::cos(phi) * e1 + std::sin(phi) * e2);
            const glm::dvec3 h = glm::normalize(d + v);
            sum += std::sin(t) * ggxDistribution(alpha, glm::dot(n, h));
            weight += std::sin(t);
        }
    return sum / weight;
}

TEST(LightsShape, TowardGrazingTheLightIsTheEllipseItsHalfVectorsMake) {
    // N·v 0.1–0.3, lights of 0.05 rad about the mirror direction and off it in the plane of
    // incidence, across it and both, lobes narrower and wider than the light: within 15 % of the
    // quadrature (1–2 % about the mirror direction; the octagon's edges at the ellipse's rim),
    // where the round disc was 0.002–7.8× (printed).
    const glm::dvec3 n(0.0, 0.0, 1.0);
    double worstDisc = 0.0;
    for (double cosView : {0.1, 0.2, 0.3})
        for (double alpha : {0.02, 0.04, 0.09})
            for (const glm::dvec2 offset : {glm::dvec2(0.0, 0.0), glm::dvec2(0.03, 0.0), glm::dvec2(0.0, 0.02),
                                            glm::dvec2(0.0, 0.06), glm::dvec2(-0.02, 0.04)}) {
                const glm::dvec3 v(std::sqrt(1.0 - cosView * cosView), 0.0, cosView);
                const glm::dvec3 mirror(-v.x, 0.0, v.z);
                // Off the mirror direction: up the plane of incidence, and across it.
                const glm::dvec3 up = glm::normalize(glm::cross(glm::dvec3(0, 1, 0), mirror));
                const glm::dvec3 l = glm::normalize(mirror + offset.x * up + offset.y * glm::dvec3(0, 1, 0));
                const double radius = 0.05;
                const double brute = lightMeanOfGgx(alpha, n, v, l, radius);
                const double ellipse = lightAveragedGgx(alpha, n, v, l, radius);
                const glm::dvec3 h = glm::normalize(l + v);
                const double disc = discAveragedGgx(alpha, glm::dot(n, h), radius);
                std::printf("N·v %.1f α %.2f offset %.2f,%.2f: brute %.4g ellipse %.4g (%.3f) disc %.4g (%.3f)\n", cosView,
                            alpha, offset.x, offset.y, brute, ellipse, ellipse / brute, disc, disc / brute);
                worstDisc = std::max(worstDisc, std::abs(disc / brute - 1.0));
                EXPECT_NEAR(ellipse / brute, 1.0, 0.15) << "N·v " << cosView << " α " << alpha << " offset "
                                                         << offset.x << ", " << offset.y;
            }
    std::printf("the round disc's worst: %.3f off\n", worstDisc);
}

}  // namespace
}  // namespace mipgloss
