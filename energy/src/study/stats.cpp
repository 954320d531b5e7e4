#include "trn/energy/stats.hpp"

#include <algorithm>
#include <boost/math/distributions/normal.hpp>
#include <boost/math/distributions/students_t.hpp>
#include <cmath>
#include <numeric>

#include "trn/error.hpp"

namespace trn::energy {

double quantile(std::vector<double> x, double p) {
    if (x.empty()) return 0;
    std::sort(x.begin(), x.end());
    const double h = (static_cast<double>(x.size()) - 1) * p;
    const auto lo = static_cast<std::size_t>(std::floor(h));
    const std::size_t hi = std::min(lo + 1, x.size() - 1);
    return x[lo] + (h - static_cast<double>(lo)) * (x[hi] - x[lo]);
}

Summary summarize(std::span<const double> x) {
    Summary s;
    s.n = x.size();
    if (x.empty()) return s;
    s.mean = std::accumulate(x.begin(), x.end(), 0.0) / static_cast<double>(s.n);
    double ss = 0;
    for (double v : x) ss += (v - s.mean) * (v - s.mean);
    const std::vector<double> v(x.begin(), x.end());
    s.median = quantile(v, 0.5), s.q1 = quantile(v, 0.25), s.q3 = quantile(v, 0.75);
    s.ci_low = s.ci_high = s.mean;
    if (s.n >= 2) {
        s.sd = std::sqrt(ss / static_cast<double>(s.n - 1));
        const double tq = boost::math::quantile(boost::math::students_t(static_cast<double>(s.n - 1)), 0.975);
        const double half = tq * s.sd / std::sqrt(static_cast<double>(s.n));
        s.ci_low = s.mean - half, s.ci_high = s.mean + half;
    }
    return s;
}

namespace {

double poly(const double* c, int n, double x) {
    double r = c[n - 1];
    for (int i = n - 2; i >= 0; --i) r = r * x + c[i];
    return r;
}

}  // namespace

ShapiroWilk shapiro_wilk(std::span<const double> data) {
    const std::size_t n = data.size();
    if (n < 3 || n > 5000) throw Error("shapiro_wilk: n = " + std::to_string(n) + " is outside 3..5000");
    std::vector<double> x(data.begin(), data.end());
    std::sort(x.begin(), x.end());
    const double range = x.back() - x.front();
    if (!(range > 0) || !std::isfinite(range)) throw Error("shapiro_wilk: all values are equal (or not finite)");
    const std::size_t nn2 = n / 2;
    std::vector<double> a(nn2 + 1, 0.0);  // 1-based as in AS R94
    static const double c1[] = {0., .221157, -.147981, -2.07119, 4.434685, -2.706056};
    static const double c2[] = {0., .042981, -.293762, -1.752461, 5.682633, -3.582633};
    const double an = static_cast<double>(n);
    if (n == 3) {
        a[1] = std::sqrt(0.5);
    } else {
        const boost::math::normal norm;
        const double an25 = an + .25;
        std::vector<double> m(nn2 + 1);
        double summ2 = 0;
        for (std::size_t i = 1; i <= nn2; ++i) {
            m[i] = boost::math::quantile(norm, (static_cast<double>(i) - .375) / an25);
            summ2 += m[i] * m[i];
        }
        summ2 *= 2;
        const double ssumm2 = std::sqrt(summ2), rsn = 1 / std::sqrt(an);
        const double a1 = poly(c1, 6, rsn) - m[1] / ssumm2;
        std::size_t i1;
        double fac;
        if (n > 5) {
            i1 = 3;
            const double a2 = -m[2] / ssumm2 + poly(c2, 6, rsn);
            fac = std::sqrt((summ2 - 2 * (m[1] * m[1]) - 2 * (m[2] * m[2])) / (1 - 2 * (a1 * a1) - 2 * (a2 * a2)));
            a[2] = a2;
        } else {
            i1 = 2;
            fac = std::sqrt((summ2 - 2 * (m[1] * m[1])) / (1 - 2 * (a1 * a1)));
        }
        a[1] = a1;
        for (std::size_t i = i1; i <= nn2; ++i) a[i] = -m[i] / fac;
    }
    // W as the squared correlation of the data with the coefficients (R's formulation).
    double sa = 0, sx = 0;
    for (std::size_t i = 0; i < n; ++i) sx += x[i] / range;
    std::vector<double> coef(n, 0.0);
    for (std::size_t i = 0; i < nn2; ++i) {
        coef[i] = -a[i + 1];
        coef[n - 1 - i] = a[i + 1];
    }
    for (double c : coef) sa += c;
    sa /= an, sx /= an;
    double ssa = 0, ssx = 0, sax = 0;
    for (std::size_t i = 0; i < n; ++i) {
        const double asa = coef[i] - sa, xsx = x[i] / range - sx;
        ssa += asa * asa, ssx += xsx * xsx, sax += asa * xsx;
    }
    const double ssassx = std::sqrt(ssa * ssx);
    const double w1 = (ssassx - sax) * (ssassx + sax) / (ssa * ssx);
    ShapiroWilk r;
    r.w = 1 - w1;
    if (n == 3) {
        const double pi6 = 1.90985931710274, stqr = 1.04719755119660;
        r.p = std::max(0.0, pi6 * (std::asin(std::sqrt(r.w)) - stqr));
        return r;
    }
    static const double g[] = {-2.273, .459};
    static const double c3[] = {.544, -.39978, .025054, -6.714e-4};
    static const double c4[] = {1.3822, -.77857, .062767, -.0020322};
    static const double c5[] = {-1.5861, -.31082, -.083751, .0038915};
    static const double c6[] = {-.4803, -.082676, .0030302};
    double y = std::log(w1), m, s;
    const double xx = std::log(an);
    if (n <= 11) {
        const double gamma = poly(g, 2, an);
        if (y >= gamma) {
            r.p = 1e-99;
            return r;
        }
        y = -std::log(gamma - y);
        m = poly(c3, 4, an);
        s = std::exp(poly(c4, 4, an));
    } else {
        m = poly(c5, 4, xx);
        s = std::exp(poly(c6, 3, xx));
    }
    r.p = boost::math::cdf(boost::math::complement(boost::math::normal(m, s), y));
    return r;
}

namespace {

TTest finish_t(double diff, double se, double df) {
    TTest r;
    r.diff = diff, r.df = df;
    if (!(se > 0)) {  // identical constant samples: no evidence either way
        r.t = 0, r.p = 1, r.ci_low = r.ci_high = diff;
        return r;
    }
    r.t = diff / se;
    const boost::math::students_t dist(df);
    r.p = 2 * boost::math::cdf(boost::math::complement(dist, std::abs(r.t)));
    const double q = boost::math::quantile(dist, 0.975);
    r.ci_low = diff - q * se, r.ci_high = diff + q * se;
    return r;
}

void need_two(std::span<const double> a, std::span<const double> b, const char* what) {
    if (a.size() < 2 || b.size() < 2) throw Error(std::string(what) + ": each sample needs at least 2 values");
}

}  // namespace

TTest welch_t_test(std::span<const double> a, std::span<const double> b) {
    need_two(a, b, "welch_t_test");
    const Summary sa = summarize(a), sb = summarize(b);
    const double va = sa.sd * sa.sd / static_cast<double>(sa.n), vb = sb.sd * sb.sd / static_cast<double>(sb.n);
    const double df = (va + vb) * (va + vb) / (va * va / static_cast<double>(sa.n - 1) + vb * vb / static_cast<double>(sb.n - 1));
    return finish_t(sa.mean - sb.mean, std::sqrt(va + vb), std::isfinite(df) ? df : static_cast<double>(sa.n + sb.n - 2));
}

TTest student_t_test(std::span<const double> a, std::span<const double> b) {
    need_two(a, b, "student_t_test");
    const Summary sa = summarize(a), sb = summarize(b);
    const double df = static_cast<double>(sa.n + sb.n - 2);
    const double pooled = ((sa.n - 1) * sa.sd * sa.sd + (sb.n - 1) * sb.sd * sb.sd) / df;
    return finish_t(sa.mean - sb.mean, std::sqrt(pooled * (1.0 / sa.n + 1.0 / sb.n)), df);
}

std::vector<double> holm_adjust(std::span<const double> p) {
    const std::size_t m = p.size();
    std::vector<std::size_t> order(m);
    std::iota(order.begin(), order.end(), 0);
    std::stable_sort(order.begin(), order.end(), [&](std::size_t i, std::size_t j) { return p[i] < p[j]; });
    std::vector<double> out(m);
    double running = 0;
    for (std::size_t k = 0; k < m; ++k) {
        running = std::max(running, std::min(1.0, static_cast<double>(m - k) * p[order[k]]));
        out[order[k]] = running;
    }
    return out;
}

Ratio ratio_of_means(std::span<const double> a, std::span<const double> b) {
    const Summary sa = summarize(a), sb = summarize(b);
    Ratio r;
    if (sa.n == 0 || sb.n == 0 || sb.mean == 0) throw Error("ratio_of_means: empty sample or zero denominator mean");
    r.ratio = sa.mean / sb.mean;
    r.ci_low = r.ci_high = r.ratio;
    if (sa.mean > 0 && sb.mean > 0 && sa.n >= 2 && sb.n >= 2) {
        const double se = std::sqrt(sa.sd * sa.sd / (sa.n * sa.mean * sa.mean) + sb.sd * sb.sd / (sb.n * sb.mean * sb.mean));
        const double z = boost::math::quantile(boost::math::normal(), 0.975);
        r.ci_low = r.ratio * std::exp(-z * se), r.ci_high = r.ratio * std::exp(z * se);
    }
    return r;
}

}  // namespace trn::energy
