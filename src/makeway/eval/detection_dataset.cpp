#include "makeway/eval/detection_dataset.hpp"

#include <algorithm>
#include <map>
#include <optional>
#include <stdexcept>
#include <tuple>

#include "makeway/common/random.hpp"
#include "makeway/pipeline/front_end.hpp"
#include "makeway/sim/furniture.hpp"
#include "makeway/sim/route.hpp"
#include "makeway/sim/scene_dynamics.hpp"
#include "makeway/sim/scene_generator.hpp"
#include "makeway/sim/sequence.hpp"

namespace makeway::eval {
namespace {

sim::FurnitureStyle parse_style(const std::string& name) {
    const auto s = sim::parse_furniture_style(name);
    if (!s) throw std::invalid_argument("unknown furniture style '" + name + "'");
    return *s;
}

}  // namespace

void restyle_scene(sim::Scene& scene, const DatasetParams& p) {
    std::vector<sim::FurnitureStyle> excluded, only;
    for (const auto& n : p.exclude_styles) excluded.push_back(parse_style(n));
    for (const auto& n : p.only_styles) only.push_back(parse_style(n));
    Rng rng = make_rng(scene.seed, 0x5717);
    for (sim::SceneObject& o : scene.objects) {
        if (p.all_styles && only.empty()) {
            std::vector<sim::FurnitureStyle> allowed;
            for (sim::FurnitureStyle s : sim::styles_of(o.cls)) {
                if (std::find(excluded.begin(), excluded.end(), s) == excluded.end())
                    allowed.push_back(s);
            }
            if (!allowed.empty()) {
                o.style = std::string(sim::to_string(allowed[static_cast<std::size_t>(
                    uniform_int(rng, 0, static_cast<std::int64_t>(allowed.size()) - 1))]));
                continue;
            }
        }
        const sim::FurnitureStyle current = parse_style(o.style);
        std::optional<sim::FurnitureStyle> to;
        std::vector<sim::FurnitureStyle> only_of_class;
        for (sim::FurnitureStyle s : only) {
            if (sim::class_of(s) == o.cls) only_of_class.push_back(s);
        }
        if (only_of_class.size() == 1) to = only_of_class.front();
        if (only_of_class.size() > 1) {  // several styles of the class: one at random each
            to = only_of_class[static_cast<std::size_t>(
                uniform_int(rng, 0, static_cast<std::int64_t>(only_of_class.size()) - 1))];
        }
        if (!to && std::find(excluded.begin(), excluded.end(), current) != excluded.end()) {
            for (sim::FurnitureStyle s : sim::scene_styles_of(o.cls)) {
                if (std::find(excluded.begin(), excluded.end(), s) == excluded.end()) {
                    to = s;
                    break;
                }
            }
        }
        if (to) o.style = std::string(sim::to_string(*to));
    }
}

namespace {

// Some objects become the user's meshes of their class.
void furnish(sim::Scene& scene, const DatasetParams& p) {
    if (p.furniture.empty()) return;
    Rng rng = make_rng(scene.seed, 0xF0F0);
    for (sim::SceneObject& o : scene.objects) {
        std::vector<const UserFurniture*> of_class;
        for (const UserFurniture& f : p.furniture) {
            if (f.cls == o.cls) of_class.push_back(&f);
        }
        if (of_class.empty() || !bernoulli(rng, p.furniture_share)) continue;
        const UserFurniture& f = *of_class[static_cast<std::size_t>(
            uniform_int(rng, 0, static_cast<std::int64_t>(of_class.size()) - 1))];
        o.style.clear();
        o.mesh_file = f.name;
        o.user_mesh = f.mesh_object;
    }
}

// Clutter on the scene's free floor; items dropped from the back while they block the drive.
std::optional<std::vector<Eigen::Vector2d>> clutter_and_route(sim::Scene& scene,
                                                              const DatasetParams& p,
                                                              const sim::RobotParams& robot) {
    if (p.clutter_only) {
        scene.objects.clear();
        scene.pushers.clear();
    }
    const std::size_t before = scene.environment.size();
    if (p.clutter.count > 0) sim::add_clutter(scene, p.clutter, scene.seed * 31 + 7);
    const std::vector<sim::ObjectModel> models = sim::models_of(scene);
    for (;;) {
        const sim::CollisionChecker checker(scene, models, robot);
        auto route = sim::drive_route(scene, checker, robot);
        if (route || scene.environment.size() == before) return route;
        scene.environment.pop_back();
    }
}

}  // namespace

FurnitureSplit split_furniture(std::vector<UserFurniture> furniture, int holdout_every) {
    std::sort(furniture.begin(), furniture.end(),
              [](const UserFurniture& a, const UserFurniture& b) {
                  return std::tie(a.cls, a.name) < std::tie(b.cls, b.name);
              });
    FurnitureSplit split;
    std::map<ObjectClass, int> index;
    for (UserFurniture& f : furniture) {
        const int i = index[f.cls]++;
        const bool out = holdout_every > 0 && i % holdout_every == holdout_every - 1;
        (out ? split.held_out : split.train).push_back(std::move(f));
    }
    return split;
}

std::vector<LabelledKeyframe> generate_detection_dataset(
    const DatasetParams& p, const std::function<void(int, int)>& progress,
    std::vector<sim::Scene>* scenes) {
    std::vector<LabelledKeyframe> out;
    for (int k = 0; k < p.scenes; ++k) {
        sim::SceneGenParams g;
        g.seed = p.seed + static_cast<std::uint64_t>(k);
        g.density = static_cast<sim::Density>(k % 3);
        sim::Scene scene = sim::generate_scene(g);
        restyle_scene(scene, p);
        furnish(scene, p);
        const sim::RobotParams robot;
        auto route = clutter_and_route(scene, p, robot);
        if (scenes) scenes->push_back(scene);
        if (!route) continue;
        sim::SequenceParams sp;
        sp.seed = p.seed * 7919 + static_cast<std::uint64_t>(k);
        sp.odometry = p.odometry;
        sp.lidar.beam_pattern = p.beam_pattern;
        sp.robot.lidar_height_m = p.sensor_height_m;
        Rng sensor_rng = make_rng(scene.seed, 0x5E45);
        const DatasetParams::SensorVariety& v = p.sensor_variety;
        if (!v.patterns.empty() && bernoulli(sensor_rng, v.share)) {
            sp.lidar.beam_pattern = v.patterns[static_cast<std::size_t>(
                uniform_int(sensor_rng, 0, static_cast<std::int64_t>(v.patterns.size()) - 1))];
            sp.robot.lidar_height_m = uniform(sensor_rng, v.height_min_m, v.height_max_m);
        }
        sim::SequenceSimulator simulator(scene, *route, sp);
        // The online system's front end on the drive's sweeps and wheel odometry.
        pipeline::SystemParams system = p.system;
        system.keyframe.every = p.keyframe_every;
        system.T_base_sensor = sp.robot.T_robot_sensor();
        pipeline::FrontEnd front_end(system, simulator.start_pose());
        int made = 0;
        for (int f = 0; made < p.max_keyframes_per_scene && !simulator.reached_goal() && f < 2000;
             ++f) {
            const sim::SimFrame frame = simulator.next();
            const pipeline::FrontEndResult front =
                front_end.add({frame.points_sensor, frame.stamp_s, sp.lidar.sweep_duration_s(),
                               frame.odometry_pose, frame.odometry_end_pose});
            if (!front.keyframe) continue;
            LabelledKeyframe kf;
            kf.cloud_sensor = front.keyframe->prepared.cloud_sensor;
            std::map<std::uint32_t, std::size_t> points_of;
            for (std::uint32_t id : kf.cloud_sensor.instance) ++points_of[id];
            // Labels in the keyframe's true frame (the newest sweep's start); the pose the map gets
            // is the estimate.
            const Isometry3 T_keyframe_world = frame.T_world_sensor.inverse();
            kf.sequence = static_cast<std::uint32_t>(k);
            kf.stamp_s = frame.stamp_s;
            kf.T_world_sensor = front.keyframe->T_world_keyframe;
            kf.ground_plane_sensor = front.keyframe->prepared.ground.plane();
            for (const sim::ObjectState& o : frame.objects) {
                const OrientedBox box = o.box_world.transformed(T_keyframe_world);
                if (std::abs(box.centre_m.x()) > p.range_m ||
                    std::abs(box.centre_m.y()) > p.range_m)
                    continue;
                const auto it =
                    std::find_if(scene.objects.begin(), scene.objects.end(),
                                 [&](const sim::SceneObject& s) { return s.id == o.id; });
                const std::string style = it == scene.objects.end() ? ""
                                          : !it->mesh_file.empty()  ? "user:" + it->mesh_file
                                                                    : it->style;
                const LabelledObject label{o.id, o.cls, style, box, points_of[o.id]};
                (label.points >= p.min_points ? kf.objects : kf.unseen).push_back(label);
            }
            out.push_back(std::move(kf));
            ++made;
        }
        if (progress) progress(k + 1, p.scenes);
    }
    return out;
}

}  // namespace makeway::eval
