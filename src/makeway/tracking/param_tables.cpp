#include "makeway/tracking/param_tables.hpp"

namespace makeway::tracking {

const ParamTable<KalmanParams>& kalman_table() {
    using K = KalmanParams;
    static const ParamTable<K> table = [] {
        ParamTable<K> t;
        t.add("accel_sigma_mps2", &K::accel_sigma_mps2, open(0.0, 100.0),
              "the box filter (centre, yaw, size, velocity): white-noise acceleration")
            .add("position_sigma_mps", &K::position_sigma_mps, below(0.0, 100.0),
                 "position random walk [m/sqrt(s)] (traffic boxes jump; furniture's do not)")
            .add("yaw_rate_sigma_radps", &K::yaw_rate_sigma_radps, open(0.0, 100.0),
                 "yaw random walk")
            .add("size_sigma_mps", &K::size_sigma_mps, open(0.0, 100.0), "size random walk")
            .add("meas_position_sigma_m", &K::meas_position_sigma_m, open(0.0, 100.0),
                 "a detection's centre ...")
            .add("meas_yaw_sigma_rad", &K::meas_yaw_sigma_rad, open(0.0, 100.0), "... yaw ...")
            .add("meas_size_sigma_m", &K::meas_size_sigma_m, open(0.0, 100.0), "... and size noise")
            .add("initial_velocity_sigma_mps", &K::initial_velocity_sigma_mps, open(0.0, 100.0),
                 "a new object's velocity: 0 +- this")
            .add("heading_votes_to_turn", &K::heading_votes_to_turn, closed(1, 1000),
                 "net detections for another quarter turn that turn a track");
        return t;
    }();
    return table;
}

const ParamTable<MotionPrior>& motion_prior_table() {
    using M = MotionPrior;
    static const ParamTable<M> table = [] {
        ParamTable<M> t;
        t.add("velocity_decay_s", &M::velocity_decay_s, closed(0.0, 3600.0).or_infinity(),
              "an unobserved object's velocity decays with this time constant (.inf: never)")
            .add("max_speed_mps", &M::max_speed_mps, above(0.0, 100.0),
                 "horizontal speed estimates are clamped to this")
            .add("planar", &M::planar, "no vertical motion")
            .add("min_displacement_m", &M::min_displacement_m, closed(0.0, 100.0),
                 "held at rest until its detections moved this far ...")
            .add("motion_window_s", &M::motion_window_s, above(0.0, 3600.0),
                 "... within this window (3+ boxes over half of it)")
            .add("rest_yaw_rate_sigma_radps", &M::rest_yaw_rate_sigma_radps, open(0.0, 100.0),
                 "yaw random walk while at rest (a standing object's views averaged; with CAD "
                 "models: yaw_rate_sigma_radps)")
            .add("turn_release_rad", &M::turn_release_rad, above(0.0, 3.2),
                 "at rest: two detections in a row turned beyond this, the same way, free its yaw");
        return t;
    }();
    return table;
}

const ParamTable<TrackerParams>& tracker_table() {
    using T = TrackerParams;
    static const ParamTable<T> table = [] {
        ParamTable<T> t;
        t.add_choice(
             "classes",
             [](T& p) {
                 ParamChoice c;
                 c.list = true;
                 for (ObjectClass cls : kAllObjectClasses) c.names.emplace_back(to_string(cls));
                 c.get = [&p] {
                     std::vector<std::string> on;
                     for (ObjectClass cls : kAllObjectClasses) {
                         if (p.tracked_classes[static_cast<std::size_t>(cls)])
                             on.emplace_back(to_string(cls));
                     }
                     return on;
                 };
                 c.set = [&p](const std::vector<std::string>& names) {
                     p.tracked_classes.fill(false);
                     for (const std::string& n : names)
                         p.tracked_classes[static_cast<std::size_t>(*parse_object_class(n))] = true;
                 };
                 return c;
             },
             "detections of other classes are not used")
            .add("min_score", &T::min_score, closed(0.0, 1.0),
                 "detections scoring below this (after the transform) are not used")
            .choice("score_transform", &T::score_transform,
                    {{"none", ScoreTransform::kNone}, {"sigmoid", ScoreTransform::kSigmoid}},
                    "none (probabilities) or sigmoid (raw logits)")
            .add("min_giou", &T::min_giou, closed(-1.0, 1.0),
                 "associated pairs need at least this 3D GIoU")
            .add("sensor_range_m", &T::sensor_range_m, above(0.0, 1000.0),
                 "objects farther from the sensor are neither matched nor penalised")
            .choice("out_of_range", &T::out_of_range,
                    {{"freeze", OutOfRange::kFreeze}, {"drop", OutOfRange::kDrop}},
                    "freeze (remember where last seen) or drop")
            .add("max_unobserved_s", &T::max_unobserved_s, above(0.0, 1e9).or_infinity(),
                 "any object unseen this long leaves the map (.inf: never)")
            .add("max_floor_gap_m", &T::max_floor_gap_m, above(0.0, 100.0).or_infinity(),
                 "detections whose bottom is farther from the floor plane are not used (.inf: no "
                 "floor prior)")
            .add("merge_iou", &T::merge_iou, above(0.0, 1.0),
                 "two confirmed objects of a class overlapping more (BEV IoU) are one")
            .add("motion_gate_sigma", &T::motion_gate_sigma, above(0.0, 100.0).or_infinity(),
                 "detections farther than max speed x dt + this many sigmas are not associated "
                 "(.inf: no gate)");
        for (ObjectClass cls : kAllObjectClasses) {
            const auto i = static_cast<std::size_t>(cls);
            t.include(
                std::string(to_string(cls)) + "_",
                [i](T& p) -> MotionPrior& { return p.motion[i]; }, motion_prior_table());
        }
        t.add("association_gate_m", &T::association_gate_m, closed(0.0, 100.0), "")
            .add("max_centre_distance_m", &T::max_centre_distance_m, closed(0.0, 100.0),
                 "> 0: pairs scored by centre distance (at most this) instead of min_giou")
            .include(
                "", [](T& p) -> KalmanParams& { return p.kalman; }, kalman_table())
            .add("min_hits", &T::min_hits, closed(1, 1000),
                 "detections before an object enters the map's output")
            .add("max_misses", &T::max_misses, closed(1, 100000),
                 "consecutive unexplained misses that remove an object")
            .add("min_existence", &T::min_existence, closed(0.0, 1.0),
                 "fused existence below this removes an object ...")
            .add("existence_grace_frames", &T::existence_grace_frames, closed(1, 1000),
                 "... once it has been judged on this many frames")
            .add("same_view_m", &T::same_view_m, closed(0.0, 100.0),
                 "frames seeing an object from within this of one place ...")
            .add("same_view_period_s", &T::same_view_period_s, above(0.0, 3600.0),
                 "... and this long are one view: a still robot's repeated frames are one vote (0 "
                 "m: every frame)");
        return t;
    }();
    return table;
}

}  // namespace makeway::tracking
