#include "apps/nav_report.hpp"

#include <algorithm>
#include <cstdio>

#include "makeway/common/statistics.hpp"
#include "io/interrupt.hpp"

namespace makeway::apps {

std::pair<double, double> median_p99(const std::vector<double>& v) { return {median(v), percentile(v, 0.99)}; }

eval::NavParams nav_params(const io::Config& config) {
    eval::NavParams p;
    p.lidar = config.lidar;
    p.robot = config.robot;
    p.odometry = config.odometry;
    p.system = io::online_system_params(config);  // navigation sets each method's inflation radius
    p.on_sweep = io::throw_if_interrupted;  // Ctrl-C stops a run within one sweep
    p.seed = config.simulation.seed;
    return p;
}

io::Json run_to_json(const eval::NavRunResult& r, bool with_trajectory) {
    const auto [median, p99] = median_p99(r.cycle_ms);
    io::Json j = {{"method", r.method},
                  {"success", r.success},
                  {"reached_goal", r.reached_goal},
                  {"failure", r.failure},
                  {"total_time_s", r.time_s},
                  {"distance_m", r.distance_m},
                  {"risk_time_s", r.risk_time_s},
                  {"collisions", r.collisions},
                  {"person_contacts", r.person_contacts},
                  {"near_misses", r.near_misses},
                  {"min_clearance_m", r.min_clearance_m},
                  {"shortest_m", r.shortest_m},
                  {"spl", r.spl},
                  {"replans", r.replans},
                  {"recoveries", r.recoveries},
                  {"cycle_ms_median", median},
                  {"cycle_ms_p99", p99},
                  {"final_pose_error_m", r.final_pose_error_m},
                  {"pose_ate_m", r.pose_ate_m},
                  {"stop_distance_m", r.stop_distance_m}};
    if (!r.keyframes.empty()) {  // the online system: its keyframes, timing and final object map
        std::vector<double> chain, accumulate, ground, detect, verify, track, deskew;
        for (const auto& t : r.keyframe_timing) {
            chain.push_back(t.keyframe_ms());
            accumulate.push_back(t.accumulate_ms);
            ground.push_back(t.ground_ms);
            detect.push_back(t.detect_ms);
            verify.push_back(t.verify_ms);
            track.push_back(t.track_ms);
            deskew.push_back(t.deskew_ms);
        }
        j["keyframes"] = r.keyframes.size();
        j["keyframe_ms_median"] = median_p99(chain).first;
        j["keyframe_ms_p99"] = median_p99(chain).second;
        j["stage_ms_median"] = {{"deskew", median_p99(deskew).first}, {"accumulate", median_p99(accumulate).first},
                                {"ground", median_p99(ground).first}, {"detect", median_p99(detect).first},
                                {"verify", median_p99(verify).first}, {"track", median_p99(track).first}};
        io::Json objects = io::Json::array();
        for (const ObjectEstimate& o : r.keyframes.back().objects) {
            objects.push_back({{"id", o.id}, {"class", std::string(to_string(o.cls))}, {"box_world", io::to_json(o.box_world)}, {"existence", o.existence}});
        }
        j["final_objects"] = objects;
    }
    if (with_trajectory) {
        io::Json traj = io::Json::array();
        for (const Pose2& p : r.trajectory) traj.push_back({p.x_m, p.y_m, p.yaw_rad});
        j["trajectory_xyyaw"] = traj;
        io::Json believed = io::Json::array();
        for (const Pose2& p : r.estimated_trajectory) believed.push_back({p.x_m, p.y_m, p.yaw_rad});
        j["estimated_trajectory_xyyaw"] = believed;
    }
    return j;
}

io::Json aggregate_runs(const std::vector<eval::NavRunResult>& runs, const std::vector<std::string>& methods) {
    io::Json agg = io::Json::object();
    for (const std::string& m : methods) {
        int n = 0, success = 0, collisions = 0, near = 0, people = 0;
        double t = 0, risk = 0, dist = 0, spl = 0;
        std::vector<double> cycles, keyframe_ms, pose_error, pose_ate;
        eval::MapSanity sanity;
        for (const auto& r : runs) {
            if (r.method != m) continue;
            ++n;
            for (const auto& k : r.keyframe_timing) keyframe_ms.push_back(k.keyframe_ms());
            pose_error.push_back(r.final_pose_error_m);
            pose_ate.push_back(r.pose_ate_m);
            sanity.add(r.map_sanity);
            collisions += r.collisions;
            people += r.person_contacts;
            near += r.near_misses;
            spl += r.spl;
            cycles.insert(cycles.end(), r.cycle_ms.begin(), r.cycle_ms.end());
            if (!r.success) continue;
            ++success;
            t += r.time_s;
            risk += r.risk_time_s;
            dist += r.distance_m;
        }
        const double s = std::max(success, 1);
        const auto [median, p99] = median_p99(cycles);
        agg[m] = {{"runs", n},
                  {"success", success},
                  {"total_time_s_sum", t},
                  {"total_time_s_mean", t / s},
                  {"risk_time_s_sum", risk},
                  {"risk_time_s_mean", risk / s},
                  {"distance_m_sum", dist},
                  {"distance_m_mean", dist / s},
                  {"collisions", collisions},
                  {"person_contacts", people},
                  {"near_misses", near},
                  {"spl_mean", n ? spl / n : 0.0},
                  {"cycle_ms_median", median},
                  {"cycle_ms_p99", p99},
                  {"final_pose_error_m_median", pose_error.empty() ? 0.0 : percentile(pose_error, 0.5)},
                  {"final_pose_error_m_max", pose_error.empty() ? 0.0 : percentile(pose_error, 1.0)},
                  {"pose_ate_m_median", pose_ate.empty() ? 0.0 : percentile(pose_ate, 0.5)},
                  {"pose_ate_m_max", pose_ate.empty() ? 0.0 : percentile(pose_ate, 1.0)}};
        if (!keyframe_ms.empty()) {  // the online system's keyframe chain (front end to object map)
            agg[m]["keyframe_ms_median"] = median_p99(keyframe_ms).first;
            agg[m]["keyframe_ms_p99"] = median_p99(keyframe_ms).second;
            agg[m]["map_sanity"] = {{"object_frames", sanity.object_frames}, {"outside_room", sanity.outside_room},
                                    {"above_floor_0_3m", sanity.above_floor}, {"fast_unpushed_0_5mps", sanity.fast_unpushed},
                                    {"max_speed_mps", sanity.max_speed_mps}, {"max_bottom_m", sanity.max_bottom_m}};
        }
    }
    return agg;
}

std::string table_markdown(const io::Json& agg, const std::vector<std::string>& methods, int scenes) {
    std::string out = "| method | total time [s] (sum / mean) | risk time [s] (sum / mean) | distance [m] (sum / mean) | success | collisions | person contacts | near-misses | SPL |\n"
                      "| --- | --- | --- | --- | --- | --- | --- | --- | --- |\n";
    char line[512];
    for (const std::string& m : methods) {
        const io::Json& a = agg.at(m);
        std::snprintf(line, sizeof(line), "| %s | %.1f / %.1f | %.1f / %.2f | %.1f / %.2f | %d/%d | %d | %d | %d | %.2f |\n",
                      m.c_str(), a["total_time_s_sum"].get<double>(), a["total_time_s_mean"].get<double>(),
                      a["risk_time_s_sum"].get<double>(), a["risk_time_s_mean"].get<double>(),
                      a["distance_m_sum"].get<double>(), a["distance_m_mean"].get<double>(), a["success"].get<int>(),
                      scenes, a["collisions"].get<int>(), a["person_contacts"].get<int>(), a["near_misses"].get<int>(), a["spl_mean"].get<double>());
        out += line;
    }
    return out;
}

}  // namespace makeway::apps
