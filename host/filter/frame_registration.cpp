#include "trn/filter/frame_registration.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>

#include <opencv2/imgproc.hpp>

#include "trn/io/input_file.hpp"
#include "trn/error.hpp"
#include "trn/filter/visual_odometry.hpp"
#include "trn/parse_number.hpp"
#include "trn/detail/angles.hpp"

namespace trn::reg {
namespace {

cv::Mat as_mat(const GrayImage& g) {
    return cv::Mat(g.height, g.width, CV_8UC1, const_cast<std::uint8_t*>(g.pixels.data()));
}

GrayImage from_mat(const cv::Mat& m) {
    GrayImage g;
    g.width = m.cols;
    g.height = m.rows;
    g.pixels.resize(static_cast<std::size_t>(m.cols) * m.rows);
    for (int y = 0; y < m.rows; ++y) std::copy_n(m.ptr<std::uint8_t>(y), m.cols, g.pixels.data() + y * m.cols);
    return g;
}

// Random sparse samples: enough for a smooth score surface at a tenth of the cost of dense.
ScoreOptions sparse(double fraction) {
    ScoreOptions o;
    o.sampling = Sampling::random(fraction, 1);
    return o;
}

// Frame k's template (downscaled for the pose scale) and the poses scaled to that template.
struct Templ {
    ScaledTemplate t;
    Pose to_template(Pose p) const {
        p.scale = static_cast<float>(p.scale * t.factor);
        return p;
    }
};

std::vector<float> score_all(Backend& backend, const MapHandle& map, const Templ& templ, const std::vector<Pose>& poses,
                             const ScoreOptions& options) {
    std::vector<Pose> scaled(poses.size());
    for (std::size_t i = 0; i < poses.size(); ++i) scaled[i] = templ.to_template(poses[i]);
    std::vector<ParticleScore> out(poses.size());
    backend.score(map, templ.t.image.view(), scaled, options, out);
    std::vector<float> ncc(poses.size());
    for (std::size_t i = 0; i < poses.size(); ++i) ncc[i] = out[i].valid() ? out[i].ncc : -1.0f;
    return ncc;
}

struct Candidate {
    Pose anchor;
    double score = -2;
};

// Every frame warped into map-pixel units (divided by q) for anchor yaw/scale, averaged where
// frames overlap; uncovered canvas gets the mean so it adds nothing to the correlation.
cv::Mat mosaic(const std::vector<cv::Mat>& frames, const std::vector<Similarity>& chain, double yaw, double s, double q,
               cv::Point2d& offset) {
    const double cx = (frames[0].cols - 1) / 2.0, cy = (frames[0].rows - 1) / 2.0;
    const double ca = std::cos(yaw) * s / q, sa = std::sin(yaw) * s / q;
    // frame k pixel -> canvas (before offset): G = (s/q) R(yaw) (T_k p - c)
    std::vector<cv::Matx23d> g(frames.size());
    double x0 = 1e18, y0 = 1e18, x1 = -1e18, y1 = -1e18;
    for (std::size_t k = 0; k < frames.size(); ++k) {
        const Similarity& t = chain[k];
        const double a = ca * t.a - sa * t.b, b = sa * t.a + ca * t.b;  // (s/q) R * [a -b; b a]
        const double tx = ca * (t.tx - cx) - sa * (t.ty - cy), ty = sa * (t.tx - cx) + ca * (t.ty - cy);
        g[k] = cv::Matx23d(a, -b, tx, b, a, ty);
        for (const cv::Point2d c : {cv::Point2d(0, 0), cv::Point2d(frames[k].cols - 1, 0), cv::Point2d(0, frames[k].rows - 1),
                                    cv::Point2d(frames[k].cols - 1, frames[k].rows - 1)}) {
            const double px = a * c.x - b * c.y + tx, py = b * c.x + a * c.y + ty;
            x0 = std::min(x0, px), y0 = std::min(y0, py), x1 = std::max(x1, px), y1 = std::max(y1, py);
        }
    }
    offset = {-std::floor(x0), -std::floor(y0)};
    const cv::Size size(static_cast<int>(std::ceil(x1) - std::floor(x0)) + 1, static_cast<int>(std::ceil(y1) - std::floor(y0)) + 1);
    cv::Mat sum = cv::Mat::zeros(size, CV_32F), count = cv::Mat::zeros(size, CV_32F);
    for (std::size_t k = 0; k < frames.size(); ++k) {
        cv::Matx23d m = g[k];
        m(0, 2) += offset.x;
        m(1, 2) += offset.y;
        cv::Mat f, w;
        frames[k].convertTo(f, CV_32F);
        cv::warpAffine(f, w, m, size, cv::INTER_AREA, cv::BORDER_CONSTANT, 0);
        cv::Mat ones(frames[k].size(), CV_32F, cv::Scalar(1)), wm;
        cv::warpAffine(ones, wm, m, size, cv::INTER_NEAREST, cv::BORDER_CONSTANT, 0);
        sum += w.mul(wm);
        count += wm;
    }
    cv::Mat covered = count > 0.5f;
    cv::Mat out;
    cv::divide(sum, cv::max(count, 1e-6f), out);
    out.setTo(cv::mean(out, covered)[0], ~covered);
    return out;
}

// Coarse search of the whole map over yaw and scale: best few distinct anchors.
// No-data filled with the mean grey of the valid pixels: matchTemplate has no image mask, and a
// white or black no-data wall would otherwise correlate with the frames' bright or dark parts.
cv::Mat filled_map(const GrayImage& map, GrayView valid) {
    const cv::Mat m = as_mat(map);
    if (!valid.data) return m;
    const cv::Mat v(valid.height, valid.width, CV_8UC1, const_cast<std::uint8_t*>(valid.data), static_cast<std::size_t>(valid.stride));
    const cv::Mat invalid = v == 0;
    cv::Mat out = m.clone();
    out.setTo(cv::mean(m, ~invalid)[0], invalid);
    return out;
}

std::vector<Candidate> global_candidates(const GrayImage& map, GrayView valid, const std::vector<GrayImage>& frames,
                                         const std::vector<Similarity>& chain, const RegisterOptions& o) {
    constexpr double q = 4;  // map downscale of the coarse search
    cv::Mat small;
    cv::resize(filled_map(map, valid), small, cv::Size(), 1 / q, 1 / q, cv::INTER_AREA);
    small.convertTo(small, CV_32F);
    std::vector<cv::Mat> mats;
    for (const GrayImage& f : frames) mats.push_back(as_mat(f));
    std::vector<Candidate> all;
    for (double s = o.min_scale; s <= o.max_scale + 1e-9; s *= 1.05) {
        for (double yd = 0; yd < 360; yd += o.yaw_step_deg) {
            cv::Point2d off;
            const cv::Mat m = mosaic(mats, chain, yd * kDeg, s, q, off);
            if (m.cols >= small.cols || m.rows >= small.rows) continue;
            cv::Mat r;
            cv::matchTemplate(small, m, r, cv::TM_CCOEFF_NORMED);
            double best;
            cv::Point loc;
            cv::minMaxLoc(r, nullptr, &best, nullptr, &loc);
            Candidate c;
            c.anchor = {static_cast<float>(q * (loc.x + off.x) + (q - 1) / 2), static_cast<float>(q * (loc.y + off.y) + (q - 1) / 2),
                        static_cast<float>(yd * kDeg), static_cast<float>(s)};
            c.score = best;
            all.push_back(c);
        }
    }
    std::sort(all.begin(), all.end(), [](const Candidate& a, const Candidate& b) { return a.score > b.score; });
    std::vector<Candidate> distinct;
    for (const Candidate& c : all) {
        bool near = false;
        for (const Candidate& d : distinct)
            near = near || std::hypot(c.anchor.x - d.anchor.x, c.anchor.y - d.anchor.y) < 40;
        if (!near) distinct.push_back(c);
        if (distinct.size() == 6) break;
    }
    return distinct;
}

// Mean NCC over all frames of the chained poses, for every anchor in `anchors`.
std::vector<double> joint_scores(Backend& backend, const MapHandle& map, const std::vector<GrayImage>& frames,
                                 const std::vector<Templ>& templs, const std::vector<Similarity>& chain,
                                 const std::vector<Pose>& anchors) {
    std::vector<double> total(anchors.size(), 0.0);
    std::vector<Pose> poses(anchors.size());
    for (std::size_t k = 0; k < templs.size(); ++k) {
        for (std::size_t i = 0; i < anchors.size(); ++i) poses[i] = chained_pose(anchors[i], chain[k], frames[0], frames[k]);
        const std::vector<float> ncc = score_all(backend, map, templs[k], poses, sparse(0.2));
        for (std::size_t i = 0; i < anchors.size(); ++i) total[i] += ncc[i] / templs.size();
    }
    return total;
}

// Grid of anchors around `a`: +-r px (step), +-ny yaw steps, +-ns relative scale steps.
std::vector<Pose> anchor_grid(const Pose& a, double r, double step, int ny, double yaw_step, int ns, double scale_step) {
    std::vector<Pose> g;
    for (int iy = -ny; iy <= ny; ++iy)
        for (int is = -ns; is <= ns; ++is)
            for (double dy = -r; dy <= r + 1e-9; dy += step)
                for (double dx = -r; dx <= r + 1e-9; dx += step)
                    g.push_back({static_cast<float>(a.x + dx), static_cast<float>(a.y + dy), static_cast<float>(a.yaw + iy * yaw_step),
                                 static_cast<float>(a.scale * (1 + is * scale_step))});
    return g;
}

Candidate best_of(const std::vector<Pose>& poses, const std::vector<double>& scores) {
    const auto i = std::max_element(scores.begin(), scores.end()) - scores.begin();
    return {poses[i], scores[i]};
}

}  // namespace

double Similarity::angle() const { return std::atan2(b, a); }
double Similarity::scale() const { return std::hypot(a, b); }

Similarity compose(const Similarity& o, const Similarity& i) {
    return {o.a * i.a - o.b * i.b, o.b * i.a + o.a * i.b, o.a * i.tx - o.b * i.ty + o.tx, o.b * i.tx + o.a * i.ty + o.ty};
}

std::vector<RelativeMotion> relative_motions(const std::vector<GrayImage>& frames, const std::vector<std::string>& names) {
    // The visual odometry's feature step (trn/filter/visual_odometry.hpp) at full size with more
    // features and RANSAC effort than the odometry needs: 16 frames, accuracy first.
    filter::VisualOdometryOptions o;
    o.max_features = 3000;
    o.max_width = 16384;
    o.ransac_iterations = 5000;
    o.ransac_confidence = 0.999;
    o.min_inliers = 20;
    o.phase_correlation = false;
    filter::VisualOdometry vo(o);
    vo.track(frames.at(0).view());
    std::vector<RelativeMotion> out;
    for (std::size_t k = 0; k + 1 < frames.size(); ++k) {
        const filter::FrameMotion m = vo.track(frames[k + 1].view());
        if (!m.ok()) throw Error(names[k] + " -> " + names[k + 1] + ": no consistent motion (" + m.failure + ")");
        // Rigid about frame k+1's centre: its rotation, and its centre at frame k's centre + (dx, dy).
        const double cx = (frames[k + 1].width - 1) / 2.0, cy = (frames[k + 1].height - 1) / 2.0;
        const double mx = (frames[k].width - 1) / 2.0 + m.dx_px, my = (frames[k].height - 1) / 2.0 + m.dy_px;
        const double ca = std::cos(m.rotation_rad), sa = std::sin(m.rotation_rad);
        const Similarity rigid{ca, sa, mx - (ca * cx - sa * cy), my - (sa * cx + ca * cy)};
        out.push_back({rigid, m.scale, m.inliers});
    }
    return out;
}

std::vector<Similarity> chain(const std::vector<RelativeMotion>& motions) {
    std::vector<Similarity> c{Similarity{}};
    for (const RelativeMotion& m : motions) c.push_back(compose(c.back(), m.next_to_this));
    return c;
}

Pose chained_pose(const Pose& anchor, const Similarity& t, const GrayImage& frame0, const GrayImage& frame_k) {
    const double c0x = (frame0.width - 1) / 2.0, c0y = (frame0.height - 1) / 2.0;
    const double cx = (frame_k.width - 1) / 2.0, cy = (frame_k.height - 1) / 2.0;
    const double qx = t.a * cx - t.b * cy + t.tx - c0x, qy = t.b * cx + t.a * cy + t.ty - c0y;  // T(c_k) - c_0
    const double c = std::cos(anchor.yaw) * anchor.scale, s = std::sin(anchor.yaw) * anchor.scale;
    return {static_cast<float>(anchor.x + c * qx - s * qy), static_cast<float>(anchor.y + s * qx + c * qy),
            static_cast<float>(anchor.yaw + t.angle()), static_cast<float>(anchor.scale * t.scale())};
}

ScaledTemplate template_for_scale(const GrayImage& frame, double scale) {
    if (scale >= 1) return {frame, 1.0};
    const int w = std::max(8, static_cast<int>(std::lround(frame.width * scale)));
    const int h = std::max(8, static_cast<int>(std::lround(frame.height * scale)));
    cv::Mat small;
    cv::resize(as_mat(frame), small, cv::Size(w, h), 0, 0, cv::INTER_AREA);
    // cv::resize maps template centre (w-1)/2 onto frame centre (W-1)/2 exactly, factor W/w.
    return {from_mat(small), static_cast<double>(frame.width) / w};
}

Registration register_frames(Backend& backend, const GrayImage& map, const std::vector<GrayImage>& frames,
                             const std::vector<std::string>& names, const RegisterOptions& o, GrayView valid) {
    if (frames.size() < 2) throw Error("register: need at least two consecutive frames");
    Registration r;
    r.motions = relative_motions(frames, names);
    r.chain = chain(r.motions);
    const MapHandle handle = backend.upload_map(map.view(), valid);

    const std::vector<Candidate> candidates =
        o.anchor_hint ? std::vector<Candidate>{{*o.anchor_hint, 0}} : global_candidates(map, valid, frames, r.chain, o);
    if (candidates.empty()) throw Error("register: the chained frames do not fit inside the map at any searched scale");
    std::vector<Templ> templs;
    for (std::size_t k = 0; k < frames.size(); ++k)
        templs.push_back({template_for_scale(frames[k], candidates[0].anchor.scale * r.chain[k].scale())});

    // Joint refinement of each candidate, coarse to fine; the best mean NCC wins.
    Candidate best;
    for (const Candidate& c : candidates) {
        Candidate cur = c;
        const struct {
            double r, step;
            int ny;
            double yaw;
            int ns;
            double sc;
        } levels[] = {{8, 2, 2, 1.5 * kDeg, 2, 0.02}, {2, 1, 1, 0.5 * kDeg, 1, 0.01}, {1, 0.5, 1, 0.2 * kDeg, 1, 0.004}};
        for (const auto& l : levels) {
            const std::vector<Pose> g = anchor_grid(cur.anchor, l.r, l.step, l.ny, l.yaw, l.ns, l.sc);
            cur = best_of(g, joint_scores(backend, handle, frames, templs, r.chain, g));
        }
        if (cur.score > best.score) best = cur;
    }
    r.anchor = best.anchor;
    r.joint_ncc = best.score;

    // Per frame: predicted from the previous frame's refined pose and the rigid motion, then a
    // local NCC refinement (coarse sparse grid, then fine dense) of position, yaw and scale.
    for (std::size_t k = 0; k < frames.size(); ++k) {
        const Pose predicted = k == 0 ? r.anchor
                                      : chained_pose(r.frames[k - 1].pose, r.motions[k - 1].next_to_this, frames[k - 1], frames[k]);
        const std::vector<Pose> g1 = anchor_grid(predicted, o.refine_radius_px, 2, 2, 1.5 * kDeg, 2, 0.04);
        const std::vector<float> s1 = score_all(backend, handle, templs[k], g1, sparse(0.2));
        Candidate cur = best_of(g1, std::vector<double>(s1.begin(), s1.end()));
        const std::vector<Pose> g2 = anchor_grid(cur.anchor, 2, 0.5, 2, 0.5 * kDeg, 2, 0.01);
        const std::vector<float> s2 = score_all(backend, handle, templs[k], g2, {});
        cur = best_of(g2, std::vector<double>(s2.begin(), s2.end()));
        const Pose chained = chained_pose(r.anchor, r.chain[k], frames[0], frames[k]);
        r.frames.push_back({cur.anchor, cur.score, cur.anchor.x - predicted.x, cur.anchor.y - predicted.y, cur.anchor.x - chained.x,
                            cur.anchor.y - chained.y});
    }
    return r;
}

Uniqueness check_unique(Backend& backend, const MapHandle& map, const GrayImage& frame, const Pose& pose, double radius,
                        double step) {
    // A template of half the map's resolution and 10 % random samples: the peaks of a
    // 200-metre-wide template are far wider than that sampling, and 26 000 poses stay cheap.
    const Templ t{template_for_scale(frame, pose.scale * 0.5)};
    Uniqueness u;
    u.ncc_at_pose = score_all(backend, map, Templ{template_for_scale(frame, pose.scale)}, {pose}, {})[0];
    const int n = static_cast<int>(std::floor(radius / step)), side = 2 * n + 1;
    const std::vector<Pose> g = anchor_grid(pose, n * step, step, 0, 0, 0, 0);  // row-major, side x side
    const std::vector<float> s = score_all(backend, map, t, g, sparse(0.1));
    const auto bi = std::max_element(s.begin(), s.end()) - s.begin();
    u.best_ncc = s[bi];
    u.best = g[bi];
    u.best_dist = std::hypot(g[bi].x - pose.x, g[bi].y - pose.y);
    // Runner-up: the best other local maximum (a separate peak, not the shoulder of the best).
    u.runner_up_ncc = -2;
    for (int r = 0; r < side; ++r)
        for (int c = 0; c < side; ++c) {
            const std::size_t i = static_cast<std::size_t>(r) * side + c;
            if (static_cast<std::ptrdiff_t>(i) == bi || s[i] <= u.runner_up_ncc) continue;
            bool peak = true;
            for (int dr = -1; dr <= 1 && peak; ++dr)
                for (int dc = -1; dc <= 1 && peak; ++dc) {
                    const int rr = r + dr, cc = c + dc;
                    if ((dr || dc) && rr >= 0 && rr < side && cc >= 0 && cc < side) peak = s[static_cast<std::size_t>(rr) * side + cc] <= s[i];
                }
            if (!peak || std::hypot(g[i].x - g[bi].x, g[i].y - g[bi].y) <= kShoulderPx) continue;
            u.runner_up_ncc = s[i];
            u.runner_up_dist = std::hypot(g[i].x - pose.x, g[i].y - pose.y);
        }
    return u;
}

std::vector<PoseRow> read_pose_rows(const std::string& path) {
    // Read whole after the file checks (a FIFO or device is refused), a UTF-8 byte order mark skipped.
    const std::string text = io::read_input_file(path, io::kMaxTableFileBytes, "a pose file");
    std::istringstream in(std::string(io::strip_bom(text)));
    std::vector<PoseRow> rows;
    std::string line;
    for (int n = 1; std::getline(in, line); ++n) {
        const std::string where = path + ":" + std::to_string(n) + ": ";
        if (line.size() > 4096) throw Error(where + "line of " + std::to_string(line.size()) + " bytes (at most 4096); not a pose file?");
        if (n == 1) {
            if (line.rfind("frame,x,y,yaw,scale,ncc", 0) != 0) throw Error(where + "expected the header frame,x,y,yaw,scale,ncc");
            continue;
        }
        if (line.empty() || line[0] == '#') continue;
        std::vector<std::string> f;
        std::stringstream ss(line);
        for (std::string cell; std::getline(ss, cell, ',');) f.push_back(cell);
        if (f.size() < 6 || f[0].empty()) throw Error(where + "expected frame,x,y,yaw,scale,ncc");
        double v[5];
        for (int i = 0; i < 5; ++i) {
            const auto x = parse_finite_real(f[i + 1]);
            if (!x) throw Error(where + "column " + std::to_string(i + 2) + " '" + io::quote_input(f[i + 1]) + "' is not a finite number");
            v[i] = *x;
        }
        if (!(v[3] > 0)) throw Error(where + "scale must be positive");
        if (std::fabs(v[0]) > 1e7 || std::fabs(v[1]) > 1e7 || std::fabs(v[2]) > 1000 || v[3] > 1e4)
            throw Error(where + "x, y beyond 1e7 px, |yaw| beyond 1000 rad or scale beyond 1e4: not a pose");
        rows.push_back({f[0], {static_cast<float>(v[0]), static_cast<float>(v[1]), static_cast<float>(v[2]), static_cast<float>(v[3])}, v[4]});
    }
    if (rows.empty()) throw Error(path + ": no poses");
    return rows;
}

}  // namespace trn::reg
