#include "apps/recording.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <iostream>
#include <optional>

#include "io/error.hpp"
#include "io/file_util.hpp"
#include "io/json_io.hpp"
#include "io/point_cloud_io.hpp"
#include "io/pose_io.hpp"
#include "io/progress.hpp"
#include "io/scene_io.hpp"
#include "io/scene_png.hpp"
#include "io/staged_output.hpp"
#include "makeway/sim/route.hpp"
#include "ros/bag_io.hpp"

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
        people.push_back({{"id", sim::kPersonInstanceBase + k},
                          {"position_m", {f.people_m[k].x(), f.people_m[k].y()}}});
    }
    return {{"frame", f.index},
            {"stamp_s", f.stamp_s},
            {"collided", f.collided},
            {"objects", objects},
            {"people", people}};
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
    pic.title = scene.name + ": " + std::to_string(tables) + " tables, " + std::to_string(chairs) +
                " chairs, " + std::to_string(scene.walkers.size()) + " walkers, " +
                std::to_string(scene.pushers.size()) + " chair pushers";
    auto png = path;
    io::write_scene_png(png.replace_extension(".png"), scene, models, pic);
    return pic.title;
}

std::vector<Eigen::Vector2d> auto_route(const sim::Scene& scene, const sim::RobotParams& robot,
                                        const std::string& scene_name) {
    const auto models = models_of(scene);
    const sim::CollisionChecker checker(scene, models, robot);
    auto route = sim::drive_route(scene, checker, robot);
    if (!route)
        throw io::FileError(scene_name,
                            "no collision-free route from start through waypoint to goal");
    return *route;
}

std::uintmax_t recording_bytes_upper_bound(const sim::LidarParams& lidar,
                                           const RecordingOptions& options) {
    // Every ray returning, in the chosen format, plus a frame's ground-truth JSON (generous).
    PointCloud one, many;
    one.resize(1, PointFields::all());
    many.resize(1001, PointFields::all());
    const std::size_t per_point =
        options.format == "bin" ? 16 + 4  // .bin xyzi + .label
        : options.format == "bag"
            ? 22 + 8  // PointCloud2 x y z intensity ring time, bag overhead
            : (io::serialize_pcd(many, io::PcdEncoding::kBinary).size() -
               io::serialize_pcd(one, io::PcdEncoding::kBinary).size() + 999) /
                  1000;
    const std::uintmax_t rays = static_cast<std::uintmax_t>(lidar.num_beams()) *
                                static_cast<std::uintmax_t>(lidar.num_columns());
    const std::uintmax_t clouds =
        (static_cast<std::uintmax_t>(options.frames) + options.cloud_every - 1) /
        options.cloud_every;
    return clouds * rays * per_point + static_cast<std::uintmax_t>(options.frames) * 16384;
}

RecordingSummary record_sequence(const sim::Scene& scene, const std::vector<Eigen::Vector2d>& route,
                                 const sim::SequenceParams& params, const RecordingOptions& options,
                                 const std::filesystem::path& out, const std::string& scene_label) {
    io::check_free_space(out, recording_bytes_upper_bound(params.lidar, options),
                         std::to_string(options.frames) + " frames of " +
                             std::to_string(params.lidar.num_beams()) + " beams x " +
                             std::to_string(params.lidar.num_columns()) + " columns");
    io::RecordingFolder folder(out, "simulate");
    const int frames = options.frames;
    const std::string& format = options.format;
    sim::SequenceSimulator simulator(scene, route, params);
    std::vector<io::StampedPose> gt, odom;
    RecordingSummary summary;
    const auto summary_json = [&] {
        const auto& trajectory = simulator.trajectory();
        summary.distance_m = 0.0;
        for (std::size_t i = 1; i < trajectory.size(); ++i) {
            summary.distance_m += std::hypot(trajectory[i].x_m - trajectory[i - 1].x_m,
                                             trajectory[i].y_m - trajectory[i - 1].y_m);
        }
        return io::Json{{"scene", scene_label},
                        {"frames", summary.frames},
                        {"frames_requested", frames},
                        {"reached_goal", summary.reached_goal},
                        {"frames_in_collision", summary.frames_in_collision},
                        {"distance_m", summary.distance_m},
                        {"points", summary.points},
                        {"ms_per_frame", summary.ms_per_frame},
                        {"format", format}};
    };
    std::string writing;  // the frame whose files are being written
    // --format bag: the drive as a robot records it (clouds, wheel odometry, the sensor's mount),
    // the truth on topics of its own. Written to drive.bag.active, renamed when complete.
    std::optional<rosio::BagWriter> bag;
    const double epoch = rosio::kSimulatedEpoch_s;
    try {
        if (format == "bag") {
            bag.emplace(out / "drive.bag");
            bag->write_tf(params.robot.T_robot_sensor(), epoch, "base_link", "velodyne", true);
        }
        io::ProgressBar bar("simulate", static_cast<std::size_t>(frames));
        double sim_s = 0.0;
        for (int i = 0; i < frames && !(options.stop_at_goal && simulator.reached_goal()); ++i) {
            const auto t0 = std::chrono::steady_clock::now();
            const sim::SimFrame f = simulator.next();
            sim_s += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
            summary.frames_in_collision += f.collided;
            summary.points += f.points_sensor.size();
            const std::string name = io::frame_name(static_cast<std::size_t>(f.index));
            writing = name;
            if (i % options.cloud_every != 0) {
                // ground truth only
            } else if (bag) {
                bag->write_cloud("/velodyne_points", f.points_sensor, epoch + f.stamp_s,
                                 "velodyne");
                bag->write_odometry("/odom", f.odometry_pose, 0.0, 0.0, epoch + f.stamp_s, "odom",
                                    "base_link");
                bag->write_odometry("/odom", f.odometry_end_pose, 0.0, 0.0,
                                    epoch + f.stamp_s + params.lidar.sweep_duration_s(), "odom",
                                    "base_link");
                bag->write_odometry("/ground_truth/odom", f.true_pose, 0.0, 0.0, epoch + f.stamp_s,
                                    "map", "base_link");
                bag->write_text("/ground_truth/objects", io::dump_json(frame_json(f)),
                                epoch + f.stamp_s);
            } else if (format == "bin") {
                io::write_point_cloud(out / "clouds" / (std::string(name) + ".bin"),
                                      f.points_sensor);
                io::write_file_atomic(out / "labels" / (std::string(name) + ".label"),
                                      semantic_kitti_labels(f.points_sensor));
            } else {
                io::write_point_cloud(out / "clouds" / (std::string(name) + ".pcd"),
                                      f.points_sensor);
            }
            io::write_json(out / "objects" / (std::string(name) + ".json"), frame_json(f));
            gt.push_back({f.stamp_s, f.T_world_sensor});
            odom.push_back({f.stamp_s, lift_to_3d(f.odometry_pose)});
            ++summary.frames;  // only once everything of the frame is on disk
            writing.clear();
            summary.ms_per_frame = 1e3 * sim_s / summary.frames;
            bar.update(static_cast<std::size_t>(i + 1),
                       std::to_string(f.points_sensor.size()) + " points");
        }
        bar.finish(simulator.reached_goal() ? "goal reached" : "");
        io::write_tum(out / "poses_gt.txt", gt);
        io::write_tum(out / "odometry.txt", odom);
        if (bag) bag->close();
        summary.reached_goal = simulator.reached_goal();
        const io::Json done = summary_json();  // sets distance_m
        const auto& trajectory = simulator.trajectory();
        io::ScenePicture pic;
        pic.route_m = route;
        pic.trajectory = trajectory;
        pic.title =
            scene.name + ": " + std::to_string(summary.frames) + " frames, " +
            std::to_string(summary.distance_m).substr(0, 5) + " m" +
            (summary.reached_goal ? ", goal reached" : "") +
            (summary.frames_in_collision
                 ? ", " + std::to_string(summary.frames_in_collision) + " frames in collision"
                 : "");
        io::write_scene_png(out / "scene.png", scene, simulator.world().models(), pic);
        folder.complete(done);
    } catch (const std::exception& e) {
        // Each write may throw again (the interrupt flag stays set): best effort, one by one.
        const auto attempt = [](const auto& write) {
            try {
                write();
            } catch (...) {
            }
        };
        // The frame being written when it stopped is removed: every frame on disk is whole.
        for (const char* part :
             {"clouds/%.pcd", "clouds/%.bin", "labels/%.label", "objects/%.json"}) {
            if (writing.empty()) break;
            std::string rel = part;
            rel.replace(rel.find('%'), 1, writing);
            std::error_code ec;
            std::filesystem::remove(out / rel, ec);
        }
        // The poses of the frames on disk, so that the part that exists can be used.
        gt.resize(std::min(gt.size(), static_cast<std::size_t>(summary.frames)));
        odom.resize(std::min(odom.size(), static_cast<std::size_t>(summary.frames)));
        attempt([&] { io::write_tum(out / "poses_gt.txt", gt); });
        attempt([&] { io::write_tum(out / "odometry.txt", odom); });
        folder.stopped(summary_json(), e.what());
        throw;
    }
    return summary;
}

}  // namespace makeway::apps
