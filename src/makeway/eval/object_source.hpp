#pragma once
// Where the truth-fed navigation methods get their objects from: none (the classic planners) or the
// simulator's ground truth (gt-perc). The full system (ours) runs the online pipeline instead.
#include <memory>
#include <string>
#include <vector>

#include "makeway/common/object_estimate.hpp"
#include "makeway/common/point_cloud.hpp"
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

/// Perfect perception: every chair and table of the scene where it is at time t.
class GroundTruthObjects : public ObjectSource {
  public:
    GroundTruthObjects(const sim::Scene& scene, std::vector<sim::ObjectModel> models)
        : scene_(scene), models_(std::move(models)) {}
    std::string name() const override { return "ground_truth"; }
    std::vector<ObjectEstimate> objects(const ObjectSourceInput& input) override;
    bool reads_intensity() const override { return false; }

  private:
    const sim::Scene& scene_;
    std::vector<sim::ObjectModel> models_;
};

/// The simulator's ground truth at t_s as object estimates.
std::vector<ObjectEstimate> ground_truth_objects(const sim::Scene& scene,
                                                 const std::vector<sim::ObjectModel>& models,
                                                 double t_s);

}  // namespace makeway::eval
