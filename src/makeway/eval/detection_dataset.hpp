#pragma once
// Labelled keyframes for the detector, from simulated drives: the online system's own keyframes
// (pipeline/front_end: wheel odometry from the start pose, de-skewed sweeps, ground plane, ground
// and ceiling removed), and every chair and table seen by enough points labelled with its true box
// in the keyframe's sensor frame.
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "makeway/common/labelled_keyframe.hpp"
#include "makeway/pipeline/system_params.hpp"
#include "makeway/sim/clutter.hpp"
#include "makeway/sim/lidar.hpp"
#include "makeway/sim/robot.hpp"
#include "makeway/sim/scene.hpp"

namespace makeway::eval {

/// A user's own piece of furniture (io::read_furniture_folder), in makeway's object frame.
struct UserFurniture {
    std::string name;
    ObjectClass cls = ObjectClass::kChair;
    std::shared_ptr<const TriangleMesh> mesh_object;
};

struct DatasetParams {
    int scenes = 10;
    std::uint64_t seed = 0;
    int keyframe_every = 10;  ///< sweeps between keyframes along the drive
    int max_keyframes_per_scene = 30;
    std::size_t min_points = 10;  ///< objects seen by fewer keyframe points go to `unseen`
    double range_m = 8.0;         ///< objects whose centre is farther (|x| or |y|) are not labelled
    /// Styles replaced by another style of their class (training without them), or, with
    /// `only_styles`, the styles every object is given (evaluation on held-out styles).
    std::vector<std::string> exclude_styles;
    std::vector<std::string> only_styles;
    /// The wider world: every object takes a random style of its class among all the simulator's
    /// (sim::styles_of; twelve chairs, nine tables) that are not excluded, not only the seven
    /// generated scenes draw from.
    bool all_styles = false;
    /// A user's own furniture: each object of a class takes one of that class's meshes with
    /// probability furniture_share (seeded by the scene), so the detector learns them.
    std::vector<UserFurniture> furniture;
    double furniture_share = 0.5;
    /// Non-furniture of furniture size (sim/clutter.hpp) added to every scene, unlabelled: the
    /// detector's negatives. None by default, so older datasets are reproduced.
    sim::ClutterParams clutter{.count = 0};
    /// The scene's furniture removed and only clutter left (the false-positive measurement).
    bool clutter_only = false;
    /// The sensor every drive is recorded with, unless drawn by sensor_variety: its beams and its
    /// height above the floor (the simulated Jackal's VLP-32C by default).
    sim::BeamPattern beam_pattern = sim::BeamPattern::kVlp32c;
    double sensor_height_m = 0.45;
    /// Sensors a user may have (issue 32): a share of the scenes (drawn per scene, seeded by it)
    /// recorded with one of `patterns` at a height drawn uniformly in [height_min_m, height_max_m].
    struct SensorVariety {
        double share = 0.0;
        std::vector<sim::BeamPattern> patterns{sim::BeamPattern::kVlp16, sim::BeamPattern::kVlp32c,
                                               sim::BeamPattern::kOs1_64,
                                               sim::BeamPattern::kOs1_128};
        double height_min_m = 0.3, height_max_m = 1.1;
    } sensor_variety;
    /// The front end's parameters (keyframe.every is overridden by keyframe_every).
    pipeline::SystemParams system;
    sim::OdometryNoiseParams odometry;  ///< the wheel odometry the front end runs on
};

/// A user's furniture split by model for training and measuring: within each class, sorted by
/// name, every `holdout_every`-th model (the 3rd, 6th, ... for 3) is held out; 0 holds none out.
struct FurnitureSplit {
    std::vector<UserFurniture> train, held_out;
};
FurnitureSplit split_furniture(std::vector<UserFurniture> furniture, int holdout_every);

/// The styles of `params` on a scene: excluded styles become the first allowed scene style of their
/// class; with `only_styles`, every object takes one of those of its class (at random among
/// several, seeded by the scene); with `all_styles`, a random style of its class that is not
/// excluded. Throws std::invalid_argument on unknown style names.
void restyle_scene(sim::Scene& scene, const DatasetParams& params);

/// Keyframes in time order, `sequence` = the scene's index. With `scenes`, the (restyled) scenes
/// are appended to it, one per index, for CAD libraries of the furniture actually there.
/// Throws std::invalid_argument on unknown style names.
std::vector<LabelledKeyframe> generate_detection_dataset(
    const DatasetParams& params, const std::function<void(int, int)>& progress = {},
    std::vector<sim::Scene>* scenes = nullptr);

}  // namespace makeway::eval
