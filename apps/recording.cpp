#include "apps/recording.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <iostream>

#include "io/error.hpp"
#include "io/file_util.hpp"
#include "io/json_io.hpp"
#include "io/point_cloud_io.hpp"
#include "io/pose_io.hpp"
#include "io/progress.hpp"
#include "io/scene_io.hpp"
#include "io/scene_png.hpp"
#include "makeway/sim/route.hpp"

namespace makeway::apps {
namespace {

// SemanticKITTI .label: uint32 per point, semantic label in the low 16 bits, instance in the high.
std::string semantic_kitti_labels(const PointCloud& cloud) {
    std::string out(cloud.size() * 4, '\0');
    for (std::size_t i = 0; i < cloud.size(); ++i) {
        const std::uint32_t v = cloud.label[i] | ((cloud.instance[i] & 0xFFFFu) << 16);
        std::memcpy(out.data() + 4 * i, &v, 4);
    }
    return out;
}

io::Json frame_json(const sim::SimFrame& f) {
    io::Json objects = io::Json::array();
    for (const auto& o : f.objects) {
        const Pose2 p = project_to_plane(o.T_world_object);
        objects.push_back({{"id", o.id},
                           {"class", std::string(to_string(o.cls))},
                           {"box_world", io::to_json(o.box_world)},
                           {"pose_world", {{"x_m", p.x_m}, {"y_m", p.y_m}, {"yaw_rad", p.yaw_rad}}},
                           {"velocity_mps", {o.velocity_mps.x(), o.velocity_mps.y()}}});
    }
    io::Json people = io::Json::array();
    for (std::size_t k = 0; k < f.people_m.size(); ++k) {
        people.push_back({{"id", sim::kPersonInstanceBase + k}, {"position_m", {f.people_m[k].x(), f.people_m[k].y()}}});
    }
    return {{"frame", f.index}, {"stamp_s", f.stamp_s}, {"collided", f.collided}, {"objects", objects}, {"people", people}};
}

}  // namespace

std::string write_scene_with_picture(const std::filesystem::path& path, const sim::Scene& scene) {
    io::write_scene(path, scene);
    const auto models = models_of(scene);
    const sim::CollisionChecker checker(scene, models, sim::RobotParams{});
    io::ScenePicture pic;
    if (auto route = sim::drive_route(scene, checker, sim::RobotParams{})) pic.route_m = *route;
    int chairs = 0, tables = 0;
    for (const auto& o : scene.objects) (o.cls == ObjectClass::kChair ? chairs : tables)++;
    pic.title = scene.name + ": " + std::to_string(tables) + " tables, " + std::to_string(chairs) + " chairs, " +
                std::to_string(scene.walkers.size()) + " walkers, " + std::to_string(scene.pushers.size()) +
                " chair pushers";
    auto png = path;
    io::write_scene_png(png.replace_extension(".png"), scene, models, pic);
    return pic.title;
}

std::vector<Eigen::Vector2d> auto_route(const sim::Scene& scene, const sim::RobotParams& robot,
                                        const std::string& scene_name) {
    const auto models = models_of(scene);
    const sim::CollisionChecker checker(scene, models, robot);
    auto route = sim::drive_route(scene, checker, robot);
    if (!route) throw io::FileError(scene_name, "no collision-free route from start through waypoint to goal");
    return *route;
}

RecordingSummary record_sequence(const sim::Scene& scene, const std::vector<Eigen::Vector2d>& route,
                                 const sim::SequenceParams& params, const RecordingOptions& options,
                                 const std::filesystem::path& out, const std::string& scene_label) {
    const int frames = options.frames;
    const std::string& format = options.format;
    sim::SequenceSimulator simulator(scene, route, params);
    std::vector<io::StampedPose> gt, odom;
    io::ProgressBar bar("simulate", static_cast<std::size_t>(frames));
    RecordingSummary summary;
    double sim_s = 0.0;
    for (int i = 0; i < frames && !(options.stop_at_goal && simulator.reached_goal()); ++i) {
        const auto t0 = std::chrono::steady_clock::now();
        const sim::SimFrame f = simulator.next();
        sim_s += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        summary.frames_in_collision += f.collided;
        summary.points += f.points_sensor.size();
        char name[32];
        std::snprintf(name, sizeof(name), "%06d", f.index);
        ++summary.frames;
        if (i % options.cloud_every != 0) {
            // ground truth only
        } else if (format == "bin") {
            io::write_point_cloud(out / "clouds" / (std::string(name) + ".bin"), f.points_sensor);
            io::write_file_atomic(out / "labels" / (std::string(name) + ".label"), semantic_kitti_labels(f.points_sensor));
        } else {
            io::write_point_cloud(out / "clouds" / (std::string(name) + ".pcd"), f.points_sensor);
        }
        io::write_json(out / "objects" / (std::string(name) + ".json"), frame_json(f));
        gt.push_back({f.stamp_s, f.T_world_sensor});
        odom.push_back({f.stamp_s, lift_to_3d(f.odometry_pose)});
        bar.update(static_cast<std::size_t>(i + 1), std::to_string(f.points_sensor.size()) + " points");
    }
    bar.finish(simulator.reached_goal() ? "goal reached" : "");
    io::write_tum(out / "poses_gt.txt", gt);
    io::write_tum(out / "odometry.txt", odom);
    const auto& trajectory = simulator.trajectory();
    for (std::size_t i = 1; i < trajectory.size(); ++i) {
        summary.distance_m += std::hypot(trajectory[i].x_m - trajectory[i - 1].x_m, trajectory[i].y_m - trajectory[i - 1].y_m);
    }
    summary.reached_goal = simulator.reached_goal();
    summary.ms_per_frame = 1e3 * sim_s / std::max(summary.frames, 1);
    io::ScenePicture pic;
    pic.route_m = route;
    pic.trajectory = trajectory;
    pic.title = scene.name + ": " + std::to_string(summary.frames) + " frames, " + std::to_string(summary.distance_m).substr(0, 5) +
                " m" + (summary.reached_goal ? ", goal reached" : "") +
                (summary.frames_in_collision ? ", " + std::to_string(summary.frames_in_collision) + " frames in collision" : "");
    io::write_scene_png(out / "scene.png", scene, simulator.world().models(), pic);
    io::write_json(out / "summary.json", {{"scene", scene_label},
                                          {"frames", summary.frames},
                                          {"reached_goal", summary.reached_goal},
                                          {"frames_in_collision", summary.frames_in_collision},
                                          {"distance_m", summary.distance_m},
                                          {"points", summary.points},
                                          {"ms_per_frame", summary.ms_per_frame},
                                          {"format", format}});
    return summary;
}

}  // namespace makeway::apps
