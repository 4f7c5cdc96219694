#pragma once
// Points on the surface of oriented boxes: a ground-truth-labelled cloud for tests, benchmarks and
// the demo before the LiDAR simulator exists to produce real sweeps.
#include <string>
#include <vector>

#include "makeway/common/oriented_box.hpp"
#include "makeway/common/point_cloud.hpp"
#include "makeway/common/random.hpp"
#include "makeway/common/semantic_label.hpp"

namespace makeway {

struct LabelledBox {
    OrientedBox box;
    SemanticLabel label = SemanticLabel::kClutter;
    std::uint32_t instance = 0;
};

struct BoxSamplingParams {
    double points_per_m2 = 400.0;  ///< surface density
    double noise_m = 0.01;         ///< isotropic Gaussian noise on every coordinate
    bool skip_bottom = true;       ///< a LiDAR never sees the underside of an object on the floor
};

/// Every channel filled: intensity from the face, ring 0, time 0, label and instance from the box.
PointCloud sample_box_surfaces(const std::vector<LabelledBox>& boxes,
                               const BoxSamplingParams& params, Rng& rng);

}  // namespace makeway

namespace makeway {

/// A random layout of chair- and table-sized boxes standing on the floor of a square room, none
/// overlapping another. A stand-in scene for tests and the demo until the simulator's scenes exist.
struct ObjectLayoutParams {
    std::uint64_t seed = 0;
    int num_objects = 12;       ///< chairs and tables together
    double room_size_m = 8.0;   ///< side of the square room, centred on the origin
    double table_share = 0.3;   ///< fraction of objects that are tables, [0, 1]

    /// Every problem, e.g. "num_objects must be in [1, 1000] (got 0)"; empty when valid.
    std::vector<std::string> validate() const;
};

/// Fails soft: returns fewer objects when the room is too full to place them all.
std::vector<LabelledBox> random_object_layout(const ObjectLayoutParams& params);

/// Every problem of a sampling parameter set; empty when valid.
std::vector<std::string> validate(const BoxSamplingParams& params);

}  // namespace makeway
