#include "bench_plot.h"

#include <QtCore/QByteArray>
#include <QtCore/QRectF>
#include <QtCore/QString>
#include <QtGui/QFont>
#include <QtGui/QFontMetricsF>
#include <QtGui/QGuiApplication>
#include <QtGui/QImage>
#include <QtGui/QPainter>
#include <QtGui/QPainterPath>
#include <QtSvg/QSvgGenerator>

#include <algorithm>
#include <cmath>
#include <map>
#include <stdexcept>

namespace mipgloss::app {

namespace {

constexpr double kWidth = 960, kHeight = 640;
constexpr double kLeft = 90, kRight = 230, kTop = 78, kBottom = 66;

QColor builderColour(const std::string& b, int index) {
    if (b == "phong") return QColor(31, 119, 180);
    if (b == "box") return QColor(230, 110, 20);
    if (b == "paper") return QColor(44, 160, 44);
    if (b == "reference") return QColor(110, 110, 110);
    static const QColor extra[] = {QColor(148, 103, 189), QColor(214, 39, 40), QColor(140, 86, 75)};
    return extra[index % 3];
}

// Marker shapes, one per environment.
QPainterPath marker(int shape, QPointF c, double r) {
    QPainterPath p;
    switch (shape % 5) {
        case 0: p.addEllipse(c, r, r); break;
        case 1: p.addRect(QRectF(c.x() - 0.9 * r, c.y() - 0.9 * r, 1.8 * r, 1.8 * r)); break;
        case 2:
            p.moveTo(c.x(), c.y() - 1.15 * r);
            p.lineTo(c.x() + r, c.y() + 0.75 * r);
            p.lineTo(c.x() - r, c.y() + 0.75 * r);
            p.closeSubpath();
            break;
        case 3:
            p.moveTo(c.x(), c.y() - 1.2 * r);
            p.lineTo(c.x() + 1.2 * r, c.y());
            p.lineTo(c.x(), c.y() + 1.2 * r);
            p.lineTo(c.x() - 1.2 * r, c.y());
            p.closeSubpath();
            break;
        default:
            p.moveTo(c.x(), c.y() + 1.15 * r);
            p.lineTo(c.x() + r, c.y() - 0.75 * r);
            p.lineTo(c.x() - r, c.y() - 0.75 * r);
            p.closeSubpath();
            break;
    }
    return p;
}

struct LogAxis {
    double lo = 0, hi = 1;  // log10 bounds
    double map(double v, double a, double b) const { return a + (std::log10(v) - lo) / (hi - lo) * (b - a); }
};

LogAxis fitAxis(double mn, double mx) {
    mn = std::max(mn, 1e-12) / 1.2;  // keep markers off the frame
    mx = std::max(mx * 1.2, mn);
    LogAxis ax;
    ax.lo = std::floor(std::log10(mn) + 1e-9);
    ax.hi = std::ceil(std::log10(mx) - 1e-9);
    if (ax.hi <= ax.lo) ax.hi = ax.lo + 1;
    return ax;
}

// Ticks 1, 2, 5 per decade when the axis spans few decades, decades only otherwise.
std::vector<double> ticks(const LogAxis& ax) {
    std::vector<double> t;
    const bool fine = ax.hi - ax.lo <= 3;
    for (int e = static_cast<int>(ax.lo); e <= static_cast<int>(ax.hi); ++e)
        for (double m : fine ? std::vector<double>{1, 2, 5} : std::vector<double>{1}) {
            const double v = m * std::pow(10.0, e);
            if (std::log10(v) <= ax.hi + 1e-9) t.push_back(v);
        }
    return t;
}

// Tick values in plain decimals (0.0001, 1000), never in exponent notation.
QString number(double v) {
    const int decimals = v >= 1.0 ? 0 : static_cast<int>(std::ceil(-std::log10(v) - 1e-9));
    return QString::number(v, 'f', decimals);
}

void draw(QPainter& p, const std::vector<BenchPlotPoint>& pts, const QString& title, const QString& subtitle) {
    p.setRenderHint(QPainter::Antialiasing);
    p.fillRect(QRectF(0, 0, kWidth, kHeight), Qt::white);
    const QRectF area(kLeft, kTop, kWidth - kLeft - kRight, kHeight - kTop - kBottom);

    double tmin = 1e300, tmax = 0, emin = 1e300, emax = 0;
    for (const auto& q : pts) {
        tmin = std::min(tmin, q.seconds);
        tmax = std::max(tmax, q.seconds);
        emin = std::min(emin, 100.0 * q.worstRead);
        emax = std::max(emax, 100.0 * q.worstRead);
    }
    const LogAxis ax = fitAxis(tmin, tmax), ay = fitAxis(emin, emax);
    auto X = [&](double s) { return ax.map(s, area.left(), area.right()); };
    auto Y = [&](double pc) { return ay.map(pc, area.bottom(), area.top()); };

    QFont font("DejaVu Sans");
    font.setPixelSize(13);
    QFont small = font;
    small.setPixelSize(11);
    QFont big = font;
    big.setPixelSize(17);
    big.setBold(true);

    // Title.
    p.setPen(Qt::black);
    p.setFont(big);
    p.drawText(QRectF(0, 8, kWidth, 26), Qt::AlignHCenter | Qt::AlignVCenter, title);
    p.setFont(small);
    p.setPen(QColor(60, 60, 60));
    p.drawText(QRectF(0, 36, kWidth, 34), Qt::AlignHCenter | Qt::AlignTop | Qt::TextWordWrap, subtitle);

    // Grid and tick labels.
    p.setFont(font);
    const QFontMetricsF fm(font);
    for (double t : ticks(ax)) {
        const double x = X(t);
        const bool decade = std::fabs(std::log10(t) - std::round(std::log10(t))) < 1e-9;
        p.setPen(QPen(decade ? QColor(200, 200, 200) : QColor(232, 232, 232), 1));
        p.drawLine(QPointF(x, area.top()), QPointF(x, area.bottom()));
        p.setPen(QPen(Qt::black, 1));
        p.drawLine(QPointF(x, area.bottom()), QPointF(x, area.bottom() + 5));
        p.drawText(QRectF(x - 40, area.bottom() + 7, 80, 18), Qt::AlignHCenter | Qt::AlignTop, number(t) + " s");
    }
    for (double t : ticks(ay)) {
        const double y = Y(t);
        const bool decade = std::fabs(std::log10(t) - std::round(std::log10(t))) < 1e-9;
        p.setPen(QPen(decade ? QColor(200, 200, 200) : QColor(232, 232, 232), 1));
        p.drawLine(QPointF(area.left(), y), QPointF(area.right(), y));
        p.setPen(QPen(Qt::black, 1));
        p.drawLine(QPointF(area.left() - 5, y), QPointF(area.left(), y));
        p.drawText(QRectF(area.left() - 88, y - 9, 80, 18), Qt::AlignRight | Qt::AlignVCenter, number(t) + " %");
    }
    p.setPen(QPen(Qt::black, 1.2));
    p.setBrush(Qt::NoBrush);
    p.drawRect(area);

    // Axis titles.
    p.drawText(QRectF(area.left(), kHeight - 26, area.width(), 20), Qt::AlignHCenter | Qt::AlignVCenter,
               "chain build time (median, log scale)");
    p.save();
    p.translate(18, area.center().y());
    p.rotate(-90);
    p.drawText(QRectF(-area.height() / 2, -10, area.height(), 20), Qt::AlignHCenter | Qt::AlignVCenter,
               "worst between-centres read error over read levels (log scale)");
    p.restore();

    // Series: colour per builder, shape per environment, a thin line through the face sizes.
    std::vector<std::string> builders, envs;
    for (const auto& q : pts) {
        if (std::find(builders.begin(), builders.end(), q.builder) == builders.end()) builders.push_back(q.builder);
        if (std::find(envs.begin(), envs.end(), q.env) == envs.end()) envs.push_back(q.env);
    }
    auto bi = [&](const std::string& b) { return static_cast<int>(std::find(builders.begin(), builders.end(), b) - builders.begin()); };
    auto ei = [&](const std::string& e) { return static_cast<int>(std::find(envs.begin(), envs.end(), e) - envs.begin()); };
    std::map<std::pair<int, int>, std::vector<const BenchPlotPoint*>> series;
    for (const auto& q : pts) series[{bi(q.builder), ei(q.env)}].push_back(&q);
    for (auto& [key, s] : series) {
        std::sort(s.begin(), s.end(), [](auto* a, auto* b) { return a->size < b->size; });
        QColor c = builderColour(builders[static_cast<std::size_t>(key.first)], key.first);
        c.setAlpha(110);
        p.setPen(QPen(c, 1.2, key.second == 0 ? Qt::SolidLine : Qt::DashLine));
        for (std::size_t i = 1; i < s.size(); ++i)
            p.drawLine(QPointF(X(s[i - 1]->seconds), Y(100 * s[i - 1]->worstRead)),
                       QPointF(X(s[i]->seconds), Y(100 * s[i]->worstRead)));
    }
    const double r = 6;
    std::vector<QRectF> taken;
    for (const auto& q : pts) {
        const QPointF c(X(q.seconds), Y(100 * q.worstRead));
        taken.emplace_back(c.x() - r, c.y() - r, 2 * r, 2 * r);
    }
    for (const auto& q : pts) {
        const QPointF c(X(q.seconds), Y(100 * q.worstRead));
        const QColor col = builderColour(q.builder, bi(q.builder));
        p.setPen(QPen(col.darker(140), 1));
        p.setBrush(col);
        p.drawPath(marker(ei(q.env), c, r));
    }
    // Labels: the face size beside each marker, placed where it overlaps nothing drawn yet.
    p.setFont(small);
    const QFontMetricsF fs(small);
    for (const auto& q : pts) {
        const QPointF c(X(q.seconds), Y(100 * q.worstRead));
        const QString label = QString::number(q.size);
        const double w = fs.horizontalAdvance(label) + 2, h = fs.height();
        const QPointF offsets[] = {{r + 2, -h / 2}, {-r - 2 - w, -h / 2}, {-w / 2, -r - h - 1}, {-w / 2, r + 1},
                                   {r + 2, -h - 2}, {r + 2, 2},         {-r - 2 - w, -h - 2}, {-r - 2 - w, 2},
                                   {r + 10, -h / 2}, {-r - 10 - w, -h / 2}, {-w / 2, -r - 2 * h}, {-w / 2, r + h}};
        QRectF best;
        int bestHits = 1 << 30;
        for (const QPointF& o : offsets) {
            const QRectF rect(c + o, QSizeF(w, h));
            int hits = 0;
            for (const QRectF& t : taken) hits += rect.intersects(t) ? 1 : 0;
            if (!area.contains(rect)) hits += 100;
            if (hits < bestHits) {
                bestHits = hits;
                best = rect;
            }
            if (hits == 0) break;
        }
        taken.push_back(best);
        p.setPen(builderColour(q.builder, bi(q.builder)).darker(150));
        p.drawText(best, Qt::AlignCenter, label);
    }

    // Legend.
    const double lx = area.right() + 22;
    double ly = area.top() + 4;
    p.setFont(font);
    p.setPen(Qt::black);
    p.drawText(QPointF(lx, ly + 12), "builder (colour)");
    ly += 24;
    for (std::size_t i = 0; i < builders.size(); ++i) {
        const QColor col = builderColour(builders[i], static_cast<int>(i));
        p.setPen(QPen(col.darker(140), 1));
        p.setBrush(col);
        p.drawRect(QRectF(lx, ly, 14, 14));
        p.setPen(Qt::black);
        p.drawText(QPointF(lx + 22, ly + 12), QString::fromStdString(builders[i]));
        ly += 22;
    }
    ly += 12;
    p.drawText(QPointF(lx, ly + 12), "environment (shape)");
    ly += 24;
    for (std::size_t i = 0; i < envs.size(); ++i) {
        p.setPen(QPen(QColor(60, 60, 60), 1));
        p.setBrush(QColor(170, 170, 170));
        p.drawPath(marker(static_cast<int>(i), QPointF(lx + 7, ly + 7), 6));
        p.setPen(Qt::black);
        p.drawText(QPointF(lx + 22, ly + 12), QString::fromStdString(envs[i]));
        ly += 22;
    }
    ly += 12;
    p.setFont(small);
    p.drawText(QRectF(lx, ly, kRight - 30, 80), Qt::AlignLeft | Qt::AlignTop | Qt::TextWordWrap,
               "label: base face size N;\nlines join one builder and\nenvironment across sizes");
}

void ensureGuiApplication() {
    if (QCoreApplication::instance()) return;
    // Fonts need a QGuiApplication; no window is shown, so the offscreen platform serves anywhere.
    if (qEnvironmentVariableIsEmpty("QT_QPA_PLATFORM")) qputenv("QT_QPA_PLATFORM", "offscreen");
    static int argc = 1;
    static char name[] = "mipgloss";
    static char* argv[] = {name, nullptr};
    static QGuiApplication app(argc, argv);
}

}  // namespace

std::filesystem::path writeBenchPlot(const std::vector<BenchPlotPoint>& points, const std::filesystem::path& svg,
                                     const std::string& title, const std::string& subtitle) {
    if (points.empty()) throw std::runtime_error("nothing to plot");
    ensureGuiApplication();
    const QString t = QString::fromStdString(title), sub = QString::fromStdString(subtitle);
    {
        QSvgGenerator gen;
        gen.setFileName(QString::fromStdString(svg.string()));
        gen.setSize(QSize(static_cast<int>(kWidth), static_cast<int>(kHeight)));
        gen.setViewBox(QRectF(0, 0, kWidth, kHeight));
        gen.setTitle(t);
        gen.setDescription(sub);
        QPainter p;
        if (!p.begin(&gen)) throw std::runtime_error("cannot write " + svg.string());
        draw(p, points, t, sub);
        p.end();
    }
    if (!std::filesystem::exists(svg)) throw std::runtime_error("cannot write " + svg.string());
    std::filesystem::path png = svg;
    png.replace_extension(".png");
    QImage img(static_cast<int>(kWidth * 1.5), static_cast<int>(kHeight * 1.5), QImage::Format_RGB32);
    img.fill(Qt::white);
    {
        QPainter p(&img);
        p.scale(1.5, 1.5);
        draw(p, points, t, sub);
    }
    if (!img.save(QString::fromStdString(png.string()), "PNG")) throw std::runtime_error("cannot write " + png.string());
    return png;
}

}  // namespace mipgloss::app
