#pragma once
// The online system, assembled once. The benchmark's `ours`, `makeway run` and the ROS node all
// build this from the same parameters (io::online_system_params: the configuration with the robot
// applied), so where objects may stand, the robot's limits and the safety layer cannot drift apart:
//
//   sweep + wheel odometry -> Pipeline (pose, keyframes, detection, verification, object map)
//     -> Controller: the Navigator's layered costmap (always: the map is kept while idle),
//        with a route A* + DWA -> the CollisionMonitor on the same de-skewed sweep -> the command.
//
// Without a route the command is zero and the monitor still sees every sweep (its memory of what
// the sensor can no longer see, and which returns are new, stay current for the next goal).
#include <deque>
#include <map>
#include <optional>
#include <unordered_map>
#include <vector>

#include "makeway/common/costmap.hpp"
#include "makeway/common/velocity_command.hpp"
#include "makeway/pipeline/navigator.hpp"
#include "makeway/pipeline/pipeline.hpp"
#include "makeway/planning/collision_monitor.hpp"

namespace makeway::pipeline {

/// A chair's footprint for the collision monitor: its box, swept along its velocity for lead_s
/// (collision_monitor.object_lead_s: the object map lags a pulled chair by up to a keyframe);
/// lead_s 0 or a still chair: the box.
Polygon2 chair_footprint(const ObjectEstimate& o, double lead_s);

/// The chairs the collision monitor gives way to (give_way_horizon_s): those the object map has
/// moving at least min_speed_mps, or whose box moved that fast over window_s. The map holds a chair
/// at rest until its detections moved it 0.3 m (noise must not read as motion in its zones); a
/// chair pulled out 0.4 m is at the robot by then, while its box already steps a few centimetres
/// per keyframe. Each box is carried along the velocity from when it was measured: lag_s before
/// the cycle it changed in (collision_monitor.give_way_lag_s: a keyframe's box is 0.3 s old when
/// it arrives, and it stays until the next keyframe, 0.5 s later; a box that changes every cycle,
/// the truth's, with lag_s 0 is where it is).
class MovingChairs {
  public:
    MovingChairs(double min_speed_mps, double window_s, double lag_s = 0.0);
    /// One control cycle's object map (objects less likely than min_existence left out): the
    /// moving chairs, each its box (carried to t_s) and velocity.
    std::vector<planning::MovingOutline> update(double t_s,
                                                const std::vector<ObjectEstimate>& objects,
                                                double min_existence);

  private:
    double min_speed_mps_, window_s_, lag_s_;
    std::unordered_map<std::uint32_t, std::deque<std::pair<double, Eigen::Vector2d>>>
        centres_;  ///< each chair's box centre per cycle, over window_s
};

/// The navigator, then the collision monitor between it and the motors (every method of the
/// benchmark drives through this; `ours` inside an OnlineSystem).
class Controller {
  public:
    /// Throws std::invalid_argument listing every problem of `params` (monitor included).
    Controller(const Costmap& static_map, const NavigatorParams& params);

    struct Step {
        NavigatorStep nav;              ///< the navigator's step (the costmap was updated)
        planning::MonitorResult guard;  ///< what the monitor did to the command
        VelocityCommand
            command;  ///< what goes to the motors: zero without a route, on arrival, on giving up
        bool navigating = false;  ///< a route was being driven at this step
        double monitor_ms = 0.0;
    };
    /// One control cycle on the latest sweep (`in.points_world` may be null: the monitor's memory
    /// alone).
    Step step(const NavigatorInput& in);
    /// The legs to drive (waypoints, then the goal); empty: idle.
    void set_route(std::vector<Eigen::Vector2d> legs_m);
    void cancel() { set_route({}); }
    bool navigating() const { return navigating_; }
    const Navigator& navigator() const { return navigator_; }

  private:
    Navigator navigator_;
    planning::CollisionMonitor monitor_;
    double min_existence_;  ///< objects this likely lend the monitor their footprints ...
    bool object_map_;       ///< the navigator uses the objects (NavigatorParams::affordance_layer)
    std::unordered_map<std::uint32_t, double>
        moved_at_;  ///< ... when they moved lately: object id -> when last seen moving
    MovingChairs moving_chairs_;
    struct KeptParts {
        std::vector<Polygon2> parts;  ///< ObjectEstimate::parts_world
        double t_s = 0.0;             ///< when the map last held the object
    };
    std::map<std::uint32_t, KeptParts> parts_;  ///< by object id (ordered: the monitor's input is)
    bool navigating_ = false;
};

/// What the prebuilt map holds, which decides where objects may stand.
enum class MapKind {
    kNone,       ///< no map: a free square of free_area_m around the start; objects anywhere
    kWalls,      ///< walls only (the benchmark's): objects in its free space, below lethal
    kFurnished,  ///< a SLAM map of the furnished room (map_server): objects within its known area
};

struct OnlineSystemSetup {
    SystemParams params;  ///< io::online_system_params(config): the robot is applied
    Pose2 start;          ///< the base at the first sweep
    std::optional<Costmap> map;
    MapKind map_kind = MapKind::kNone;  ///< with a map: kWalls or kFurnished
    double free_area_m = 40.0, free_area_resolution_m = 0.05;
    const perception::ObjectDetector* detector =
        nullptr;  ///< may be null (no detection); must outlive the system
    const verification::CadLibrary* library = nullptr;  ///< may be null (no CAD verification)
    const verification::ShapePrior* prior = nullptr;    ///< may be null (no learned shapes)
};

struct OnlineStep {
    SweepResult sweep;
    Controller::Step control;
    double v_mps = 0.0, w_radps = 0.0;  ///< the base's velocity over the sweep (wheel odometry;
                                        ///< else the pose estimate)
    /// The per-sweep work: the pose (odometry and de-skewing), the costmap, planning and the
    /// monitor [ms].
    double per_sweep_ms() const {
        return sweep.timing.deskew_ms + control.nav.update_ms + control.monitor_ms;
    }
};

/// Without a prebuilt map: a free square grid of `side_m` centred on the start, to map into.
Costmap free_area(const Pose2& centre, double side_m, double resolution_m = 0.05);

class OnlineSystem {
  public:
    /// Throws std::invalid_argument listing every problem of the parameters.
    explicit OnlineSystem(const OnlineSystemSetup& setup);

    /// One sweep, top to bottom: perception, the costmap, and (with a route) the guarded command.
    /// The sweep is taken by value: a caller done with it moves it in (no copy of its points).
    OnlineStep process(Sweep sweep);
    /// The control path alone, for a robot that must act before perception ends (the ROS node):
    /// the front end, then the costmap and the guarded command on the object map as it stands; a
    /// keyframe the front end formed is left in `pending` for perceive(), which may run on another
    /// thread (one call at a time) and updates the object map the next drive() uses.
    OnlineStep drive(Sweep sweep, std::optional<PendingKeyframe>* pending);
    KeyframeResult perceive(PendingKeyframe pending, StageTiming& timing) {
        return pipeline_.perceive(std::move(pending), timing);
    }
    void set_route(std::vector<Eigen::Vector2d> legs_m) {
        controller_.set_route(std::move(legs_m));
    }
    void cancel() { controller_.cancel(); }

    const Costmap& costmap() const { return controller_.navigator().costmap(); }
    const Costmap& static_map() const { return static_map_; }
    /// The object map now (a copy: perceive() may be updating it).
    std::vector<ObjectEstimate> objects() const { return pipeline_.objects(); }
    const std::vector<Eigen::Vector2d>& plan() const { return controller_.navigator().plan(); }
    const Controller& controller() const { return controller_; }
    const Pipeline& pipeline() const { return pipeline_; }
    const SystemParams& params() const { return pipeline_.params(); }

  private:
    Costmap static_map_;
    Pipeline pipeline_;
    Controller controller_;
    std::optional<Pose2> last_pose_;

    void control(const Sweep& sweep, OnlineStep& out);
};

}  // namespace makeway::pipeline
