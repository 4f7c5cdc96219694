#include "ros/sim_engine.hpp"

#include <cmath>
#include <filesystem>
#include <optional>
#include <set>

#include "io/json_io.hpp"
#include "io/mesh_io.hpp"
#include "io/scene_io.hpp"
#include "io/sim_config.hpp"
#include "makeway/costmap/affordance.hpp"
#include "makeway/pipeline/keyframe.hpp"
#include "makeway/sim/contact_judge.hpp"
#include "makeway/sim/lidar.hpp"
#include "makeway/sim/robot.hpp"
#include "makeway/sim/scene_dynamics.hpp"
#include "makeway/sim/world.hpp"

namespace makeway::rosio {

struct SimRobot::Impl {
    io::SimConfig config;
    sim::Scene scene;
    std::vector<sim::ObjectModel> models;
    sim::World world;
    sim::CollisionChecker checker;
    sim::ContactJudge contact_judge;  // as the benchmark judges
    sim::WheelOdometry odometry;
    sim::RobotState state;
    SimRobotSettings settings;
    VelocityCommand last_command;
    double last_command_t = -1e9;
    double t = 0.0;
    std::uint64_t sweeps = 0;
    double distance_m = 0.0;
    double risk_time_s = 0.0;
    std::vector<Pose2> path;  // every sweep's end
    std::vector<sim::ContactEvent> contacts;
    static constexpr int kPhysicsSteps = 10;

    Impl(const SimRobotSettings& s, io::SimConfig c, sim::Scene sc)
        : config(std::move(c)),
          scene(std::move(sc)),
          models(sim::models_of(scene)),
          world(scene, models),
          checker(scene, models, config.robot),
          contact_judge(checker, config.robot),
          odometry(scene.start, config.odometry, s.seed ^ 0x0D0ULL),
          settings(s) {
        state.pose = scene.start;
        config.lidar.num_threads = std::max(1, s.lidar_threads);
        path.push_back(state.pose);
    }

    void judge(double ts, double dt) {
        const Eigen::Vector2d centre(state.pose.x_m, state.pose.y_m);
        bool risky = false;
        for (const ObjectEstimate& o : sim::object_estimates_at(scene, models, ts))
            risky |= costmap::in_affordance_zone(o, config.affordance, centre);
        if (risky) risk_time_s += dt;
        for (sim::ContactEvent& e : contact_judge.step(state, ts)) contacts.push_back(std::move(e));
    }
};

SimRobot::SimRobot(const SimRobotSettings& s) {
    io::SimConfig config = io::load_sim_config(s.config);
    sim::Scene scene = io::read_scene(s.scene);
    impl_ = std::make_unique<Impl>(s, std::move(config), std::move(scene));
}

SimRobot::~SimRobot() = default;

void SimRobot::command(const VelocityCommand& c, double t_s) {
    impl_->last_command = c;
    impl_->last_command_t = t_s;
}

SimTick SimRobot::tick() {
    Impl& m = *impl_;
    const double period = m.config.lidar.sweep_duration_s(), dt = period / Impl::kPhysicsSteps;
    SimTick out;
    out.t_start_s = m.t;
    std::vector<Pose2> poses{m.state.pose};
    for (int i = 0; i < Impl::kPhysicsSteps; ++i) {
        const double ts = m.t + i * dt;
        // A robot whose driver hears nothing brakes: a stale command is no command.
        const VelocityCommand c = ts - m.last_command_t <= m.settings.command_timeout_s
                                      ? m.last_command
                                      : VelocityCommand{};
        const Pose2 before = m.state.pose;
        m.state = sim::step_diff_drive(m.state, c, dt, m.config.robot);
        m.odometry.update(before, m.state.pose);
        m.distance_m += std::hypot(m.state.pose.x_m - before.x_m, m.state.pose.y_m - before.y_m);
        poses.push_back(m.state.pose);
        m.judge(ts + dt, dt);
        out.odometry.push_back({ts + dt, m.odometry.pose(), m.state.v_mps, m.state.w_radps});
    }
    const sim::PoseAtTime T_world_sensor_at =
        sim::sensor_pose_along(std::move(poses), m.t, dt, m.config.robot.T_robot_sensor());
    out.sweep = sim::simulate_sweep(m.world, m.config.lidar, T_world_sensor_at, m.t,
                                    m.settings.seed, m.sweeps++);
    out.sweep = pipeline::sensor_channels_only(
        std::move(out.sweep));  // what a driver gives: no labels, no instance ids
    m.t += period;
    out.t_end_s = m.t;
    out.truth = m.state.pose;
    out.v_mps = m.state.v_mps;
    out.w_radps = m.state.w_radps;
    m.path.push_back(m.state.pose);
    return out;
}

double SimRobot::period_s() const { return impl_->config.lidar.sweep_duration_s(); }
Pose2 SimRobot::start() const { return impl_->scene.start; }
Isometry3 SimRobot::T_base_sensor() const { return impl_->config.robot.T_robot_sensor(); }

int SimRobot::robot_caused_contacts() const {
    int n = 0;
    for (const auto& c : impl_->contacts) n += c.robot_caused;
    return n;
}

void SimRobot::write_cad_folder(const std::string& folder) const {
    namespace fs = std::filesystem;
    const fs::path final_dir(folder), staging = fs::path(folder + ".partial");
    fs::remove_all(staging);
    fs::create_directories(staging);
    std::set<std::string> written;
    for (const sim::SceneObject& o : impl_->scene.objects) {
        const std::string name =
            o.style.empty() ? fs::path(o.mesh_file).stem().string() + "_x" + std::to_string(o.scale)
                            : o.style + "_" + std::to_string(o.model_seed);
        if (!written.insert(name).second) continue;
        io::write_mesh(staging / (std::string(to_string(o.cls)) + "_" + name + ".obj"),
                       sim::model_of(o).mesh_object);
    }
    fs::remove_all(final_dir);
    fs::rename(staging, final_dir);
}

std::vector<Eigen::Vector2d> SimRobot::route() const {
    const sim::Scene& s = impl_->scene;
    return {{s.waypoint.x_m, s.waypoint.y_m}, {s.goal.x_m, s.goal.y_m}};
}

bool SimRobot::collided() const {
    for (const auto& c : impl_->contacts) {
        if (c.kind != "people") return true;
    }
    return false;
}

std::string SimRobot::report_json(const std::string& extra) const {
    const Impl& m = *impl_;
    io::Json j = io::Json::parse(extra);
    j["scene"] = m.scene.name;
    j["time_s"] = m.t;
    j["distance_m"] = m.distance_m;
    j["risk_time_s"] = m.risk_time_s;
    j["collided"] = collided();
    const Pose2& p = m.state.pose;
    const double to_goal = std::hypot(p.x_m - m.scene.goal.x_m, p.y_m - m.scene.goal.y_m);
    j["distance_to_goal_m"] = to_goal;
    j["goal"] = {m.scene.goal.x_m, m.scene.goal.y_m};
    io::Json counts = io::Json::object();
    for (const char* kind : {"walls", "furniture", "people"})
        counts[kind] = {{"robot_caused", 0}, {"other_caused", 0}};
    io::Json events = io::Json::array();
    for (const auto& c : m.contacts) {
        counts[c.kind][c.robot_caused ? "robot_caused" : "other_caused"] =
            counts[c.kind][c.robot_caused ? "robot_caused" : "other_caused"].get<int>() + 1;
        events.push_back({{"t_s", c.t_s},
                          {"kind", c.kind},
                          {"robot_caused", c.robot_caused},
                          {"toward_mps", c.toward_mps},
                          {"where_m", {c.where_m.x(), c.where_m.y()}}});
    }
    j["contacts"] = counts;
    j["robot_caused_contacts"] = robot_caused_contacts();
    j["contact_events"] = events;
    io::Json path = io::Json::array();
    for (const Pose2& q : m.path) path.push_back({q.x_m, q.y_m, q.yaw_rad});
    j["path_xyyaw"] = path;
    return io::dump_json(j);
}

}  // namespace makeway::rosio
