#pragma once
// The full perception chain as the navigation stack's object source (the paper's "ours"): sweeps
// accumulated into keyframes, ground plane by RANSAC at start-up, ground and ceiling removed,
// the neural detector, geometric verification against CAD models, and the tracker's object map.
#include <optional>

#include "makeway/eval/object_source.hpp"
#include "makeway/perception/accumulator.hpp"
#include "makeway/perception/detector.hpp"
#include "makeway/perception/ground.hpp"
#include "makeway/sim/scene.hpp"
#include "makeway/tracking/object_map.hpp"
#include "makeway/verification/verifier.hpp"

namespace makeway::eval {

struct PerceptionSourceParams {
    int keyframe_every = 5;          ///< sweeps between keyframes (10 Hz sweeps: 2 Hz keyframes)
    bool verification = true;
    tracking::TrackerParams tracker;
};

class PerceptionObjects : public ObjectSource {
public:
    /// `library` may be null (no verification). Both must outlive the source.
    PerceptionObjects(const perception::Detector& detector, const verification::CadLibrary* library, const PerceptionSourceParams& params = {});
    std::string name() const override { return "perception"; }
    std::vector<ObjectEstimate> objects(const ObjectSourceInput& input) override;
    std::size_t keyframes() const { return keyframes_; }

private:
    const perception::Detector& detector_;
    const verification::CadLibrary* library_;
    PerceptionSourceParams params_;
    perception::KeyframeAccumulator accumulator_;
    std::optional<perception::GroundPlaneResult> ground_;  ///< fitted once, at start-up
    tracking::ObjectMap map_;
    std::vector<ObjectEstimate> last_;
    std::size_t sweeps_ = 0, keyframes_ = 0;
};

/// The tracker's parameters with misses judged only within what the detector covers.
tracking::TrackerParams tracker_params_for(const perception::Detector& detector, tracking::TrackerParams params);

/// Every furniture style of the simulator at its default dimensions, as a verification library:
/// for furniture whose CAD models are not known.
verification::CadLibrary default_cad_library();
/// The CAD models of the furniture in the scene, one per distinct model (the paper's setting: the
/// robot's owner has the models of the room's chairs and tables).
verification::CadLibrary scene_cad_library(const sim::Scene& scene);

}  // namespace makeway::eval
