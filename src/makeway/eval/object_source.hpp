#pragma once
// Where the truth-fed navigation methods get their objects from: none (the classic planners) or the
// simulator's ground truth (gt-perc). The full system (ours) runs the online pipeline instead.
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "makeway/common/object_estimate.hpp"
#include "makeway/common/point_cloud.hpp"
#include "makeway/common/polygon2d.hpp"
#include "makeway/common/robot_body.hpp"
#include "makeway/common/transforms.hpp"
#include "makeway/sim/scene_dynamics.hpp"

namespace makeway::eval {

struct ObjectSourceInput {
    double t_s = 0.0;
    Isometry3 T_world_sensor = Isometry3::Identity();
    const PointCloud* points_sensor = nullptr;  ///< the latest sweep
};

class ObjectSource {
  public:
    virtual ~ObjectSource() = default;
    virtual std::string name() const = 0;
    virtual std::vector<ObjectEstimate> objects(const ObjectSourceInput& input) = 0;
    /// Whether objects() reads the sweep's intensity (if not, the simulator leaves it out).
    virtual bool reads_intensity() const { return true; }
};

/// No semantics: the classic costmap planners.
class NoObjects : public ObjectSource {
  public:
    std::string name() const override { return "none"; }
    std::vector<ObjectEstimate> objects(const ObjectSourceInput&) override { return {}; }
    bool reads_intensity() const override { return false; }
};

/// Perfect perception: every chair and table of the scene where it is at time t. Given the body's
/// height band, each also carries the outlines of its model's parts the body can hit
/// (ObjectEstimate::parts_world: an office chair's star base, a table's legs), as the full system
/// has them for what it verified against a CAD model: without them a truth-fed method would be
/// blinder than `ours` where the LiDAR cannot see the floor (the collision monitor's blind ring).
class GroundTruthObjects : public ObjectSource {
  public:
    GroundTruthObjects(const sim::Scene& scene, std::vector<sim::ObjectModel> models,
                       const std::optional<BodyHeights>& parts_band = std::nullopt);
    std::string name() const override { return "ground_truth"; }
    std::vector<ObjectEstimate> objects(const ObjectSourceInput& input) override;
    bool reads_intensity() const override { return false; }

  private:
    const sim::Scene& scene_;
    std::vector<sim::ObjectModel> models_;
    std::vector<std::vector<Polygon2>> parts_object_;  ///< per model (empty: no band given)
};

/// The simulator's ground truth at t_s as object estimates.
std::vector<ObjectEstimate> ground_truth_objects(const sim::Scene& scene,
                                                 const std::vector<sim::ObjectModel>& models,
                                                 double t_s);

}  // namespace makeway::eval
