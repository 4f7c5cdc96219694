#include "makeway/verification/param_tables.hpp"

namespace makeway::verification {

const ParamTable<VerifyParams>& verify_table() {
    using V = VerifyParams;
    static const ParamTable<V> table = [] {
        ParamTable<V> t;
        t.add("box_margin_m", &V::box_margin_m, below(0.0, 2.0),
              "the box grown by this on every side cuts the segment")
            .add("max_size_mismatch", &V::max_size_mismatch, above(0.0, 10.0),
                 "|log(model / detected size)| per dimension for a model to be tried")
            .add("max_models", &V::max_models, closed(1, 1000),
                 "at most this many models (closest in size) are tried")
            .add("refined_candidates", &V::refined_candidates, closed(1, 1000),
                 "best-ranked candidates aligned fully; the lowest residual wins")
            .add("reseed_tolerance_m", &V::reseed_tolerance_m, below(0.0, 1.0),
                 "> 0: a tracked object verified lately gets one ICP from its last fit, kept when "
                 "its residual ends within this of "
                 "that fit's (0: always the full search; 0.005 is faster but lost 7 of 200 bench "
                 "runs) ...")
            .add("reseed_radius_m", &V::reseed_radius_m, closed(0.0, 5.0),
                 "... for a detection this close to the fit ...")
            .add("reseed_max_age_s", &V::reseed_max_age_s, closed(0.0, 3600.0),
                 "... of at most this age")
            .add("min_yaw_margin", &V::min_yaw_margin, closed(0.0, 10.0),
                 "rejected when another yaw's residual is within this fraction of the winner's (0: "
                 "off)")
            .add("e_min_m", &V::e_min_m, closed(0.0, 1.0), "residual at or below which p_exist = 1")
            .add("e_max_m", &V::e_max_m, above(0.0, 1.0),
                 "residual above which a detection is rejected ...")
            .add("approx_e_max_m", &V::approx_e_max_m, below(0.0, 1.0),
                 "... unless at most this: an approximate fit places the box, the network's score "
                 "stays (0: off)")
            .add("keep_unfitted", &V::keep_unfitted,
                 "a detection no CAD model fits keeps the network's box and score (false: dropped)")
            .add("shape_e_max_m", &V::shape_e_max_m, open(0.0, 1.0),
                 "the same for a learned shape prior's completed mesh (--shape-model)")
            .add("min_points", &V::min_points, closed(0.0, 1e9),
                 "fewer segment points: rejected without fitting")
            .add("num_threads", &V::num_threads, closed(1, 256),
                 "detections verified side by side on this many threads (1: in turn)")
            .require([](const V& v) { return v.e_min_m < v.e_max_m; },
                     "need 0 <= e_min_m < e_max_m")
            .require([](const V& v) { return v.shape_e_max_m > v.e_min_m; },
                     "need e_min_m < shape_e_max_m < 1")
            .require(
                [](const V& v) { return v.approx_e_max_m == 0.0 || v.approx_e_max_m > v.e_max_m; },
                "need approx_e_max_m 0 (off) or e_max_m < approx_e_max_m < 1");
        return t;
    }();
    return table;
}

const ParamTable<BackYawParams>& back_yaw_table() {
    using B = BackYawParams;
    static const ParamTable<B> table = [] {
        ParamTable<B> t;
        t.add("enabled", &B::enabled,
              "without CAD models: chairs turned to their back rest's yaw (false: the network's)")
            .add("top_share", &B::top_share, closed(0.01, 1.0),
                 "the back: segment points in this top share of the box's height above the floor")
            .add("margin_m", &B::margin_m, closed(0.0, 1.0),
                 "the box grown by this on every side cuts the segment")
            .add("min_points", &B::min_points, closed(3.0, 1e9),
                 "fewer back points: the network's yaw stays")
            .add("min_elongation", &B::min_elongation, closed(1.0, 1e6),
                 "variance along the back's axis over across it, at least")
            .add("max_turn_rad", &B::max_turn_rad, closed(0.0, 1.5707963267948966),
                 "a larger turn is not trusted: the network's yaw stays");
        return t;
    }();
    return table;
}

}  // namespace makeway::verification
