#pragma once
// The robot's body in height: one definition of what it can hit. The simulator's collision check
// counts furniture parts inside this band, the costmap's obstacle layer marks returns inside it,
// and the benchmark's ground truth uses the same numbers, so a part the robot can hit is a part
// the costmap sees. Parts lower than the clearance (door thresholds, cables, the thinnest chair
// runners) are rolled over; a cantilever chair's runner (up to 2.8 cm) or a table's foot plate is
// not. 2 cm is the Jackal's: its 20 cm wheels climb a 2 cm edge; and it is what a LiDAR with 1.5 cm
// range noise can tell from the floor at the grazing angles of its lowest rings (sigma 6 mm in
// height, obstacle_layer.hpp).
namespace makeway {

struct BodyHeights {
    double ground_clearance_m = 0.02;  ///< lower parts are rolled over; higher ones stop the robot
    double top_m = 0.5;  ///< the top of the robot with its sensor: higher parts pass over it
    bool can_hit(double z_m) const { return z_m >= ground_clearance_m && z_m <= top_m; }
};

}  // namespace makeway
