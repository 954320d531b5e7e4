#include "trn/filter/visual_odometry.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include <opencv2/calib3d.hpp>
#include <opencv2/features2d.hpp>
#include <opencv2/imgproc.hpp>

#include "trn/detail/angles.hpp"
#include "trn/filter/visual_odometry_track.hpp"
#include "trn/error.hpp"

namespace trn::filter {

namespace {

std::string number(double v) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.3g", v);
    return buf;
}

cv::Mat as_mat(GrayView v) { return cv::Mat(v.height, v.width, CV_8UC1, const_cast<std::uint8_t*>(v.data), static_cast<std::size_t>(v.stride)); }

}  // namespace

// A frame as the tracker keeps it: the working (downscaled) copy, its features in full-frame pixels.
struct VisualOdometry::Reference {
    int width = 0, height = 0;
    double factor = 1;  // full-frame pixels per working pixel
    cv::Mat small;
    std::vector<cv::Point2f> points;  // keypoints, full-frame pixels
    cv::Mat descriptors;
};

void VisualOdometryOptions::validate() const {
    if (max_features < 16 || max_features > 100000) throw Error("visual odometry: max_features " + std::to_string(max_features) + " is outside [16, 100000]");
    if (max_width < 32 || max_width > 16384) throw Error("visual odometry: max_width " + std::to_string(max_width) + " is outside [32, 16384]");
    if (!(ransac_threshold_px > 0 && ransac_threshold_px <= 50)) throw Error("visual odometry: ransac_threshold_px must be in (0, 50]");
    if (ransac_iterations < 1 || ransac_iterations > 1000000) throw Error("visual odometry: ransac_iterations must be in [1, 1000000]");
    if (!(ransac_confidence > 0 && ransac_confidence < 1)) throw Error("visual odometry: ransac_confidence must be in (0, 1)");
    if (min_inliers < 3) throw Error("visual odometry: min_inliers " + std::to_string(min_inliers) + " must be >= 3 (2 matches fix a similarity)");
    if (!(min_phase_response >= 0 && min_phase_response <= 1)) throw Error("visual odometry: min_phase_response must be in [0, 1]");
}

const char* to_string(MotionMethod m) {
    switch (m) {
        case MotionMethod::Features: return "features";
        case MotionMethod::PhaseCorrelation: return "phase";
        default: return "none";
    }
}

VisualOdometry::VisualOdometry(const VisualOdometryOptions& options) : options_(options) { options_.validate(); }
VisualOdometry::~VisualOdometry() = default;
void VisualOdometry::reset() { reference_.reset(); }

FrameMotion VisualOdometry::track(GrayView frame) {
    if (frame.empty() || frame.width < 16 || frame.height < 16)
        throw Error("visual odometry: frame " + std::to_string(frame.width) + "x" + std::to_string(frame.height) + " is smaller than 16x16");
    auto cur = std::make_unique<Reference>();
    cur->width = frame.width, cur->height = frame.height;
    const cv::Mat full = as_mat(frame);
    if (frame.width > options_.max_width) {
        const int h = std::max(16, static_cast<int>(std::lround(double(frame.height) * options_.max_width / frame.width)));
        cv::resize(full, cur->small, cv::Size(options_.max_width, h), 0, 0, cv::INTER_AREA);
        cur->factor = double(frame.width) / options_.max_width;
    } else {
        cur->small = full.clone();
    }
    std::vector<cv::KeyPoint> kps;
    cv::ORB::create(options_.max_features)->detectAndCompute(cur->small, cv::noArray(), kps, cur->descriptors);
    for (const cv::KeyPoint& k : kps)  // working pixel centre -> full-frame pixel centre (cv::resize's mapping)
        cur->points.push_back({static_cast<float>((k.pt.x + 0.5) * cur->factor - 0.5), static_cast<float>((k.pt.y + 0.5) * cur->factor - 0.5)});

    FrameMotion m;
    if (!reference_) {
        m.failure = "first frame";
        reference_ = std::move(cur);
        return m;
    }
    const Reference& prev = *reference_;
    const double pcx = (prev.width - 1) / 2.0, pcy = (prev.height - 1) / 2.0;
    const double ccx = (cur->width - 1) / 2.0, ccy = (cur->height - 1) / 2.0;

    // Features: current -> previous similarity by RANSAC; the current centre mapped into the previous frame.
    std::string why;
    if (prev.descriptors.empty() || cur->descriptors.empty()) {
        why = "no ORB features";
    } else {
        std::vector<cv::DMatch> matches;
        cv::BFMatcher(cv::NORM_HAMMING, true).match(cur->descriptors, prev.descriptors, matches);
        std::vector<cv::Point2f> from, to;
        for (const cv::DMatch& d : matches) from.push_back(cur->points[d.queryIdx]), to.push_back(prev.points[d.trainIdx]);
        if (from.size() < static_cast<std::size_t>(options_.min_inliers)) {
            why = std::to_string(from.size()) + " ORB matches";
        } else {
            std::vector<std::uint8_t> inlier;
            const cv::Mat t = cv::estimateAffinePartial2D(from, to, inlier, cv::RANSAC, options_.ransac_threshold_px * prev.factor,
                                                              static_cast<std::size_t>(options_.ransac_iterations), options_.ransac_confidence);
            m.inliers = static_cast<int>(std::count(inlier.begin(), inlier.end(), 1));
            const double a = t.empty() ? 0 : t.at<double>(0, 0), b = t.empty() ? 0 : t.at<double>(1, 0);
            const double scale = std::hypot(a, b);
            if (t.empty() || m.inliers < options_.min_inliers) {
                why = std::to_string(m.inliers) + " RANSAC inliers < " + std::to_string(options_.min_inliers);
            } else if (!(scale > 0.5 && scale < 2)) {  // a frame-to-frame altitude change of 2x is no flight's
                why = "similarity scale " + number(scale) + " outside (0.5, 2)";
            } else {
                m.method = MotionMethod::Features;
                m.dx_px = a * ccx - b * ccy + t.at<double>(0, 2) - pcx;
                m.dy_px = b * ccx + a * ccy + t.at<double>(1, 2) - pcy;
                m.rotation_rad = std::atan2(b, a);
                m.scale = scale;
            }
        }
    }
    // Phase correlation: a pure shift of the whole frame (no rotation), same-size frames only.
    if (!m.ok() && options_.phase_correlation) {
        if (prev.small.size() != cur->small.size() || prev.width != cur->width || prev.height != cur->height) {
            why += "; no phase correlation (frames differ in size)";
        } else {
            cv::Mat p, c, window;
            prev.small.convertTo(p, CV_64F);
            cur->small.convertTo(c, CV_64F);
            cv::createHanningWindow(window, p.size(), CV_64F);
            double response = 0;
            const cv::Point2d shift = cv::phaseCorrelate(p, c, window, &response);  // content moved by +shift
            m.response = response;
            if (response >= options_.min_phase_response && std::isfinite(shift.x) && std::isfinite(shift.y)) {
                m.method = MotionMethod::PhaseCorrelation;
                m.dx_px = -shift.x * prev.factor, m.dy_px = -shift.y * prev.factor;  // the camera moved the other way
            } else {
                why += "; phase-correlation peak " + number(response) + " < " + number(options_.min_phase_response);
            }
        }
    }
    if (!m.ok()) m.failure = why;
    reference_ = std::move(cur);
    return m;
}

FrameMotion estimate_frame_motion(GrayView previous, GrayView current, const VisualOdometryOptions& options) {
    VisualOdometry vo(options);
    vo.track(previous);
    return vo.track(current);
}

GroundStep ground_displacement(double dx_px, double dy_px, double metres_per_px, double heading_rad) {
    // camera.hpp: map offset = scale * R(yaw) * (du, dv), map x east, map y south.
    const double c = std::cos(heading_rad), s = std::sin(heading_rad);
    return {metres_per_px * (c * dx_px - s * dy_px), -metres_per_px * (s * dx_px + c * dy_px)};
}

VisualOdometrySource::VisualOdometrySource(FlightSource& inner, double map_metres_per_pixel, const VisualOdometryOptions& options,
                                           bool own_yaw)
    : inner_(inner), mpp_(map_metres_per_pixel) {
    if (!(map_metres_per_pixel > 0)) throw Error("VisualOdometrySource: map_metres_per_pixel must be > 0");
    track_ = std::make_unique<VisualOdometryTrack>(options, own_yaw);
}

VisualOdometrySource::~VisualOdometrySource() = default;

const VisualOdometrySource::Counts& VisualOdometrySource::counts() const { return track_->counts(); }

const FrameMotion& VisualOdometrySource::last_motion() const { return track_->last_motion(); }

bool VisualOdometrySource::next(FlightSample& s) {
    if (!inner_.next(s)) return false;
    const VisualOdometryTrack::Step v =
        track_->next(s.image.pixels.empty() ? GrayView{} : s.image.view(), s.map_px_per_camera_px * mpp_, s.heading_rad);
    s.odometry_east_m = v.east_m, s.odometry_north_m = v.north_m, s.odometry_yaw_rad = v.yaw_rad;
    s.odometry_source = v.source;
    return true;
}

}  // namespace trn::filter
