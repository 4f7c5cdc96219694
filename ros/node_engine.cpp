#include "ros/node_engine.hpp"

#include <sys/resource.h>
#include <sys/syscall.h>
#include <tbb/task_arena.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <condition_variable>
#include <cstdio>
#include <cstring>
#include <deque>
#include <mutex>
#include <thread>
#include <utility>

#include "io/cad_folder.hpp"
#include "io/config_reader.hpp"
#include "io/error.hpp"
#include "io/json_io.hpp"
#include "io/map_server_io.hpp"
#include "io/tracking_io.hpp"
#include "io/zones_io.hpp"
#include "makeway/perception/detector.hpp"
#include "makeway/pipeline/online_system.hpp"
#include "makeway/planning/beam_check.hpp"
#include "ros/node_engine_params.hpp"
#include "ros/sweep_source.hpp"

namespace makeway::rosio {
namespace {

using Clock = std::chrono::steady_clock;

perception::Detector load_weights(const std::string& given) {
    const std::filesystem::path path = given.empty()
                                           ? std::filesystem::path("models") / "detector.pt"
                                           : std::filesystem::path(given);
    try {
        return perception::Detector::load(path);
    } catch (const std::runtime_error& e) {
        // The loader names the file itself ("PATH: what"); the networks' module's errors do not.
        throw io::FileError(path.string(),
                            io::problem_after_path(path.string(), e.what()).value_or(e.what()));
    }
}

// Why a goal cannot be driven to on this costmap (empty: it can).
std::string goal_problem(const Eigen::Vector2d& goal, const Costmap& costmap) {
    if (!goal.allFinite()) return "goal is not finite";
    const std::optional<std::uint8_t> c = costmap.cost_at(goal);
    if (!c) return "goal is outside the map";
    if (*c >= cost::kInscribed && *c != cost::kUnknown) return "goal is inside an obstacle";
    return {};
}

}  // namespace

pipeline::SystemParams node_system_params(const NodeSettings& s) {
    const io::Config config = io::load_config(s.config);
    pipeline::SystemParams p =
        io::online_system_params(config, s.T_base_sensor ? &*s.T_base_sensor : nullptr);
    p.navigator.affordance.learned = io::load_zones(s.zones);
    return p;
}

std::string to_json(const NavStatus& s) {
    io::Json j = {{"state", s.state}, {"why", s.why}, {"distance_left_m", s.distance_left_m}};
    j["goal"] = s.goal ? io::Json::array({s.goal->x(), s.goal->y()}) : io::Json(nullptr);
    return io::dump_json(j);
}

GatedCommand gate_command(const VelocityCommand& last, std::optional<double> last_sweep_end_s,
                          std::optional<double> last_odometry_s, double now_s,
                          double sensor_timeout_s, double odometry_timeout_s) {
    if (!last_sweep_end_s || now_s - *last_sweep_end_s > sensor_timeout_s)
        return {{}, "no sweep for " + std::to_string(sensor_timeout_s).substr(0, 4) + " s"};
    if (!last_odometry_s || now_s - *last_odometry_s > odometry_timeout_s)
        return {{}, "no odometry for " + std::to_string(odometry_timeout_s).substr(0, 4) + " s"};
    return {last, {}};
}

struct NodeEngine::Impl {
    NodeSettings settings;
    Publish publish;
    pipeline::SystemParams params;
    perception::Detector detector;
    std::optional<verification::CadLibrary> library;
    std::optional<Costmap> static_map;
    std::unique_ptr<pipeline::OnlineSystem> system;  // built at the first sweep (its start pose)

    mutable std::mutex mutex;
    std::condition_variable changed;
    std::deque<std::pair<CloudSweep, Clock::time_point>> queue;
    std::vector<StampedPose2> odometry;
    NodeStats stats;
    // Navigation, shared with the callbacks' threads (under `mutex`).
    std::optional<Eigen::Vector2d> pending_goal;  // set_goal(), applied at the next sweep
    bool pending_cancel = false;
    VelocityCommand last_command;
    std::optional<double> last_sweep_end;
    NavStatus status;  // the worker's; copied into each output
    bool busy = false, stopping = false;
    std::thread worker;
    // Async perception: keyframes waiting, and its thread.
    std::deque<pipeline::PendingKeyframe> keyframes;
    bool perceiving = false;
    std::thread perceiver;

    Impl(const NodeSettings& s, Publish p)
        : settings(s),
          publish(std::move(p)),
          params(node_system_params(s)),
          detector(load_weights(s.model)) {
        if (!s.cad.empty()) library = io::read_cad_folder(s.cad);
        if (!s.map.empty()) static_map = io::read_map_server(s.map);
        if (settings.async_perception) perception::set_inference_threads(perception_threads());
        worker = std::thread([this] { run(); });
        if (settings.async_perception) perceiver = std::thread([this] { perceive_loop(); });
    }

    // The wheels at t: waits (up to odometry_wait_s) for odometry that covers t; nullopt without.
    // Odometry within kStampSlack_s of t covers it: stamps travel as integer nanoseconds and a
    // sweep's end is its stamp plus its last point's float time, so the odometry message of the
    // sweep's end can read a few ns early, and waiting for the next one costs a whole message
    // period.
    static constexpr double kStampSlack_s = 1e-3;
    std::optional<Pose2> wheels_at(double t, std::unique_lock<std::mutex>& lock) {
        const auto deadline =
            Clock::now() + std::chrono::duration<double>(settings.odometry_wait_s);
        while (!odometry.empty() && odometry.back().stamp_s < t - kStampSlack_s && !stopping &&
               Clock::now() < deadline) {
            changed.wait_until(lock, deadline);
        }
        if (odometry.empty()) return std::nullopt;
        if (const auto p = interpolate_at(odometry, t)) return p;
        return t > odometry.back().stamp_s ? std::optional<Pose2>(odometry.back().pose)
                                           : std::nullopt;
    }

    void run() {
        std::unique_lock<std::mutex> lock(mutex);
        double previous_duration = 0.1;
        while (true) {
            changed.wait(lock, [&] { return stopping || !queue.empty(); });
            if (queue.empty()) return;  // stopping, nothing left
            auto [sweep, arrived] = std::move(queue.front());
            queue.pop_front();
            busy = true;
            const double duration =
                sweep.timed && sweep.duration_s > 1e-4 ? sweep.duration_s : previous_duration;
            previous_duration = duration;
            const std::optional<Pose2> start = wheels_at(sweep.stamp_s, lock);
            const std::optional<Pose2> end =
                start ? wheels_at(sweep.stamp_s + duration, lock) : std::nullopt;
            const double waited_ms =
                std::chrono::duration<double, std::milli>(Clock::now() - arrived).count();
            lock.unlock();
            process(std::move(sweep), duration, start, end, waited_ms, arrived);
            lock.lock();
            busy = false;
            ++stats.processed;
            changed.notify_all();
        }
    }

    // The last command through gate_command at now_s. Under `mutex`.
    GatedCommand gated_at(double now_s) const {
        const std::optional<double> odometry_s =
            odometry.empty() ? std::nullopt : std::optional<double>(odometry.back().stamp_s);
        return gate_command(last_command, last_sweep_end, odometry_s, now_s,
                            settings.sensor_timeout_s, settings.odometry_timeout_s);
    }

    int perception_threads() const {
        if (settings.perception_threads > 0) return settings.perception_threads;
        return std::max(1, static_cast<int>(std::thread::hardware_concurrency()) - 1);
    }

    // The keyframe chain, one keyframe at a time, in order (the tracker needs every one).
    void perceive_loop() {
        // Below the control path: when the cores are short, the keyframe waits, the command does
        // not. Linux gives each thread its own nice value (PRIO_PROCESS with a thread id).
        if (settings.perception_nice != 0) {
            errno = 0;
            if (setpriority(PRIO_PROCESS, static_cast<id_t>(syscall(SYS_gettid)),
                            settings.perception_nice) != 0) {
                std::fprintf(stderr,
                             "makeway_node: perception keeps the control path's priority "
                             "(setpriority: %s)\n",
                             std::strerror(errno));
            }
        }
        // Its verification's parallel loops use at most perception_threads() threads (with one,
        // only this niced thread; TBB's workers that join a larger arena keep the default
        // priority).
        tbb::task_arena arena(perception_threads());
        std::unique_lock<std::mutex> lock(mutex);
        while (true) {
            changed.wait(
                lock, [&] { return (stopping && queue.empty() && !busy) || !keyframes.empty(); });
            if (keyframes.empty()) return;  // stopping, the worker is done, nothing left
            pipeline::PendingKeyframe k = std::move(keyframes.front());
            keyframes.pop_front();
            perceiving = true;
            lock.unlock();
            pipeline::StageTiming timing;
            pipeline::KeyframeResult kf;
            arena.execute([&] { kf = system->perceive(std::move(k), timing); });
            NodeOutput out;
            out.perception = true;
            out.stamp_s = kf.stamp_s;
            out.objects = kf.tracking.objects_world;
            out.keyframe_ms = timing.keyframe_ms();
            io::Json frame = io::objects_to_json(0, kf.stamp_s, out.objects);
            frame["T_world_sensor"] = io::pose_to_json(kf.T_world_keyframe);
            out.object_map_json = io::dump_json(frame);
            publish(out);
            lock.lock();
            perceiving = false;
            ++stats.keyframes;
            changed.notify_all();
        }
    }

    void process(CloudSweep sweep, double duration, const std::optional<Pose2>& wheel_start,
                 const std::optional<Pose2>& wheel_end, double waited_ms,
                 Clock::time_point arrived) {
        std::string notice;
        if (!system) {
            // The first sweep shows the sensor's lowest beam: a monitor told a lower one would
            // forget the obstacles near the robot it no longer sees (planning/beam_check.hpp).
            notice = planning::raise_lowest_beam(params.navigator.monitor, sweep.points);
            const Pose2 start = settings.start ? *settings.start : wheel_start.value_or(Pose2{});
            pipeline::OnlineSystemSetup setup;
            setup.params = params;
            setup.start = start;
            setup.map = static_map;
            setup.map_kind = static_map ? pipeline::MapKind::kFurnished : pipeline::MapKind::kNone;
            setup.free_area_m = settings.costmap_size_m;
            setup.detector = &detector;
            setup.library = library ? &*library : nullptr;
            system = std::make_unique<pipeline::OnlineSystem>(setup);
        }
        const double stamp = sweep.stamp_s;
        const pipeline::OnlineStep step = [&] {
            std::optional<Eigen::Vector2d> goal;
            bool cancel = false;
            {
                std::lock_guard<std::mutex> guard(mutex);
                goal = std::exchange(pending_goal, std::nullopt);
                cancel = std::exchange(pending_cancel, false);
            }
            if (cancel) {
                system->cancel();
                status = {"stopped", "cancelled", -1.0, std::nullopt};
            }
            if (goal) {  // checked against the costmap the robot has now
                const std::string problem = goal_problem(*goal, system->costmap());
                if (problem.empty()) {
                    system->set_route({*goal});
                    status = {"driving", "", -1.0, goal};
                } else {
                    system->cancel();
                    status = {"stopped", problem, -1.0, goal};
                }
            }
            pipeline::Sweep input{std::move(sweep.points), stamp, duration, wheel_start, wheel_end};
            if (!settings.async_perception) return system->process(std::move(input));
            std::optional<pipeline::PendingKeyframe> pending;
            pipeline::OnlineStep s = system->drive(std::move(input), &pending);
            if (pending) {
                std::lock_guard<std::mutex> guard(mutex);
                keyframes.push_back(std::move(*pending));
                changed.notify_all();
            }
            return s;
        }();
        NodeOutput out;
        out.stamp_s = stamp + duration;
        out.notice = notice;
        out.pose = step.sweep.pose;
        out.wheel_pose = wheel_end;
        out.T_world_sensor = step.sweep.T_world_sensor_end;
        out.keyframe = step.sweep.keyframe_formed;
        out.objects = step.sweep.objects;
        out.command = step.control.command;
        update_status(step, out);
        out.costmap = &system->costmap();
        out.per_sweep_ms = step.per_sweep_ms();
        out.front_end_ms = step.sweep.timing.deskew_ms;
        out.navigation_ms = step.control.nav.update_ms + step.control.monitor_ms;
        out.keyframe_ms = step.sweep.timing.keyframe_ms();
        out.queue_wait_ms = waited_ms;
        if (step.sweep.keyframe) {  // perceived in line (not async)
            io::Json frame = io::objects_to_json(0, out.stamp_s, out.objects);
            frame["T_world_sensor"] = io::pose_to_json(step.sweep.keyframe->T_world_keyframe);
            out.object_map_json = io::dump_json(frame);
            std::lock_guard<std::mutex> guard(mutex);
            ++stats.keyframes;
        }
        {
            std::lock_guard<std::mutex> guard(mutex);
            // A cancel that came in while this sweep was processed wins over its command.
            last_command = pending_cancel ? VelocityCommand{} : out.command;
            last_sweep_end = out.stamp_s;
            if (pending_cancel) out.command = {};
            out.gated = gated_at(settings.clock ? settings.clock() : out.stamp_s);
            if (settings.send_command)
                settings.send_command(
                    out.gated.command);  // the command first: the robot waits for it
        }
        out.latency_ms = std::chrono::duration<double, std::milli>(Clock::now() - arrived).count();
        publish(out);
    }

    void update_status(const pipeline::OnlineStep& step, NodeOutput& out) {
        const pipeline::Controller::Step& c = step.control;
        const Eigen::Vector2d here(out.pose.x_m, out.pose.y_m);
        if (c.navigating) {
            out.plan = system->plan();
            status.distance_left_m = system->controller().navigator().remaining_m(here);
            if (c.nav.arrived) {
                status = {"reached", "", 0.0, status.goal};
                out.plan.clear();
            } else if (c.nav.gave_up) {
                status = {"stopped",
                          "gave up: no plan or no progress for " +
                              std::to_string(static_cast<int>(params.navigator.give_up_s)) + " s",
                          status.distance_left_m, status.goal};
                out.plan.clear();
            } else if (c.guard.scale < params.navigator.monitor.min_scale && !c.guard.recovering) {
                status.state = "blocked";
                status.why =
                    "collision monitor: " + std::string(planning::to_string(c.guard.action));
            } else {
                status.state = "driving";
                status.why.clear();
            }
        }
        out.status = status;
    }
};

NodeEngine::NodeEngine(const NodeSettings& settings, Publish publish)
    : impl_(std::make_unique<Impl>(settings, std::move(publish))) {}

NodeEngine::~NodeEngine() {
    {
        std::lock_guard<std::mutex> lock(impl_->mutex);
        impl_->stopping = true;
    }
    impl_->changed.notify_all();
    impl_->worker.join();
    {
        std::lock_guard<std::mutex> lock(impl_->mutex);
        impl_->changed.notify_all();  // the worker is done: the perceiver may finish
    }
    if (impl_->perceiver.joinable()) impl_->perceiver.join();
}

void NodeEngine::push_sweep(CloudSweep sweep) {
    std::lock_guard<std::mutex> lock(impl_->mutex);
    ++impl_->stats.received;
    if (impl_->queue.size() >= impl_->settings.max_queue) {
        impl_->queue.pop_front();  // the oldest goes: the robot needs the present
        ++impl_->stats.dropped;
    }
    impl_->queue.emplace_back(std::move(sweep), Clock::now());
    impl_->stats.max_queue = std::max(impl_->stats.max_queue, impl_->queue.size());
    impl_->changed.notify_all();
}

void NodeEngine::push_odometry(const StampedPose2& pose) {
    std::lock_guard<std::mutex> lock(impl_->mutex);
    auto& odo = impl_->odometry;
    if (!odo.empty() && pose.stamp_s <= odo.back().stamp_s) return;  // out of order or repeated
    odo.push_back(pose);
    if (odo.size() > 20000) odo.erase(odo.begin(), odo.begin() + 10000);  // ~ minutes of history
    impl_->changed.notify_all();
}

void NodeEngine::set_goal(const Eigen::Vector2d& goal_m) {
    std::lock_guard<std::mutex> lock(impl_->mutex);
    impl_->pending_goal = goal_m;
    impl_->pending_cancel = false;
}

void NodeEngine::cancel() {
    std::lock_guard<std::mutex> lock(impl_->mutex);
    impl_->pending_goal.reset();
    impl_->pending_cancel = true;
    impl_->last_command = {};
    if (impl_->settings.send_command) impl_->settings.send_command({});
}

GatedCommand NodeEngine::send_command_at(double now_s) {
    std::lock_guard<std::mutex> lock(impl_->mutex);
    const GatedCommand gated = impl_->gated_at(now_s);
    if (impl_->settings.send_command) impl_->settings.send_command(gated.command);
    return gated;
}

void NodeEngine::drain() {
    std::unique_lock<std::mutex> lock(impl_->mutex);
    impl_->changed.wait(lock, [&] {
        return impl_->queue.empty() && !impl_->busy && impl_->keyframes.empty() &&
               !impl_->perceiving;
    });
}

NodeStats NodeEngine::stats() const {
    std::lock_guard<std::mutex> lock(impl_->mutex);
    return impl_->stats;
}

const costmap::AffordanceParams& NodeEngine::zones() const {
    return impl_->params.navigator.affordance;
}

}  // namespace makeway::rosio
