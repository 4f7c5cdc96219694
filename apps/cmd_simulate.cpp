// makeway simulate: drive the simulated Jackal through a scene and record every sweep with its
// ground truth.
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <iostream>

#include "apps/commands.hpp"
#include "io/error.hpp"
#include "io/file_util.hpp"
#include "io/json_io.hpp"
#include "io/point_cloud_io.hpp"
#include "io/pose_io.hpp"
#include "io/progress.hpp"
#include "io/scene_io.hpp"
#include "io/scene_png.hpp"
#include "io/text_scan.hpp"
#include "makeway/sim/route.hpp"
#include "makeway/sim/sequence.hpp"

namespace makeway::apps {
namespace {

// A route file: one "x y" pair [m] per line, '#' comments.
std::vector<Eigen::Vector2d> read_route(const std::string& path) {
    const std::string text = io::read_file(path);
    std::vector<Eigen::Vector2d> route;
    std::size_t pos = 0, line_no = 0;
    while (const auto line = io::next_line(text, pos)) {
        ++line_no;
        const auto words = io::split_words(*line);
        if (words.empty() || words[0].front() == '#') continue;
        double xy[2];
        for (int k = 0; k < 2; ++k) {
            if (words.size() != 2 || std::sscanf(std::string(words[k]).c_str(), "%lf", &xy[k]) != 1 || !std::isfinite(xy[k])) {
                throw io::FileError(path, "line " + std::to_string(line_no) + ": expected two numbers 'x y'");
            }
        }
        route.emplace_back(xy[0], xy[1]);
    }
    if (route.empty()) throw io::FileError(path, "no route points");
    return route;
}

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

int run_simulate(const SimulateOptions& options) {
    const sim::Scene scene = io::read_scene(options.scene);
    const std::filesystem::path out = options.out_dir;
    if (options.frames < 1 || options.frames > 1000000) throw io::FileError(options.scene, "--frames must be in [1, 1000000]");
    sim::SequenceParams params;
    params.seed = options.seed;
    params.lidar.num_threads = options.threads;

    std::vector<sim::ObjectModel> models;
    for (const auto& o : scene.objects) models.push_back(sim::model_of(o));
    std::vector<Eigen::Vector2d> route;
    if (options.route == "auto") {
        const sim::CollisionChecker checker(scene, models, params.robot);
        auto r = sim::drive_route(scene, checker, params.robot);
        if (!r) throw io::FileError(options.scene, "no collision-free route from start through waypoint to goal");
        route = *r;
    } else {
        route = read_route(options.route);
        route.insert(route.begin(), Eigen::Vector2d(scene.start.x_m, scene.start.y_m));
    }

    sim::SequenceSimulator simulator(scene, route, params);
    std::vector<io::StampedPose> gt, odom;
    io::ProgressBar bar("simulate", static_cast<std::size_t>(options.frames));
    std::size_t rays = 0, collisions = 0;
    double cast_s = 0.0;
    for (int i = 0; i < options.frames; ++i) {
        const auto t0 = std::chrono::steady_clock::now();
        const sim::SimFrame f = simulator.next();
        cast_s += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        rays += f.sweep.rays;
        collisions += f.collided;
        char name[32];
        std::snprintf(name, sizeof(name), "%06d", f.index);
        if (options.format == "bin") {
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
    bar.finish();
    io::write_tum(out / "poses_gt.txt", gt);
    io::write_tum(out / "odometry.txt", odom);
    io::ScenePicture pic;
    pic.route_m = route;
    pic.trajectory = simulator.trajectory();
    pic.title = scene.name + ": " + std::to_string(options.frames) + " frames" +
                (simulator.reached_goal() ? ", goal reached" : "") +
                (collisions ? ", " + std::to_string(collisions) + " frames in collision" : "");
    io::write_scene_png(out / "scene.png", scene, models, pic);
    double distance = 0.0;
    for (std::size_t i = 1; i < pic.trajectory.size(); ++i) {
        distance += std::hypot(pic.trajectory[i].x_m - pic.trajectory[i - 1].x_m,
                               pic.trajectory[i].y_m - pic.trajectory[i - 1].y_m);
    }
    io::write_json(out / "summary.json", {{"scene", options.scene},
                                          {"frames", options.frames},
                                          {"reached_goal", simulator.reached_goal()},
                                          {"frames_in_collision", collisions},
                                          {"distance_m", distance},
                                          {"rays", rays},
                                          {"seconds_per_frame", cast_s / options.frames},
                                          {"format", options.format}});
    std::cout << "wrote " << options.frames << " frames to " << out.string() << " (distance " << distance
              << " m, goal " << (simulator.reached_goal() ? "reached" : "not reached") << ", "
              << cast_s / options.frames * 1e3 << " ms per frame)\n";
    return 0;
}

}  // namespace makeway::apps
