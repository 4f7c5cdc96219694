#pragma once
// The online system without control, as `makeway run` and the ROS node run it: every sweep
// through the Pipeline (pose, keyframes, perception, object map), then into the object-aware
// costmap. Navigation adds the Navigator on top of the same two.
#include <functional>
#include <memory>

#include "makeway/common/costmap.hpp"
#include "makeway/pipeline/object_costmap.hpp"
#include "makeway/pipeline/pipeline.hpp"

namespace makeway::pipeline {

struct MappingStep {
    SweepResult sweep;
    double costmap_ms = 0.0;  ///< obstacle and affordance update of this sweep
    /// The per-sweep work: the pose (odometry and de-skewing) and the costmap update [ms].
    double per_sweep_ms() const { return sweep.timing.deskew_ms + costmap_ms; }
};

/// Without a prebuilt map: a free square grid of `side_m` centred on the start, to map into.
Costmap free_area(const Pose2& centre, double side_m, double resolution_m = 0.05);

class MappingSystem {
public:
    /// `static_map`: the prebuilt map (or a free grid of the area to map); with
    /// `restrict_objects`, objects stand only within its known area. `detector` and `library` as the
    /// Pipeline's. Throws std::invalid_argument listing every problem of `params`.
    MappingSystem(const SystemParams& params, const Pose2& start_pose, const Costmap& static_map, bool restrict_objects,
                  const perception::ObjectDetector* detector, const verification::CadLibrary* library);

    MappingStep process(const Sweep& sweep);
    /// See Pipeline::set_shape_prior.
    void set_shape_prior(const verification::ShapePrior* prior) { pipeline_.set_shape_prior(prior); }

    const Costmap& costmap() const { return costmap_.master(); }
    const std::vector<ObjectEstimate>& objects() const { return objects_; }
    const SystemParams& params() const { return pipeline_.params(); }

private:
    Costmap static_map_;
    Pipeline pipeline_;
    ObjectCostmap costmap_;
    std::vector<ObjectEstimate> objects_;
};

}  // namespace makeway::pipeline
