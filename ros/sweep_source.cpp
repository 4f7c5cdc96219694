#include "ros/sweep_source.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "io/error.hpp"
#include "io/pose_io.hpp"

namespace makeway::rosio {
namespace fs = std::filesystem;
namespace {

// The base's planar poses from a TUM file: wheel odometry holds the base; external poses hold the
// sensor (as `makeway odometry` and `simulate`'s poses_gt.txt write them).
std::vector<StampedPose2> read_base_poses(const std::string& path, bool sensor_poses,
                                          const Isometry3& T_base_sensor) {
    std::vector<StampedPose2> out;
    for (const io::StampedPose& p : io::read_tum(path)) {
        out.push_back(
            {p.stamp_s, project_to_plane(sensor_poses ? p.T_world_sensor * T_base_sensor.inverse()
                                                      : p.T_world_sensor)});
    }
    return out;
}

double sweep_duration(const PointCloud& points) {
    float last = 0.0f;
    for (float t : points.time_s) last = std::max(last, t);
    return last;
}

// A spinning LiDAR's sweep lasts until the next one starts; the last sweep lasts as long as the
// one before it; without stamps between sweeps, until its last point, else one period at `rate`.
double choose_duration(std::optional<double> gap_to_next, double previous, double measured,
                       double rate_hz) {
    if (gap_to_next && *gap_to_next > 0.0 && *gap_to_next <= 1.0) return *gap_to_next;
    if (previous > 0.0) return previous;
    if (measured > 1e-4) return measured;
    return 1.0 / rate_hz;
}

class FolderSource : public SweepSource {
  public:
    explicit FolderSource(const SourceOptions& o) : o_(o) {
        files_ = io::sweep_files(o.clouds);
        const std::string& pose_file = !o.poses.empty() ? o.poses : o.odometry;
        if (!pose_file.empty()) {
            poses_ = read_base_poses(pose_file, !o.poses.empty(), o.T_base_sensor);
            if (poses_.size() < files_.size()) {
                throw io::FileError(pose_file, "holds " + std::to_string(poses_.size()) +
                                                   " poses for " + std::to_string(files_.size()) +
                                                   " sweeps (line k is sweep k's start)");
            }
        }
    }
    std::size_t size() const override { return files_.size(); }
    std::optional<Pose2> first_pose() const override {
        return poses_.empty() ? std::nullopt : std::optional<Pose2>(poses_.front().pose);
    }
    std::string describe() const override {
        return std::to_string(files_.size()) + " sweeps in " + o_.clouds +
               (!o_.poses.empty()      ? ", external poses " + o_.poses
                : !o_.odometry.empty() ? ", wheel odometry " + o_.odometry
                                       : ", no odometry");
    }
    std::optional<SourceSweep> next() override {
        if (k_ >= files_.size()) return std::nullopt;
        const std::size_t k = k_++;
        SourceSweep s;
        s.file = files_[k].string();
        s.points = io::read_point_cloud(files_[k], {.non_finite = o_.non_finite}).cloud;
        s.timed = s.points.time_s.size() == s.points.size() && !s.points.empty();
        if (s.timed) {
            // The bag path's rules (from_point_cloud2): finite times within one sweep's span.
            if (std::any_of(s.points.time_s.begin(), s.points.time_s.end(),
                            [](float t) { return !std::isfinite(t); })) {
                throw io::FileError(s.file, "the per-point time holds a non-finite value");
            }
            const auto [lo, hi] =
                std::minmax_element(s.points.time_s.begin(), s.points.time_s.end());
            if (const std::string p = sweep_span_problem(*hi - *lo); !p.empty())
                throw io::FileError(s.file, "the per-point times span " + p);
        }
        const double measured = s.timed ? sweep_duration(s.points) : 0.0;
        if (poses_.empty()) {
            s.stamp_s = static_cast<double>(k) / o_.rate_hz;
            s.duration_s = measured > 1e-4 ? measured : 1.0 / o_.rate_hz;
            return s;
        }
        s.stamp_s = poses_[k].stamp_s;
        const std::optional<double> gap =
            k + 1 < poses_.size() ? std::optional<double>(poses_[k + 1].stamp_s - s.stamp_s)
                                  : std::nullopt;
        s.duration_s = previous_duration_ =
            choose_duration(gap, previous_duration_, measured, o_.rate_hz);
        s.pose_start = poses_[k].pose;
        // The end: the next line (an extra last line gives the last sweep's end), else the last
        // increment again.
        s.pose_end = k + 1 < poses_.size() ? poses_[k + 1].pose
                     : k > 0 ? compose(poses_[k].pose, between(poses_[k - 1].pose, poses_[k].pose))
                             : poses_[k].pose;
        return s;
    }

  private:
    SourceOptions o_;
    std::vector<fs::path> files_;
    std::vector<StampedPose2> poses_;
    std::size_t k_ = 0;
    double previous_duration_ = 0.0;
};

class BagSource : public SweepSource {
  public:
    explicit BagSource(const SourceOptions& o)
        : o_(o), reader_(o.bag, o.topics, false, o.skip_bad_messages) {
        if (!o.poses.empty()) {
            poses_ = read_base_poses(o.poses, true, o.T_base_sensor);
            pose_source_ = "the poses span";
        } else {
            poses_ = reader_.odometry();
            pose_source_ = "the odometry on " + o.topics.odometry + " spans";
        }
        if (reader_.sweeps() == 0) throw io::FileError(o.bag, "no messages on " + o.topics.cloud);
    }
    std::size_t size() const override { return reader_.sweeps(); }
    std::optional<Pose2> first_pose() const override {
        return poses_.empty() ? std::nullopt : std::optional<Pose2>(poses_.front().pose);
    }
    std::string describe() const override {
        return std::to_string(reader_.sweeps()) + " sweeps on " + o_.topics.cloud + " in " +
               o_.bag +
               (poses_.empty()      ? ", no odometry on " + o_.topics.odometry
                : !o_.poses.empty() ? ", external poses " + o_.poses
                                    : ", wheel odometry on " + o_.topics.odometry);
    }
    std::size_t skipped() const override { return reader_.skipped() + out_of_order_; }
    std::optional<SourceSweep> next() override {
        std::optional<CloudSweep> c = pending_ ? std::move(pending_) : following();
        pending_.reset();
        if (!c) return std::nullopt;
        last_stamp_s_ = c->stamp_s;
        pending_ = following();  // one sweep ahead: this one lasts until that one starts
        const std::size_t k = c->index;
        SourceSweep s;
        s.file = o_.bag;
        s.item = o_.topics.cloud + " message " + std::to_string(k);
        s.points = std::move(c->points);
        const std::size_t bad = s.points.count_non_finite();
        if (bad > 0 && o_.non_finite == io::NonFinitePolicy::kReject) {
            throw io::FileError(
                o_.bag,
                o_.topics.cloud + " message " + std::to_string(k) + ": " + std::to_string(bad) +
                    " points have NaN or infinite coordinates (--non-finite drop to skip them)");
        }
        if (bad > 0 && o_.non_finite == io::NonFinitePolicy::kDrop)
            s.points = remove_non_finite(s.points);
        s.timed = c->timed;
        s.stamp_s = c->stamp_s;
        const std::optional<double> gap =
            pending_ ? std::optional<double>(pending_->stamp_s - s.stamp_s) : std::nullopt;
        s.duration_s = previous_duration_ =
            choose_duration(gap, previous_duration_, c->timed ? c->duration_s : 0.0, o_.rate_hz);
        if (!poses_.empty()) {
            s.pose_start = interpolate_at(poses_, s.stamp_s);
            s.pose_end = interpolate_at(poses_, s.stamp_s + s.duration_s);
            if (!s.pose_start || !s.pose_end) {
                throw io::FileError(o_.poses.empty() ? o_.bag : o_.poses,
                                    pose_source_ + " " + seconds_text(poses_.front().stamp_s) +
                                        "-" + seconds_text(poses_.back().stamp_s) + " s; sweep " +
                                        std::to_string(k) + " (" + seconds_text(s.stamp_s) + "-" +
                                        seconds_text(s.stamp_s + s.duration_s) +
                                        " s) lies outside");
            }
        }
        return s;
    }

  private:
    // The next sweep whose stamp follows the last one taken (sweeps overlap otherwise: a driver
    // stamping every sweep alike, a clock that jumped back).
    std::optional<CloudSweep> following() {
        const double after = last_stamp_s_;
        while (std::optional<CloudSweep> c = reader_.next()) {
            if (c->stamp_s > after) return c;
            const std::string what = o_.topics.cloud + " message " + std::to_string(c->index) +
                                     ": its sweep starts at " + seconds_text(c->stamp_s) +
                                     " s, not after the previous sweep's " + seconds_text(after) +
                                     " s";
            if (!o_.skip_bad_messages)
                throw io::FileError(o_.bag, what + " (--skip-bad-messages to skip such sweeps)");
            if (out_of_order_++ == 0)
                io::print_warning(o_.bag + ": " + what +
                                  "; skipped (more are counted in the summary)");
        }
        return std::nullopt;
    }

    SourceOptions o_;
    BagReader reader_;
    double last_stamp_s_ = -std::numeric_limits<double>::infinity();
    std::size_t out_of_order_ = 0;
    std::vector<StampedPose2> poses_;
    std::string pose_source_;
    double previous_duration_ = 0.0;
    std::optional<CloudSweep> pending_;
};

}  // namespace

std::optional<Pose2> interpolate_at(const std::vector<StampedPose2>& poses, double t) {
    constexpr double kSlack_s = 1e-3;
    if (poses.empty() || t < poses.front().stamp_s - kSlack_s ||
        t > poses.back().stamp_s + kSlack_s)
        return std::nullopt;
    const auto it = std::lower_bound(poses.begin(), poses.end(), t,
                                     [](const StampedPose2& p, double v) { return p.stamp_s < v; });
    if (it == poses.begin()) return poses.front().pose;
    if (it == poses.end()) return poses.back().pose;
    const StampedPose2& a = *(it - 1);
    const StampedPose2& b = *it;
    const double span = b.stamp_s - a.stamp_s;
    const double s = span > 0.0 ? (t - a.stamp_s) / span : 1.0;
    return interpolate(a.pose, b.pose, std::clamp(s, 0.0, 1.0));
}

std::unique_ptr<SweepSource> open_sweep_source(const SourceOptions& options) {
    if (!options.bag.empty()) return std::make_unique<BagSource>(options);
    return std::make_unique<FolderSource>(options);
}

}  // namespace makeway::rosio
