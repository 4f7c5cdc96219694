#include "makeway/sim/param_tables.hpp"

namespace makeway::sim {

const ParamTable<SceneGenParams>& scene_gen_table() {
    using S = SceneGenParams;
    static const ParamTable<S> table = [] {
        ParamTable<S> t;
        t.add("seed", &S::seed, closed(0.0, 1.8446744073709552e19), "")
            .choice("density", &S::density,
                    {{"sparse", Density::kSparse},
                     {"medium", Density::kMedium},
                     {"dense", Density::kDense}},
                    "sparse | medium | dense (for layout: random)")
            .choice("layout", &S::layout,
                    {{"study_space", Layout::kStudySpace}, {"random", Layout::kRandom}},
                    "study_space (the paper's room: 12 tables, 22 chairs) | random")
            .add("people", &S::people, "walkers and chair pushers");
        return t;
    }();
    return table;
}

const ParamTable<LidarParams>& lidar_table() {
    using L = LidarParams;
    static const ParamTable<L> table = [] {
        ParamTable<L> t;
        t.choice("beam_pattern", &L::beam_pattern, beam_patterns_by_name(),
                 "the beams: Velodyne VLP-16 (16, +-15 deg), VLP-32C (32, -25..+15), Ouster "
                 "OS1-64 and OS1-128 (+-22.5)")
            .add("azimuth_step_deg", &L::azimuth_step_deg, closed(0.01, 10.0), "")
            .add("rate_hz", &L::rate_hz, closed(1.0, 50.0), "turns per second")
            .add("min_range_m", &L::min_range_m, closed(0.0, 1000.0), "")
            .add("max_range_m", &L::max_range_m, above(0.0, 1000.0), "")
            .add("range_noise_m", &L::range_noise_m, closed(0.0, 1.0), "Gaussian sigma")
            .add("dropout", &L::dropout, closed(0.0, 1.0), "probability a return is lost")
            .add("intensity_falloff_m", &L::intensity_falloff_m, above(0.0, 1000.0),
                 "intensity: each surface's reflectivity x |cos incidence|, falling linearly to 20 "
                 "% at this range ...")
            .add("intensity_speckle", &L::intensity_speckle, closed(0.0, 1.0),
                 "... with this relative sigma ...")
            .add("intensity_noise", &L::intensity_noise, closed(0.0, 50.0),
                 "... and this additive sigma (0..255)")
            .add("time_slices", &L::time_slices, closed(1, 3600),
                 "the world moves this often per sweep")
            .add("num_threads", &L::num_threads, closed(1, 256), "ray-casting threads")
            .add("use_packets", &L::use_packets, "Embree 16-ray packets")
            .require([](const L& l) { return l.min_range_m < l.max_range_m; },
                     "min_range_m must be in [0, max_range_m)");
        return t;
    }();
    return table;
}

const ParamTable<OdometryNoiseParams>& wheel_noise_table() {
    using O = OdometryNoiseParams;
    static const ParamTable<O> table = [] {
        ParamTable<O> t;
        t.add("translation_noise_per_m", &O::translation_noise_per_m, closed(0.0, 1.0),
              "distance error sigma after 1 m [m]")
            .add("heading_noise_per_rad", &O::heading_noise_per_rad, closed(0.0, 1.0),
                 "heading error sigma after turning 1 rad [rad]")
            .add("heading_noise_per_m", &O::heading_noise_per_m, closed(0.0, 1.0),
                 "heading drift sigma after 1 m [rad]");
        return t;
    }();
    return table;
}

}  // namespace makeway::sim
