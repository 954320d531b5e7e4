#include "trn/filter/particle_filter.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <unordered_set>

#include "trn/detail/splitmix.hpp"
#include "trn/error.hpp"
#include "trn/filter/kld.hpp"
#include "trn/limits.hpp"
#include "trn/detail/angles.hpp"

namespace trn::filter {
namespace {
// Lost odometry: a heading change above this since the last step is a turn (UpdateModel).
constexpr double kLostStraightTurnRad = 30 * kDeg;
// Odometry lost within this many steps supports no position: the map is then the better prior,
// and a particle without a valid score gets weight 0 again (UpdateModel::unknown_neutral).
constexpr std::size_t kDoubtSteps = 20;
constexpr double kDoubtWholeShare = 0.9;  // of a whole patch's samples, while in doubt
constexpr double kSettledSpreadM = 10;    // the cloud's spread (m) that ends the start's doubt
}  // namespace

SamplingMethod parse_sampling_method(std::string_view text) {
    if (text == "kld") return SamplingMethod::Kld;
    if (text == "importance") return SamplingMethod::Importance;
    if (text == "rejection") return SamplingMethod::Rejection;
    throw Error("sampling method '" + std::string(text) + "': unknown; expected kld, importance or rejection");
}

const char* to_string(SamplingMethod m) {
    return m == SamplingMethod::Kld ? "kld" : m == SamplingMethod::Importance ? "importance" : "rejection";
}

HeadingMode parse_heading_mode(std::string_view text) {
    if (text == "compass") return HeadingMode::Compass;
    if (text == "none") return HeadingMode::None;
    throw Error("heading '" + std::string(text) + "': unknown; expected compass or none");
}

const char* to_string(HeadingMode m) { return m == HeadingMode::None ? "none" : "compass"; }

Profile parse_profile(std::string_view text) {
    if (text == "ours") return Profile::Ours;
    if (text == "dissertation") return Profile::Dissertation;
    throw Error("profile '" + std::string(text) + "': unknown; expected ours or dissertation");
}

const char* to_string(Profile p) { return p == Profile::Dissertation ? "dissertation" : "ours"; }

FilterConfig dissertation_profile() {
    FilterConfig c;  // particle_filter.hpp says where each value comes from
    c.kld_epsilon = 0.05;
    c.kld_upper_quantile = 1 - 0.9;  // z_(1-delta), delta = 0.9: -1.28
    c.kld_bin_m = 5;
    c.min_particles = 100;
    c.max_particles = kDissertationMaxParticles;
    c.initial_particles = 500;
    c.fixed_particles = 500;
    c.init_radius_m = 300;
    c.lock.enabled = false;
    c.update.unknown_neutral = false;
    c.update.min_ess_fraction = 0;
    c.update.min_valid_fraction = 0.9;
    c.update.lost_body_velocity = false;
    c.motion.equations = MotionEquations::Dissertation;
    c.motion.alpha1 = c.motion.alpha2 = c.motion.alpha3 = 1;
    c.motion.eps_tran_m = 3;
    c.motion.eps_rot_deg = 6;
    c.init_heading_sd_deg = c.motion.eps_rot_deg / 3;
    return c;
}

FilterConfig profile_config(Profile p) { return p == Profile::Dissertation ? dissertation_profile() : FilterConfig{}; }

void UpdateModel::validate() const {
    if (!(min_ess_fraction >= 0 && min_ess_fraction <= 1))
        throw Error("filter config: update.min_ess_fraction " + std::to_string(min_ess_fraction) + " must be in [0, 1]");
    if (!(min_valid_fraction > 0 && min_valid_fraction <= 1))
        throw Error("filter config: update.min_valid_fraction " + std::to_string(min_valid_fraction) + " must be in (0, 1]");
    if (!(unknown_quantile >= 0 && unknown_quantile <= 1))
        throw Error("filter config: update.unknown_quantile " + std::to_string(unknown_quantile) + " must be in [0, 1]");
}

void FilterConfig::validate() const {
    auto positive = [](double v, const char* name) {
        if (!(v > 0) || !std::isfinite(v)) throw Error(std::string("filter config: ") + name + " must be > 0");
    };
    positive(metres_per_pixel, "metres_per_pixel");
    positive(kld_epsilon, "kld_epsilon");
    positive(kld_bin_m, "kld_bin_m");
    if (!(kld_yaw_bin_deg > 0 && kld_yaw_bin_deg <= 360)) throw Error("filter config: kld_yaw_bin_deg must be in (0, 360]");
    if (heading != HeadingMode::Compass && heading != HeadingMode::None) throw Error("filter config: heading must be compass or none");
    positive(init_radius_m, "init_radius_m");
    positive(reinit_radius_m, "reinit_radius_m");
    if (!std::isnan(init_heading_sd_deg) && !(init_heading_sd_deg >= 0 && init_heading_sd_deg <= 360))
        throw Error("filter config: init_heading_sd_deg must be in [0, 360] (or NaN: the motion model's eps_rot_deg)");
    motion.validate();
    update.validate();
    lock.validate();
    if (!(kld_upper_quantile > 0 && kld_upper_quantile < 1)) throw Error("filter config: kld_upper_quantile must be in (0, 1)");
    if (min_particles < 1) throw Error("filter config: min_particles must be >= 1");
    if (max_particles < min_particles) throw Error("filter config: max_particles must be >= min_particles");
    if (fixed_particles < 1) throw Error("filter config: fixed_particles must be >= 1");
    limits::check_count("filter config: initial_particles", static_cast<std::int64_t>(std::min<std::size_t>(initial_particles, INT64_MAX)),
                        limits::kMaxParticles, limits::kParticleBytes);
    limits::check_count("filter config: max_particles", static_cast<std::int64_t>(std::min<std::size_t>(max_particles, INT64_MAX)),
                        limits::kMaxParticles, limits::kParticleBytes);
    limits::check_count("filter config: fixed_particles", static_cast<std::int64_t>(std::min<std::size_t>(fixed_particles, INT64_MAX)),
                        limits::kMaxParticles, limits::kParticleBytes);
}

ParticleFilter::ParticleFilter(ParticleScorer& scorer, const FilterConfig& config)
    : scorer_(scorer),
      config_(config),
      lock_((config.validate(), config.lock), config.metres_per_pixel, config.seed),  // validated before anything is built
      yaw_state_(config.heading == HeadingMode::None),
      rng_(splitmix::mix64(config.seed ^ 0x5DEECE66Dull)) {}

double ParticleFilter::uniform() { return splitmix::uniform(rng_); }

double ParticleFilter::normal() { return splitmix::normal(rng_); }

void ParticleFilter::scatter(double x, double y, double heading, bool have_heading, double radius_m, std::size_t count,
                             std::size_t first, double heading_sd_deg) {
    if (std::isnan(heading_sd_deg)) heading_sd_deg = config_.motion.eps_rot_deg;
    const double r_px = radius_m / config_.metres_per_pixel;
    particles_.resize(first + count);
    for (std::size_t i = first; i < particles_.size(); ++i) {
        Particle& p = particles_[i];
        const double r = r_px * std::sqrt(uniform()), a = 2 * kPi * uniform();  // uniform over the disc
        p.x = x + r * std::cos(a);
        p.y = y + r * std::sin(a);
        p.yaw = have_heading ? wrap_angle(heading + heading_sd_deg * kDeg * normal()) : wrap_angle(2 * kPi * uniform());
        p.weight = 1;
    }
}

// Without a compass, re-scattered particles keep the yaw the filter has learnt: around `yaw` with
// its spread (at least one KLD yaw bin), uniform while that spread is still above 90 degrees.
void ParticleFilter::scatter_yaw_state(double x, double y, double yaw, double yaw_sd, double radius_m, std::size_t count, std::size_t first) {
    const double sd_deg = std::max(yaw_sd / kDeg, config_.kld_yaw_bin_deg);
    scatter(x, y, yaw, sd_deg <= 90, radius_m, count, first, sd_deg);
}

std::size_t ParticleFilter::initial_count() const {
    return config_.initial_particles > 0                  ? config_.initial_particles
           : config_.sampling == SamplingMethod::Kld ? config_.max_particles
                                                     : config_.fixed_particles;
}

void ParticleFilter::initialise(double x, double y, double heading_rad) {
    if (!std::isfinite(x) || !std::isfinite(y)) throw Error("ParticleFilter::initialise: position must be finite");
    const std::size_t n = initial_count();
    scatter(x, y, heading_rad, std::isfinite(heading_rad), config_.init_radius_m, n, 0, config_.init_heading_sd_deg);
    last_east_ = last_north_ = 0;
    last_dt_s_ = NAN;
    lost_span_ = 0;
    steps_since_start_ = 0;
    last_heading_ = heading_rad;
    lock_.reset(x, y, config_.init_radius_m);
    initialised_ = true;
    update_estimate();
}

void ParticleFilter::reanchor(double x, double y, double radius_m, double heading_rad) {
    if (!std::isfinite(x) || !std::isfinite(y)) throw Error("re-anchor: the position must be finite map pixels");
    if (!(radius_m > 0) || !std::isfinite(radius_m))
        throw Error("re-anchor: radius_m must be > 0 metres (how far the true position may be from the fix), got " + std::to_string(radius_m));
    const std::size_t n = initial_count();
    if (yaw_state_ && std::isnan(heading_rad) && initialised_)
        scatter_yaw_state(x, y, estimate_.yaw, estimate_.yaw_sd, radius_m, n, 0);
    else
        scatter(x, y, heading_rad, std::isfinite(heading_rad), radius_m, n, 0, config_.init_heading_sd_deg);
    if (std::isfinite(heading_rad)) last_heading_ = heading_rad;
    lock_.reset(x, y, radius_m);
    steps_since_start_ = 0;
    initialised_ = true;
    update_estimate();
}

StepMotion ParticleFilter::motion_from(const FilterInput& in, bool& lost) {
    double east = in.odometry_east_m, north = in.odometry_north_m;
    lost = !std::isfinite(east) || !std::isfinite(north);
    steps_since_lost_ = lost ? 0 : steps_since_lost_ + 1;
    ++steps_since_start_;
    const bool ours_lost = lost && config_.update.lost_body_velocity;
    // With frame times, a held step is the last good step's velocity over this interval (ours).
    const bool timed = std::isfinite(in.dt_s) && in.dt_s >= 0;
    const double span = ours_lost && timed && last_dt_s_ > 0 ? in.dt_s / last_dt_s_ : 1.0;
    lost_span_ = lost ? lost_span_ + span : 0;
    double diffusion_m = 0;
    if (lost) {
        east = last_east_, north = last_north_;  // constant velocity while odometry is lost
        const double step_m = std::hypot(east, north);
        const bool know_turn = !yaw_state_ && std::isfinite(in.heading_rad) && std::isfinite(last_heading_);
        const double turn = know_turn ? wrap_angle(in.heading_rad - last_heading_) : 0.0;
        if (ours_lost && (yaw_state_ || !know_turn || std::abs(turn) > kLostStraightTurnRad)) {
            // In a turn (or with no compass to tell) a held velocity flies straight on while the
            // aircraft comes round: no step, and a disc of half the distance flown since it was lost.
            east = north = 0;
            diffusion_m = 0.5 * step_m * lost_span_;
        } else if (ours_lost) {
            // Flying straight: the last step held in the aircraft's frame, turned with the compass.
            const double c = std::cos(turn), sn = std::sin(turn);
            east = last_east_ * c + last_north_ * sn, north = last_north_ * c - last_east_ * sn;
            last_east_ = east, last_north_ = north;
            east *= span, north *= span;
        }
    } else {
        last_east_ = east, last_north_ = north;
        last_dt_s_ = timed ? in.dt_s : NAN;
    }
    // Lost odometry: triple noise (the dissertation profile, and ours for one step); ours grows it
    // with every further lost step (time), as a dead-reckoned position's doubt grows.
    const double lost_gain = !lost ? 1.0 : ours_lost ? std::min(3.0 * lost_span_, 15.0) : 3.0;
    const double time_sd_px = timed ? config_.motion.eps_tran_m_per_s * in.dt_s / config_.metres_per_pixel : 0.0;
    if (yaw_state_) {  // the increment is in the previous frame's axes; the rotation unknown while lost
        StepMotion m = make_yaw_state_motion(east, north, lost ? NAN : in.odometry_yaw_rad, config_.metres_per_pixel);
        m.noise_gain = lost_gain;
        m.diffusion_px = diffusion_m / config_.metres_per_pixel;
        m.time_sd_px = time_sd_px;
        return m;
    }
    const bool have_heading = std::isfinite(in.heading_rad);
    const double frame_heading = have_heading ? in.heading_rad : last_heading_;
    const double turn = have_heading && std::isfinite(last_heading_) ? wrap_angle(in.heading_rad - last_heading_) : 0;
    StepMotion m = make_step_motion(east, north, in.heading_rad, frame_heading, turn, config_.metres_per_pixel);
    if (have_heading) last_heading_ = in.heading_rad;
    m.noise_gain = lost_gain;
    m.diffusion_px = diffusion_m / config_.metres_per_pixel;
    m.time_sd_px = time_sd_px;
    return m;
}

std::size_t ParticleFilter::draw_index(double total) {
    const double u = uniform() * total;
    const auto it = std::upper_bound(cumulative_.begin(), cumulative_.end(), u);
    return std::min<std::size_t>(it - cumulative_.begin(), cumulative_.size() - 1);
}

std::size_t ParticleFilter::sample_and_propagate(const StepMotion& m) {
    cumulative_.resize(particles_.size());
    double total = 0, max_w = 0;
    for (std::size_t i = 0; i < particles_.size(); ++i) {
        total += particles_[i].weight;
        cumulative_[i] = total;
        max_w = std::max(max_w, particles_[i].weight);
    }
    const double bin_px = config_.kld_bin_m / config_.metres_per_pixel, yaw_bin = config_.kld_yaw_bin_deg * kDeg;
    std::unordered_set<std::uint64_t> bins;
    auto occupy = [&](const Particle& p) {
        const auto bx = static_cast<std::int64_t>(std::floor(p.x / bin_px)), by = static_cast<std::int64_t>(std::floor(p.y / bin_px));
        std::uint64_t key = (static_cast<std::uint64_t>(bx) << 32) ^ static_cast<std::uint32_t>(by);
        if (yaw_state_) {  // (x, y, yaw) cells: yaw binned from -pi, the last bin at most yaw_bin wide
            const auto byaw = static_cast<std::uint64_t>(std::floor((p.yaw + kPi) / yaw_bin));
            key = splitmix::mix64(key ^ (byaw * 0x9E3779B97F4A7C15ull));
        }
        bins.insert(key);
    };
    drawn_.clear();
    auto add = [&](std::size_t i) {
        Particle p = particles_[i];
        const std::array<double, 5> z{normal(), normal(), normal(), normal(), normal()};
        propagate_particle(config_.motion, m, config_.metres_per_pixel, z, p.x, p.y, p.yaw);
        p.weight = 1;
        drawn_.push_back(p);
        occupy(p);
    };
    switch (config_.sampling) {
        case SamplingMethod::Kld: {
            double bound = 0;
            std::size_t counted_bins = 0;
            while (drawn_.size() < config_.max_particles) {
                if (drawn_.size() >= config_.min_particles) {
                    if (bins.size() != counted_bins) {  // the bound only moves when a new bin fills
                        counted_bins = bins.size();
                        bound = kld_bound(counted_bins, config_.kld_epsilon, config_.kld_upper_quantile);
                    }
                    if (static_cast<double>(drawn_.size()) >= bound) break;
                }
                add(draw_index(total));
            }
            break;
        }
        case SamplingMethod::Importance:
            while (drawn_.size() < config_.fixed_particles) add(draw_index(total));
            break;
        case SamplingMethod::Rejection:
            // Pick uniformly, keep with probability weight / max weight.
            while (drawn_.size() < config_.fixed_particles) {
                const std::size_t i = std::min(particles_.size() - 1, static_cast<std::size_t>(uniform() * particles_.size()));
                if (uniform() * max_w < particles_[i].weight) add(i);
            }
            break;
    }
    particles_.swap(drawn_);
    return bins.size();
}

namespace {
// The largest beta in (0, 1] whose weights exp(beta * log w) keep ESS >= min_ess * n (bisection:
// the ESS of tempered weights falls as beta grows). log_w: finite, any offset.
double tempering_exponent(std::span<const double> log_w, double min_ess) {
    const double top = *std::max_element(log_w.begin(), log_w.end());
    const double n = static_cast<double>(log_w.size());
    auto ess_share = [&](double beta) {
        double s = 0, s2 = 0;
        for (const double l : log_w) {
            const double w = std::exp(beta * (l - top));
            s += w, s2 += w * w;
        }
        return s * s / s2 / n;
    };
    if (ess_share(1.0) >= min_ess) return 1.0;
    double lo = 0, hi = 1;
    for (int i = 0; i < 30; ++i) {
        const double mid = 0.5 * (lo + hi);
        (ess_share(mid) >= min_ess ? lo : hi) = mid;
    }
    return lo;
}
}  // namespace

std::size_t ParticleFilter::measure(const FilterInput& in, double& score_ms, double& frame_weight) {
    poses_.resize(particles_.size());
    for (std::size_t i = 0; i < particles_.size(); ++i)
        poses_[i] = {static_cast<float>(particles_[i].x), static_cast<float>(particles_[i].y), static_cast<float>(particles_[i].yaw), 1.0f};
    // Probes at random places ride in the same batch (the lock monitor's baseline).
    const double probe_yaw = !yaw_state_ && std::isfinite(in.heading_rad) ? in.heading_rad : estimate_.yaw;
    lock_.add_probes(estimate_.x, estimate_.y, probe_yaw, poses_);
    scores_.resize(poses_.size());
    const auto t0 = std::chrono::steady_clock::now();
    scorer_.score(in.frame, in.map_px_per_camera_px, poses_, scores_, nullptr);
    score_ms += std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    std::size_t invalid = 0;
    for (std::size_t i = 0; i < particles_.size(); ++i) {
        double w = 0;
        if (scores_[i].valid()) {
            w = config_.conversion(scores_[i].ncc);
            if (!(w > 0) || !std::isfinite(w)) w = 0;
        } else {
            ++invalid;
        }
        particles_[i].weight = w;
    }
    probe_scores_.assign(scores_.begin() + static_cast<std::ptrdiff_t>(particles_.size()), scores_.end());
    scores_.resize(particles_.size());
    if (!probe_scores_.empty()) score_near_probes(in, probe_yaw, score_ms);
    frame_weight = 1;
    const UpdateModel& u = config_.update;
    // Without a compass the odometry's direction on the map is each particle's own guess until the
    // yaw has settled: from a start (or re-anchor) the odometry supports no position until the cloud
    // has gathered on one place (its spread, last step). With a compass the start circle is one.
    if (steps_since_start_ <= kDoubtSteps && (!yaw_state_ || estimate_.spread_px * config_.metres_per_pixel < kSettledSpreadM))
        steps_since_start_ = SIZE_MAX / 2;
    const bool doubt = steps_since_lost_ <= kDoubtSteps || steps_since_start_ <= kDoubtSteps;
    if (u.unknown_neutral) {
        // A whole patch's sample count: the most any particle had on the map (a frame entirely over
        // partial patches takes its best-covered one as whole).
        std::uint32_t whole = 0;
        for (std::size_t i = 0; i < particles_.size(); ++i) whole = std::max(whole, scores_[i].valid_samples);
        if (doubt) {
            // No position is supported yet (a compass-less start) or any more (lost odometry): the map
            // is the prior. A particle off it learns nothing and gets weight 0 (above), and one whose
            // patch is partly off it counts only with nearly a whole patch of evidence.
            for (std::size_t i = 0; i < particles_.size(); ++i)
                if (scores_[i].valid() && scores_[i].valid_samples < kDoubtWholeShare * whole) particles_[i].weight = 0;
        } else if (invalid == particles_.size()) {  // nothing under any particle: the frame tells nothing
            for (Particle& p : particles_) p.weight = 1;
            frame_weight = 0;
            return invalid;
        } else if (invalid > 0 || std::any_of(scores_.begin(), scores_.end(), [whole](const ParticleScore& sc) {
                       return sc.valid() && sc.valid_samples < whole;
                   })) {  // some particles unknown or partly covered
            valid_ncc_.clear();  // for their quantile
            for (std::size_t i = 0; i < particles_.size(); ++i)
                if (scores_[i].valid()) valid_ncc_.push_back(scores_[i].ncc);
            const auto rank = static_cast<std::ptrdiff_t>(std::floor(u.unknown_quantile * static_cast<double>(valid_ncc_.size() - 1) + 0.5));
            const auto mid = valid_ncc_.begin() + rank;
            std::nth_element(valid_ncc_.begin(), mid, valid_ncc_.end());
            double neutral = config_.conversion(*mid);
            if (!(neutral > 0) || !std::isfinite(neutral)) neutral = 0;
            for (std::size_t i = 0; i < particles_.size(); ++i) {
                double& w = particles_[i].weight;
                if (!scores_[i].valid()) {
                    w = neutral;
                } else if (scores_[i].valid_samples < whole && w > 0 && neutral > 0) {
                    // A partly covered patch is evidence in proportion to its samples: its weight
                    // moves from the neutral one towards its own as its share of a whole patch grows.
                    const double share = static_cast<double>(scores_[i].valid_samples) / whole;
                    w = std::exp(share * std::log(w) + (1 - share) * std::log(neutral));
                }
            }
        }
    }
    if (u.min_ess_fraction > 0) {
        log_weights_.resize(particles_.size());
        bool any = false;
        for (std::size_t i = 0; i < particles_.size(); ++i) {
            const double w = particles_[i].weight;
            any = any || w > 0;
            log_weights_[i] = w > 0 ? std::log(w) : -1e300;
        }
        if (any) {
            frame_weight = tempering_exponent(log_weights_, u.min_ess_fraction);
            if (frame_weight < 1) {
                const double top = *std::max_element(log_weights_.begin(), log_weights_.end());
                for (std::size_t i = 0; i < particles_.size(); ++i)
                    particles_[i].weight = particles_[i].weight > 0 ? std::exp(frame_weight * (log_weights_[i] - top)) : 0;
            }
        }
    }
    return invalid;
}

void ParticleFilter::update_estimate() {
    double sw = 0, sx = 0, sy = 0, ss = 0, sc = 0, best = -1;
    for (std::size_t i = 0; i < particles_.size(); ++i) {
        const Particle& p = particles_[i];
        sw += p.weight, sx += p.weight * p.x, sy += p.weight * p.y;
        ss += p.weight * std::sin(p.yaw), sc += p.weight * std::cos(p.yaw);
        if (p.weight > best) {
            best = p.weight;
            estimate_.best_x = p.x, estimate_.best_y = p.y, estimate_.best_yaw = p.yaw;
            estimate_.best_ncc = i < scores_.size() && scores_.size() == particles_.size() ? scores_[i].ncc : 0;
        }
    }
    if (sw > 0) {
        estimate_.x = sx / sw, estimate_.y = sy / sw, estimate_.yaw = std::atan2(ss, sc);
        double s2 = 0;
        for (const Particle& p : particles_) s2 += p.weight * ((p.x - estimate_.x) * (p.x - estimate_.x) + (p.y - estimate_.y) * (p.y - estimate_.y));
        estimate_.spread_px = std::sqrt(s2 / sw);
        double cxx = 0, cxy = 0, cyy = 0;
        for (const Particle& p : particles_) {
            const double dx = p.x - estimate_.x, dy = p.y - estimate_.y;
            cxx += p.weight * dx * dx, cxy += p.weight * dx * dy, cyy += p.weight * dy * dy;
        }
        estimate_.cov_xx = cxx / sw, estimate_.cov_xy = cxy / sw, estimate_.cov_yy = cyy / sw;
        const double resultant = std::min(1.0, std::hypot(ss, sc) / sw);  // mean resultant length R
        estimate_.yaw_sd = std::sqrt(-2 * std::log(std::max(resultant, 1e-12)));  // uniform yaws: large (> pi)
    }
}

StepReport ParticleFilter::step(const FilterInput& in) {
    if (!initialised_) throw Error("ParticleFilter::step: call initialise() first");
    StepReport r;
    const StepMotion m = motion_from(in, r.odometry_lost);
    r.occupied_bins = sample_and_propagate(m);
    // The step on the map: with a compass the increment is east/north already; without one it is in
    // the previous frame's axes, turned here by the estimate's yaw before the step.
    double step_east_px = m.east_px, step_north_px = m.north_px;
    const double yaw_before = estimate_.yaw, yaw_sd_before = estimate_.yaw_sd;
    if (yaw_state_) {
        const double sn = std::sin(yaw_before), cs = std::cos(yaw_before);
        step_east_px = m.east_px * cs + m.north_px * sn, step_north_px = m.north_px * cs - m.east_px * sn;
    }
    lock_.predict(step_east_px, -step_north_px);
    r.frame_missing = in.frame.empty();
    scores_.clear();
    probe_scores_.clear();
    if (!r.frame_missing) {
        r.off_map = measure(in, r.score_ms, r.frame_weight);
        double total = 0;
        for (const Particle& p : particles_) total += p.weight;
        if (!(total > 0) || !std::isfinite(total)) {
            // Collapse: redraw around the last estimate moved by this step's odometry, score again.
            r.reinitialised = true;
            const double cx = estimate_.x + step_east_px, cy = estimate_.y - step_north_px;
            const std::size_t n = particles_.size();
            if (yaw_state_)
                scatter_yaw_state(cx, cy, wrap_angle(yaw_before + (std::isfinite(m.rotation_rad) ? m.rotation_rad : 0.0)), yaw_sd_before,
                                  config_.reinit_radius_m, n, 0);
            else
                scatter(cx, cy, m.heading_rad, m.have_heading, config_.reinit_radius_m, n);
            r.off_map += measure(in, r.score_ms, r.frame_weight);
            total = 0;
            for (const Particle& p : particles_) total += p.weight;
            if (!(total > 0) || !std::isfinite(total))
                for (Particle& p : particles_) p.weight = 1;  // nothing to learn from this frame
        }
    }
    update_estimate();
    r.estimate = estimate_;
    r.particles = particles_.size();
    if (!r.frame_missing) {
        check_lock(m, r);
        r.lock.redrawn = r.reinitialised;
        r.lock.blind = r.frame_weight == 0;
    }
    ++counters_.steps;
    counters_.odometry_lost += r.odometry_lost;
    counters_.frames_missing += r.frame_missing;
    counters_.particles_off_map += r.off_map;
    counters_.reinitialisations += r.reinitialised;
    return r;
}

// The ring's probes fell off a small map (or on its no-data): random places inside the map instead
// (lock_monitor.hpp, "Small maps").
void ParticleFilter::score_near_probes(const FilterInput& in, double yaw, double& score_ms) {
    const auto valid = static_cast<std::size_t>(std::count_if(probe_scores_.begin(), probe_scores_.end(), [](const ParticleScore& s) { return s.valid(); }));
    if (valid >= LockMonitor::kMinProbes) return;
    const auto [width, height] = scorer_.map_size();
    const double footprint_px = in.map_px_per_camera_px * in.frame.width;
    near_poses_.clear();
    if (lock_.add_near_probes(estimate_.x, estimate_.y, yaw, footprint_px, width, height, near_poses_) == 0) return;
    probe_scores_.resize(near_poses_.size());
    const auto t0 = std::chrono::steady_clock::now();
    scorer_.score(in.frame, in.map_px_per_camera_px, near_poses_, probe_scores_, nullptr);
    score_ms += std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

void ParticleFilter::check_lock(const StepMotion& m, StepReport& r) {
    r.lock = lock_.assess(estimate_.best_ncc, probe_scores_, estimate_.x, estimate_.y, estimate_.spread_px * config_.metres_per_pixel);
    counters_.weak_contrast_steps += r.lock.weak;
    counters_.odometry_inconsistent_steps += r.lock.inconsistent;
    if (!r.lock.lost) return;
    // Widen the search: a share of the particles re-scattered around the dead-reckoned position;
    // the rest keep the current hypothesis, which wins again at once if it was right. Re-scattered
    // ones get the kept particles' mean weight, so the next resampling draws them as often.
    ++counters_.lock_lost_events;
    const std::size_t n = particles_.size();
    const auto moved = static_cast<std::size_t>(std::lround(config_.lock.widen_fraction * static_cast<double>(n)));
    if (moved == 0 || !(r.lock.widen_radius_m > 0)) return;
    const std::size_t keep = n - moved;
    double kept_weight = 0;
    for (std::size_t i = 0; i < keep; ++i) kept_weight += particles_[i].weight;
    const double w = keep > 0 && kept_weight > 0 ? kept_weight / static_cast<double>(keep) : 1.0;
    if (yaw_state_)  // the position is in doubt, the yaw much less: around the estimate's (it is averaged over all particles)
        scatter_yaw_state(lock_.dead_reckoning_x(), lock_.dead_reckoning_y(), estimate_.yaw, estimate_.yaw_sd, r.lock.widen_radius_m, moved, keep);
    else
        scatter(lock_.dead_reckoning_x(), lock_.dead_reckoning_y(), m.heading_rad, m.have_heading, r.lock.widen_radius_m, moved, keep);
    for (std::size_t i = keep; i < n; ++i) particles_[i].weight = w;
    scores_.clear();  // no longer one score per particle
}

}  // namespace trn::filter
