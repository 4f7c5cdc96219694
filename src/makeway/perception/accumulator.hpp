#pragma once
// Keyframe accumulation: a sliding window of the last sweeps (5 by default, as in the paper)
// transformed into the newest sweep's sensor frame, each point de-skewed with its own timestamp
// when the sweep's start and end poses are known.
#include <deque>
#include <string>
#include <utility>
#include <vector>

#include "makeway/common/point_cloud.hpp"
#include "makeway/common/transforms.hpp"

namespace makeway::perception {

/// One sweep with its poses: points are in the sensor frame of their own firing time.
struct StampedSweep {
    PointCloud points_sensor;
    double stamp_s = 0.0;  ///< sweep start
    double duration_s = 0.1;
    Isometry3 T_world_sensor_start = Isometry3::Identity();
    Isometry3 T_world_sensor_end = Isometry3::Identity();  ///< equal to start: no de-skewing
};

struct AccumulatorParams {
    int window = 5;
    bool deskew = true;
    std::vector<std::string> validate() const;
};

/// The sweep's points in a target frame (T_target_world), each moved with the sensor pose at its
/// own time (linear in translation, slerp in rotation between the start and end poses) when
/// `deskew` and the sweep has per-point time and moved; otherwise all with the start pose. Channels
/// kept.
/// Taken by value: a caller done with its sweep moves it in, and its points are transformed where
/// they are (a copy per sweep was a tenth of a navigation run's page faults under ASan).
PointCloud deskew_sweep(StampedSweep sweep, const Isometry3& T_target_world, bool deskew = true);
/// deskew_sweep into the world frame.
inline PointCloud deskew_to_world(StampedSweep sweep, bool deskew = true) {
    return deskew_sweep(std::move(sweep), Isometry3::Identity(), deskew);
}

class KeyframeAccumulator {
  public:
    explicit KeyframeAccumulator(const AccumulatorParams& params = {}) : params_(params) {}
    /// De-skews the sweep into the world frame once, on arrival: a keyframe is then one rigid
    /// transform per point, not one interpolated pose per point for every keyframe it is part of.
    void add(StampedSweep sweep);
    bool full() const { return static_cast<int>(sweeps_.size()) >= params_.window; }
    std::size_t size() const { return sweeps_.size(); }
    /// The newest sweep de-skewed into the world frame (empty before the first add).
    const PointCloud& newest_world() const;

    /// Every point of the window in the newest sweep's start frame (T_world_keyframe), channels
    /// kept; `time_s` becomes time relative to the keyframe stamp. Empty when no sweep was added.
    PointCloud keyframe(Isometry3* T_world_keyframe = nullptr) const;

  private:
    struct WorldSweep {
        PointCloud points_world;
        double stamp_s = 0.0;
        Isometry3 T_world_sensor_start = Isometry3::Identity();
    };
    AccumulatorParams params_;
    std::deque<WorldSweep> sweeps_;
};

}  // namespace makeway::perception
