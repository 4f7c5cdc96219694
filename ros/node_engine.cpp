#include "ros/node_engine.hpp"

#include <chrono>
#include <condition_variable>
#include <deque>
#include <mutex>
#include <thread>

#include "io/cad_folder.hpp"
#include "io/config_reader.hpp"
#include "io/error.hpp"
#include "io/json_io.hpp"
#include "io/map_server_io.hpp"
#include "io/tracking_io.hpp"
#include "makeway/perception/detector.hpp"
#include "makeway/pipeline/mapping_system.hpp"
#include "ros/sweep_source.hpp"

namespace makeway::rosio {
namespace {

using Clock = std::chrono::steady_clock;

perception::Detector load_weights(const std::string& given) {
    const std::filesystem::path path = given.empty() ? std::filesystem::path("models") / "detector.pt" : std::filesystem::path(given);
    try {
        return perception::Detector::load(path);
    } catch (const std::runtime_error& e) {
        throw io::FileError(path.string(), e.what());
    }
}

}  // namespace

struct NodeEngine::Impl {
    NodeSettings settings;
    Publish publish;
    io::Config config;
    pipeline::SystemParams params;
    perception::Detector detector;
    std::optional<verification::CadLibrary> library;
    std::optional<Costmap> static_map;
    std::unique_ptr<pipeline::MappingSystem> system;  // built at the first sweep (its start pose)

    mutable std::mutex mutex;
    std::condition_variable changed;
    std::deque<std::pair<CloudSweep, Clock::time_point>> queue;
    std::vector<StampedPose2> odometry;
    NodeStats stats;
    bool busy = false, stopping = false;
    std::thread worker;

    Impl(const NodeSettings& s, Publish p)
        : settings(s), publish(std::move(p)), config(s.config.empty() ? io::Config{} : io::load_config(s.config)),
          params(io::online_system_params(config)), detector(load_weights(s.model)) {
        if (!s.cad.empty()) library = io::read_cad_folder(s.cad);
        if (!s.map.empty()) static_map = io::read_map_server(s.map);
        worker = std::thread([this] { run(); });
    }

    // The wheels at t: waits (up to odometry_wait_s) for odometry that covers t; nullopt without.
    std::optional<Pose2> wheels_at(double t, std::unique_lock<std::mutex>& lock) {
        const auto deadline = Clock::now() + std::chrono::duration<double>(settings.odometry_wait_s);
        while (!odometry.empty() && odometry.back().stamp_s < t && !stopping && Clock::now() < deadline) {
            changed.wait_until(lock, deadline);
        }
        if (odometry.empty()) return std::nullopt;
        if (const auto p = interpolate_at(odometry, t)) return p;
        return t > odometry.back().stamp_s ? std::optional<Pose2>(odometry.back().pose) : std::nullopt;
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
            const double duration = sweep.timed && sweep.duration_s > 1e-4 ? sweep.duration_s : previous_duration;
            previous_duration = duration;
            const std::optional<Pose2> start = wheels_at(sweep.stamp_s, lock);
            const std::optional<Pose2> end = start ? wheels_at(sweep.stamp_s + duration, lock) : std::nullopt;
            const double waited_ms = std::chrono::duration<double, std::milli>(Clock::now() - arrived).count();
            lock.unlock();
            process(std::move(sweep), duration, start, end, waited_ms);
            lock.lock();
            busy = false;
            ++stats.processed;
            changed.notify_all();
        }
    }

    void process(CloudSweep sweep, double duration, const std::optional<Pose2>& wheel_start, const std::optional<Pose2>& wheel_end,
                 double waited_ms) {
        if (!system) {
            const Pose2 start = settings.start ? *settings.start : wheel_start.value_or(Pose2{});
            const Costmap map = static_map ? *static_map : pipeline::free_area(start, settings.costmap_size_m);
            system = std::make_unique<pipeline::MappingSystem>(params, start, map, static_map.has_value(), &detector,
                                                               library ? &*library : nullptr);
        }
        const double stamp = sweep.stamp_s;
        const pipeline::MappingStep step = system->process({std::move(sweep.points), stamp, duration, wheel_start, wheel_end});
        NodeOutput out;
        out.stamp_s = stamp + duration;
        out.pose = step.sweep.pose;
        out.T_world_sensor = step.sweep.T_world_sensor_end;
        out.keyframe = step.sweep.keyframe.has_value();
        out.objects = step.sweep.objects;
        out.costmap = &system->costmap();
        out.per_sweep_ms = step.per_sweep_ms();
        out.keyframe_ms = step.sweep.timing.keyframe_ms();
        out.queue_wait_ms = waited_ms;
        if (out.keyframe) {
            io::Json frame = io::objects_to_json(0, out.stamp_s, out.objects);
            frame["T_world_sensor"] = io::pose_to_json(step.sweep.keyframe->T_world_keyframe);
            out.object_map_json = io::dump_json(frame);
            std::lock_guard<std::mutex> guard(mutex);
            ++stats.keyframes;
        }
        publish(out);
    }
};

NodeEngine::NodeEngine(const NodeSettings& settings, Publish publish) : impl_(std::make_unique<Impl>(settings, std::move(publish))) {}

NodeEngine::~NodeEngine() {
    {
        std::lock_guard<std::mutex> lock(impl_->mutex);
        impl_->stopping = true;
    }
    impl_->changed.notify_all();
    impl_->worker.join();
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

void NodeEngine::drain() {
    std::unique_lock<std::mutex> lock(impl_->mutex);
    impl_->changed.wait(lock, [&] { return impl_->queue.empty() && !impl_->busy; });
}

NodeStats NodeEngine::stats() const {
    std::lock_guard<std::mutex> lock(impl_->mutex);
    return impl_->stats;
}

const costmap::AffordanceParams& NodeEngine::zones() const { return impl_->params.navigator.affordance; }

}  // namespace makeway::rosio
