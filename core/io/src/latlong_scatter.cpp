// Lat-long -> cube by the scatter (the image about as fine as the cube or finer): the strata, the
// bands run in two phases, and the scatter itself, which takes the image strip by strip
// (ScatterStream, behind io_detail::LatLongStream and the in-memory conversion alike). The
// method: latlong.cpp's top comment, "Scatter, strip by strip" below and
// docs/latlong-conversion.md.
#include "latlong_internal.h"

#include "mipgloss/ibl/parallel.h"

#include <glm/common.hpp>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <span>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace mipgloss::latlong_detail {

// ---- Scatter ---------------------------------------------------------------------------------

// Strata spaced at most half the narrowest texel (a corner texel, (2/N)/3 rad) in θ and in φ
// at the equator, so every texel receives several and a texel's boundary is resolved to a sixth
// of its width at a face centre.
Strata strataFor(int width, int height, int n) {
    const double texel = (2.0 / n) / 3.0;
    return {std::max(1, static_cast<int>(std::ceil(2.0 * (2.0 * kPi / width) / texel))),
            std::max(1, static_cast<int>(std::ceil(2.0 * (kPi / height) / texel)))};
}

// Image rows per band. A texel's θ-extent is at most its angular diameter, at most that of a face
// centre texel, whose diagonal is ≈ 2√2/N rad (the 1×1 face's, 1.91 rad, is below 3.2/1). A band
// spanning 3.2/N rad of θ is wider, so no texel meets two bands that are not neighbours.
int bandRows(int height, int n) {
    const double rows = std::ceil((3.2 / n) / (kPi / height));
    return std::clamp(static_cast<int>(rows), 1, height);
}

// Runs band(j0, j1) for every band of `rowsPerBand` image rows of [lo, hi): the even bands in
// parallel, then the odd ones (see the note at the top of latlong.cpp), in `groups` groups per
// phase, reporting after each from the calling thread.
void forBandsInTwoPhases(int lo, int hi, int rowsPerBand, const std::function<void(int j0, int j1)>& band,
                         const ProgressSpan& progress, int groups) {
    const int bands = (hi - lo + rowsPerBand - 1) / rowsPerBand;
    for (int parity = 0; parity < 2; ++parity) {
        const int count = (bands - parity + 1) / 2;
        if (count <= 0) continue;
        forGroups(count, groups, [&](int k) {
            const int b = 2 * k + parity;
            band(lo + b * rowsPerBand, std::min(hi, lo + (b + 1) * rowsPerBand));
        }, progress.sub(0.5 * parity, 0.5 * (parity + 1)));
    }
}

// ---- Scatter, strip by strip ------------------------------------------------------------------
//
// The scatter reads the image once in row order, so it runs as the strips are decoded (the
// decoder hands each strip over while it reads the next: import.cpp). What stands in the way is
// the bright split: T comes from the whole image's weighted mean, and every tap is clamped to it.
// Strip k is therefore clamped to a lower bound of T known when it arrives,
//     T_k = 16 × (the weighted sums of the finite rows so far) / (the whole image's weight),
// which cannot exceed T: the sums only grow (non-negative terms, rounding is monotone) and the cap
// only raises T. The pixels of the strip above T_k are kept (candidates), and once T is known the
// difference D = min(L, T) − min(L, T_k) of each is scattered through the same strata (the
// quadrature is linear in the pixel values), so the cube is the quadrature of min(L, T) exactly as
// if T had been known from the start; only rounding differs. Nothing is subtracted, so a sun far
// above T_k costs no precision. A strip with more than 1/64 of its pixels above T_k (near the top
// pole the sums are still small) and the last strip are deferred: kept whole. A deferred finite strip is
// looked at again after every later one and clamped as soon as few enough of its pixels exceed
// the grown bound; what is still deferred at the end is scattered with T. The pole values (the
// means of the first and last rows clamped to T) and the two rows that read them wait for the end.
// What is held besides the cube: the deferred strips, two rows at each end of the other strips,
// the candidates (at most 1/64 of those strips) and per-row sums.
//
// Determinism: the strips are fixed by the caller (import: the decoder's strips of 256 rows;
// latLongToCube: the same), the steps run one after another, each over bands in two phases, the
// deferred rows at the end in row order and the candidates in image order after them. Nothing
// depends on the number of threads.
ScatterStream::ScatterStream(int width, int height, int n)
    : width_(width), height_(height), n_(n), st_(strataFor(width, height, n)), nv_(height * st_.kv),
      one_(st_.ku == 1 && st_.kv == 1), columns_(width, st_.ku, n), rowsPerBand_(bandRows(height, n)), cube_(n),
      weight_(6 * static_cast<std::size_t>(n) * static_cast<std::size_t>(n), 0.0f),
      rowSum_(static_cast<std::size_t>(height), glm::dvec3(0.0)), rowWeight_(static_cast<std::size_t>(height)),
      rowPeak_(static_cast<std::size_t>(height), std::numeric_limits<float>::infinity()),
      limit_(static_cast<std::size_t>(height), std::numeric_limits<float>::infinity()),
      row_(static_cast<std::size_t>(height), nullptr), kept_(static_cast<std::size_t>(height)),
      done_(static_cast<std::size_t>(height), 0), deferred_(static_cast<std::size_t>(height), 0) {
    for (int j = 0; j < height; ++j) {
        rowWeight_[static_cast<std::size_t>(j)] = std::cos(kPi * j / height) - std::cos(kPi * (j + 1) / height);
        weightSum_ += rowWeight_[static_cast<std::size_t>(j)] * width;
    }
}

// Rows [y0, y1), the next in order, sanitised. `rows` need only live for the call: what is
// needed later is copied.
void ScatterStream::addStrip(int y0, int y1, std::span<const Rgb> rows) {
    if (y0 != next_ || y1 <= y0 || y1 > height_ || rows.size() != static_cast<std::size_t>(y1 - y0) * width_)
        throw std::invalid_argument("lat-long strip rows " + std::to_string(y0) + ".." + std::to_string(y1) +
                                    " out of order or of the wrong size");
    next_ = y1;
    for (int j = y0; j < y1; ++j) row_[static_cast<std::size_t>(j)] = rows.data() + static_cast<std::size_t>(j - y0) * width_;
    sumRows(y0, y1);
    for (int j = y0; j < y1; ++j) partial_ += rowWeight_[static_cast<std::size_t>(j)] * rowSum_[static_cast<std::size_t>(j)];
    clamp_ = thresholdOfMean(partial_ / weightSum_);
    strips_.push_back({y0, y1, true, std::numeric_limits<float>::infinity(), {}});
    ++stats_.strips;
    // The last strip waits for the end whatever it holds: nothing is decoded after it.
    if (y1 == height_) {
        ++stats_.deferred;
        for (int j = y0; j < y1; ++j) {
            deferred_[static_cast<std::size_t>(j)] = 1;
            keep(j);
        }
    } else {
        clampOrDefer(strips_.back(), false);
    }
    // A strip deferred earlier is looked at again with the clamp as it is now (near the top
    // pole the first strips' sums are small, so they wait for a few more).
    for (Strip& s : strips_)
        if (s.deferred && s.y1 <= y0) clampOrDefer(s, true);
    scatterReady();
    for (int j = 0; j < y1; ++j)
        if (kept_[static_cast<std::size_t>(j)].empty()) row_[static_cast<std::size_t>(j)] = nullptr;
}

// After the last strip: T, the deferred rows, the candidates' differences, the normalising
// and the excess.
CubeMap ScatterStream::finish(const ProgressSpan& progress) {
    if (next_ != height_) throw std::invalid_argument("lat-long image incomplete: " + std::to_string(next_) + " of " +
                                                      std::to_string(height_) + " rows");
    const float threshold = finalThreshold();
    const float limit = threshold > 0.0f ? threshold : std::numeric_limits<float>::infinity();
    for (const Strip& s : strips_)
        if (s.deferred)
            for (int j = s.y0; j < s.y1; ++j) limit_[static_cast<std::size_t>(j)] = limit;
    // The poles: the first and last rows clamped to T (the rows themselves may be clamped
    // lower; their candidates' differences are corrected like any other).
    poleTop_ = poleValues(row_.front(), width_, Rgb(limit));
    poleBottom_ = poleValues(row_.back(), width_, Rgb(limit));
    progress.report(0.1);
    // The rows not scattered yet, in runs, in row order.
    for (int j = 0; j < height_;) {
        if (done_[static_cast<std::size_t>(j)]) {
            ++j;
            continue;
        }
        int end = j;
        while (end < height_ && !done_[static_cast<std::size_t>(end)]) ++end;
        scatterRows(j, end, progress.sub(0.1 + 0.7 * j / height_, 0.1 + 0.7 * end / height_), 10);
        j = end;
    }
    correctCandidates(limit);
    normalise();
    progress.report(0.85);
    if (threshold > 0.0f) {
        const std::vector<ExcessPixel> excess = excessPixels(threshold);
        stats_.excess = excess.size();
        splatExcess(excess, width_, height_, cube_, progress.sub(0.85, 1.0));
    }
    progress.report(1.0);
    return std::move(cube_);
}

// Clamps strip s to the present lower bound of T (clamp_), keeping its pixels above it as
// candidates, unless more than 1/64 of them are: then it is deferred (kept whole) or stays so.
void ScatterStream::clampOrDefer(Strip& s, bool wasDeferred) {
    if (countAbove(s.y0, s.y1, clamp_) > static_cast<std::size_t>(s.y1 - s.y0) * width_ / 64) {
        if (!wasDeferred) {
            ++stats_.deferred;
            for (int j = s.y0; j < s.y1; ++j) {
                deferred_[static_cast<std::size_t>(j)] = 1;
                keep(j);
            }
        }
        return;
    }
    if (wasDeferred) {
        --stats_.deferred;
        ++stats_.promoted;
    }
    s.deferred = false;
    s.limit = clamp_;
    s.candidates = above(s.y0, s.y1, clamp_);
    stats_.candidates += s.candidates.size();
    for (int j = s.y0; j < s.y1; ++j) {
        limit_[static_cast<std::size_t>(j)] = clamp_;
        deferred_[static_cast<std::size_t>(j)] = 0;
    }
}

// Scatters every row not done whose strata read only rows clamped already (j − 1 .. j + 1;
// rows 0 and height − 1, which read a pole, wait for the end), in runs, in row order; then
// keeps of the clamped strips only the two rows at each end, which rows left may read.
void ScatterStream::scatterReady() {
    static const Progress silent;  // in the background: only the caller's thread reports
    for (int j = 1; j < next_ - 1;) {
        if (done_[static_cast<std::size_t>(j)] || !ready(j)) {
            ++j;
            continue;
        }
        int end = j;
        while (end < next_ - 1 && !done_[static_cast<std::size_t>(end)] && ready(end)) ++end;
        scatterRows(j, end, {silent, 0.0f, 1.0f}, 1);
        j = end;
    }
    for (const Strip& s : strips_) {
        if (s.deferred) continue;
        for (int j = s.y0 + 2; j < s.y1 - 2; ++j) {
            auto& k = kept_[static_cast<std::size_t>(j)];
            if (!k.empty() && done_[static_cast<std::size_t>(j - 1)] && done_[static_cast<std::size_t>(j)] &&
                done_[static_cast<std::size_t>(j + 1)]) {
                std::vector<Rgb>().swap(k);
                row_[static_cast<std::size_t>(j)] = nullptr;
            }
        }
        for (int j : {s.y0, s.y0 + 1, s.y1 - 2, s.y1 - 1})
            if (j >= s.y0 && j < s.y1 && row_[static_cast<std::size_t>(j)]) keep(j);
    }
}

bool ScatterStream::ready(int j) const {
    for (int r = j - 1; r <= j + 1; ++r)
        if (r < 0 || r >= next_ || deferred_[static_cast<std::size_t>(r)] || !row_[static_cast<std::size_t>(r)])
            return false;
    return true;
}
void ScatterStream::keep(int j) {
    auto& k = kept_[static_cast<std::size_t>(j)];
    if (k.empty()) k.assign(row_[static_cast<std::size_t>(j)], row_[static_cast<std::size_t>(j)] + width_);
    row_[static_cast<std::size_t>(j)] = k.data();
}

// Each row's sum, and its brightest channel (rowPeak_), which lets countAbove and above skip
// the rows with nothing above the bound: on a sky with one sun, almost every row.
void ScatterStream::sumRows(int y0, int y1) {
    parallelFor(y0, y1, [&](int j) {
        const Rgb* r = row_[static_cast<std::size_t>(j)];
        glm::dvec3 sum(0.0);
        float peak = 0.0f;
        for (int i = 0; i < width_; ++i) {
            sum += glm::dvec3(r[i]);
            peak = std::max(peak, peakOf(r[i]));
        }
        rowSum_[static_cast<std::size_t>(j)] = sum;
        rowPeak_[static_cast<std::size_t>(j)] = peak;
    });
}
bool ScatterStream::anyAbove(int y0, int y1, float limit) const {
    for (int j = y0; j < y1; ++j)
        if (!(rowPeak_[static_cast<std::size_t>(j)] <= limit)) return true;
    return false;
}

// How many pixels of rows [y0, y1) have their brightest channel above `limit` (branch-free).
std::size_t ScatterStream::countAbove(int y0, int y1, float limit) const {
    if (!anyAbove(y0, y1, limit)) return 0;
    std::vector<std::size_t> counts(static_cast<std::size_t>(y1 - y0), 0);
    parallelFor(y0, y1, [&](int j) {
        if (rowPeak_[static_cast<std::size_t>(j)] <= limit) return;
        const Rgb* r = row_[static_cast<std::size_t>(j)];
        std::size_t n = 0;
        for (int i = 0; i < width_; ++i) n += peakOf(r[i]) > limit ? 1u : 0u;
        counts[static_cast<std::size_t>(j - y0)] = n;
    });
    std::size_t total = 0;
    for (std::size_t n : counts) total += n;
    return total;
}

// The pixels of rows [y0, y1) whose brightest channel exceeds `limit`, in image order.
std::vector<ScatterStream::Candidate> ScatterStream::above(int y0, int y1, float limit) const {
    if (!anyAbove(y0, y1, limit)) return {};
    std::vector<std::vector<Candidate>> parts(static_cast<std::size_t>(y1 - y0));
    parallelFor(y0, y1, [&](int j) {
        if (rowPeak_[static_cast<std::size_t>(j)] <= limit) return;
        const Rgb* r = row_[static_cast<std::size_t>(j)];
        auto& part = parts[static_cast<std::size_t>(j - y0)];
        for (int i = 0; i < width_; ++i)
            if (peakOf(r[i]) > limit) part.push_back({i, j, r[i]});
    });
    std::vector<Candidate> out;
    for (const auto& part : parts) out.insert(out.end(), part.begin(), part.end());
    return out;
}

// T: 16 × the brightest channel's weighted mean, raised to the cap-th largest peak when more
// than cap = 2 % of the pixels exceed it. Every pixel above 16 × the mean is a candidate or
// in a deferred strip, since 16 × the mean is at least every T_k.
float ScatterStream::finalThreshold() const {
    glm::dvec3 sum(0.0);
    for (int j = 0; j < height_; ++j) sum += rowWeight_[static_cast<std::size_t>(j)] * rowSum_[static_cast<std::size_t>(j)];
    const float threshold = thresholdOfMean(sum / weightSum_);
    const std::size_t cap = brightCap(static_cast<std::size_t>(width_) * static_cast<std::size_t>(height_));
    if (cap == 0) return threshold;
    std::vector<float> peaks;
    forEachBright(threshold, [&](int, int, const Rgb& p) { peaks.push_back(peakOf(p)); });
    return raisedToCap(threshold, std::move(peaks), cap);
}
// Calls f(i, j, value) for every pixel whose peak exceeds `threshold` (at least every T_k), in
// image order.
template <class F> void ScatterStream::forEachBright(float threshold, F f) const {
    for (const Strip& s : strips_) {
        if (s.deferred) {
            for (int j = s.y0; j < s.y1; ++j) {
                const Rgb* r = kept_[static_cast<std::size_t>(j)].data();
                for (int i = 0; i < width_; ++i)
                    if (peakOf(r[i]) > threshold) f(i, j, r[i]);
            }
        } else {
            for (const Candidate& c : s.candidates)
                if (peakOf(c.value) > threshold) f(c.i, c.j, c.value);
        }
    }
}
std::vector<ExcessPixel> ScatterStream::excessPixels(float threshold) const {
    std::vector<ExcessPixel> out;
    forEachBright(threshold, [&](int i, int j, const Rgb& p) { out.push_back({i, j, glm::max(p - Rgb(threshold), Rgb(0.0f))}); });
    return out;
}

// Padded row p (0: the top pole, height + 1: the bottom pole) and its clamp.
const Rgb* ScatterStream::padded(int p) const {
    if (p == 0) return poleTop_.data();
    if (p == height_ + 1) return poleBottom_.data();
    return row_[static_cast<std::size_t>(p - 1)];
}
float ScatterStream::paddedLimit(int p) const {
    return p == 0 || p == height_ + 1 ? std::numeric_limits<float>::infinity() : limit_[static_cast<std::size_t>(p - 1)];
}

Rgb& ScatterStream::texel(int index) {
    return cube_.at(kAllFaces[static_cast<std::size_t>(index / (n_ * n_))], index % n_, (index / n_) % n_);
}

// Stratum row b: its centre, and its strata's solid angle per unit Δφ, cos θ0 − cos θ1. Every
// stratum row has ku strata per pixel (fewer towards the poles was measured and not kept:
// docs/latlong-conversion.md, "Not done here").
ScatterStream::StratumRow ScatterStream::stratumRow(int b) const {
    const double v = (b + 0.5) / nv_;
    return {v, std::cos(kPi * b / nv_) - std::cos(kPi * (b + 1) / nv_), static_cast<float>(std::sin(kPi * v)),
            static_cast<float>(std::cos(kPi * v))};
}

// Every stratum of image rows [j0, j1) added with its solid angle to the texel that holds it:
// bands in two phases, `groups` groups per phase (1 in the background).
void ScatterStream::scatterRows(int j0, int j1, const ProgressSpan& progress, int groups) {
    forBandsInTwoPhases(j0, j1, rowsPerBand_, [&](int b0, int b1) { band(b0, b1); }, progress, groups);
    for (int j = j0; j < j1; ++j) done_[static_cast<std::size_t>(j)] = 1;
}
// The strata of image rows [j0, j1), a stratum row at a time, or two at a time when there are
// several per image row (kv ≥ 2): the two rows' texels (texelsOfRow, vectorised) agree for
// almost every column (a texel spans several stratum rows), so their values, each weighted
// by its row's solid angle, are summed in one pass of runs wherever they agree, and added
// one by one where they do not. Stratum values go into a padded four-float array (the
// image rows interpolated to the stratum row's θ once, vectorised, then read across at each
// stratum's u), so a run costs one vector add per stratum before the cube is touched.
void ScatterStream::band(int j0, int j1) {
    const std::size_t count = columns_.size(), w3 = 3 * static_cast<std::size_t>(width_);
    Scratch scratch{std::vector<float>(one_ ? 0 : w3), std::vector<float>(one_ ? 0 : w3), {},
                    std::vector<int>(count), std::vector<int>(count), std::vector<Lanes>(count)};
    for (int b = j0 * st_.kv; b < j1 * st_.kv;) {
        if (!one_ && b + 1 < j1 * st_.kv) {
            stratumRows(b, b + 1, scratch);
            b += 2;
        } else {
            stratumRows(b, -1, scratch);
            b += 1;
        }
    }
}

// Stratum row b's values into `line`, each times its row's weight w (not one_).
void ScatterStream::weightedLine(const StratumRow& sr, float* line) const {
    const Source::Row r = Source::rowAtV(sr.v, height_);
    const float* r0 = &padded(r.p0)->x;
    const float* r1 = &padded(r.p1)->x;
    const float l0 = paddedLimit(r.p0), l1 = paddedLimit(r.p1);
    const float w = static_cast<float>(sr.w), fy = r.fy * w, gy = (1.0f - r.fy) * w;
    const std::size_t w3 = 3 * static_cast<std::size_t>(width_);
#pragma omp simd
    for (std::size_t k = 0; k < w3; ++k) line[k] = std::min(r0[k], l0) * gy + std::min(r1[k], l1) * fy;
}
ScatterStream::Lanes ScatterStream::at(const float* line, const Source::Column& c) {
    const float* p = line + 3 * static_cast<std::size_t>(c.i0);
    const float* q = line + 3 * static_cast<std::size_t>(c.i1);
    const float gx = 1.0f - c.fx;
    return Lanes{p[0] * gx + q[0] * c.fx, p[1] * gx + q[1] * c.fx, p[2] * gx + q[2] * c.fx, 0.0f};
}

// Stratum row b0, with b1 (≥ 0) beside it.
void ScatterStream::stratumRows(int b0, int b1, Scratch& s) {
    const std::size_t count = columns_.size();
    const StratumRow sr0 = stratumRow(b0), sr1 = stratumRow(b1 >= 0 ? b1 : b0);
    const double w = b1 >= 0 ? sr0.w + sr1.w : sr0.w;  // a column of strata where both agree
    columns_.texelsOfRow(sr0.sn, sr0.ct, n_, s.texels0.data());
    if (b1 >= 0) columns_.texelsOfRow(sr1.sn, sr1.ct, n_, s.texels1.data());
    const int* t0 = s.texels0.data();
    const int* t1 = b1 >= 0 ? s.texels1.data() : t0;
    const Source::Column* taps = columns_.taps.data();
    if (one_) {  // ku = kv = 1: stratum a is pixel a, weighted here
        const float* px = &row_[static_cast<std::size_t>(b0)]->x;
        const float limit = limit_[static_cast<std::size_t>(b0)], wf = static_cast<float>(sr0.w);
        for (std::size_t a = 0; a < count; ++a)
            s.values[a] = Lanes{std::min(px[3 * a], limit) * wf, std::min(px[3 * a + 1], limit) * wf,
                                std::min(px[3 * a + 2], limit) * wf, 0.0f};
    } else {
        weightedLine(sr0, s.line0.data());
        if (b1 >= 0) {
            weightedLine(sr1, s.line1.data());
            float* l0 = s.line0.data();
            const float* l1 = s.line1.data();
            const std::size_t w3 = 3 * static_cast<std::size_t>(width_);
            // line0 + line1, the sum where the two rows agree; line1 keeps row b1's own.
            std::vector<float>& both = s.both;
            both.resize(w3);
            float* sum = both.data();
#pragma omp simd
            for (std::size_t k = 0; k < w3; ++k) sum[k] = l0[k] + l1[k];
            for (std::size_t a = 0; a < count; ++a) s.values[a] = at(sum, taps[a]);
        } else {
            for (std::size_t a = 0; a < count; ++a) s.values[a] = at(s.line0.data(), taps[a]);
        }
    }
    // Neighbouring strata mostly share a texel: values are summed in runs before the cube is
    // touched. Three runs stay open: columns where both rows' strata share a texel, and each
    // row's own where they do not (near a pole the two rows' texels differ often, and one
    // flush per stratum there put the pole texels' single-precision sums 3e-5 off).
    struct Run {
        int texel = -1;
        Lanes sum{};
        std::size_t count = 0;
    };
    auto flush = [&](Run& r, double weight) {
        if (r.count == 0) return;
        texel(r.texel) += Rgb(glm::dvec3(r.sum[0], r.sum[1], r.sum[2]));
        weight_[static_cast<std::size_t>(r.texel)] += static_cast<float>(weight * static_cast<double>(r.count));
        r.count = 0;
    };
    auto add = [&](Run& r, int t, Lanes v, double weight) {
        if (t != r.texel) {
            flush(r, weight);
            r.texel = t;
            r.sum = v;
        } else {
            r.sum += v;
        }
        ++r.count;
    };
    Run both, only0, only1;
    for (std::size_t a = 0; a < count; ++a) {
        if (t0[a] == t1[a]) {
            add(both, t0[a], s.values[a], w);
        } else {
            add(only0, t0[a], at(s.line0.data(), taps[a]), sr0.w);
            add(only1, t1[a], at(s.line1.data(), taps[a]), sr1.w);
        }
    }
    flush(both, w);
    flush(only0, sr0.w);
    flush(only1, sr1.w);
}

// Each candidate's D = min(L, T) − min(L, T_k), added through every stratum whose
// interpolation reads its pixel, with that stratum's weight for it. In image order, on the
// calling thread: they are few (at most 1/64 of the strips they came from).
void ScatterStream::correctCandidates(float limit) {
    const int nu = static_cast<int>(columns_.size());
    for (const Strip& s : strips_) {
        if (s.deferred) continue;
        for (const Candidate& c : s.candidates) {
            const Rgb d = glm::min(c.value, Rgb(limit)) - glm::min(c.value, Rgb(s.limit));
            if (d == Rgb(0.0f)) continue;
            ++stats_.corrected;
            const int p = c.j + 1;  // padded row
            // Stratum rows whose interpolation rows include p, and columns whose taps include i.
            const int b0 = std::max(0, (c.j - 1) * st_.kv), b1 = std::min(nv_, (c.j + 2) * st_.kv);
            for (int b = b0; b < b1; ++b) {
                const StratumRow sr = stratumRow(b);
                float wy = 0.0f;
                if (one_) {
                    wy = b == c.j ? 1.0f : 0.0f;
                } else {
                    const Source::Row r = Source::rowAtV(sr.v, height_);
                    wy = (r.p0 == p ? 1.0f - r.fy : 0.0f) + (r.p1 == p ? r.fy : 0.0f);
                }
                if (wy == 0.0f) continue;
                for (int a = (c.i - 1) * st_.ku; a < (c.i + 2) * st_.ku; ++a) {
                    const std::size_t col = static_cast<std::size_t>(((a % nu) + nu) % nu);
                    float wx = 0.0f;
                    if (one_) {
                        wx = columns_.pixel[col] == c.i ? 1.0f : 0.0f;
                    } else {
                        const Source::Column& t = columns_.taps[col];
                        wx = (t.i0 == c.i ? 1.0f - t.fx : 0.0f) + (t.i1 == c.i ? t.fx : 0.0f);
                    }
                    if (wx == 0.0f) continue;
                    texel(columns_.texelOf(col, sr.sn, sr.ct, n_)) += Rgb(sr.w * glm::dvec3(d * (wx * wy)));
                }
            }
        }
    }
}

// Sums to means; a texel that got no stratum (none does at this spacing, strataFor) stays 0.
void ScatterStream::normalise() {
    parallelFor(0, cubeRows(n_), [&](int r) {
        const auto [f, y] = faceRowOf(r, n_);
        for (int x = 0; x < n_; ++x) {
            const float wt = weight_[(static_cast<std::size_t>(f) * static_cast<std::size_t>(n_) + static_cast<std::size_t>(y)) *
                                         static_cast<std::size_t>(n_) + static_cast<std::size_t>(x)];
            Rgb& t = cube_.at(f, x, y);
            t = wt > 0.0f ? t / wt : Rgb(0.0f);
        }
    });
}

}  // namespace mipgloss::latlong_detail
