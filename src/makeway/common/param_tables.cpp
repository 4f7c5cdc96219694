#include "makeway/common/param_tables.hpp"

namespace makeway {

const ParamTable<RobotDescription>& robot_description_table() {
    using R = RobotDescription;
    static const ParamTable<R> table = [] {
        ParamTable<R> t;
        t.add("length_m", &R::length_m, open(0.05, 5.0),
              "footprint along x (a rectangle centred on the base)")
            .add("width_m", &R::width_m, open(0.05, 5.0), "footprint along y")
            .add("body_height_m", &R::body_height_m, open(0.0, 3.0),
                 "collisions are checked below this height")
            .add("ground_clearance_m", &R::ground_clearance_m, below(0.0, 3.0),
                 "parts lower are rolled over; the costmap marks what lies between the two")
            .add("lidar_height_m", &R::lidar_height_m, open(0.0, 3.0),
                 "the sensor over the base's centre (run --extrinsics / the node's ~extrinsics "
                 "override it)")
            .add("max_v_mps", &R::max_v_mps, above(0.0, 5.0), "top speed")
            .add("max_w_radps", &R::max_w_radps, above(0.0, 10.0), "top turn rate")
            .add("max_acc_mps2", &R::max_acc_mps2, above(0.0, 20.0),
                 "linear acceleration and braking limit")
            .add("max_ang_acc_radps2", &R::max_ang_acc_radps2, above(0.0, 50.0),
                 "angular acceleration limit")
            .require([](const R& r) { return r.ground_clearance_m < r.body_height_m; },
                     "ground_clearance_m must be in [0, body_height_m)");
        return t;
    }();
    return table;
}

}  // namespace makeway
