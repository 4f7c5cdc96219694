#include "apps/nav_report.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>

#include "io/canvas.hpp"
#include "io/interrupt.hpp"
#include "io/nav_config.hpp"
#include "makeway/common/statistics.hpp"

namespace makeway::apps {
namespace {

constexpr std::uint64_t kBootstrapSeed = 0xB0075EEDULL;  // mixed with the benchmark's seed

io::Json interval_json(const MeanInterval& m) {
    return {{"mean", m.mean}, {"lo", m.lo}, {"hi", m.hi}, {"n", m.n}};
}

double avoidable_of(const io::Json& run) {
    const double risk = run["risk_time_s"].get<double>(),
                 unavoidable = run["unavoidable_risk_s"].get<double>();
    return unavoidable < 0.0 ? risk : std::max(0.0, risk - unavoidable);
}

const std::vector<std::pair<std::string, std::string>>& compared_pairs() {
    static const std::vector<std::pair<std::string, std::string>> kPairs{
        {"ours", "oppo"}, {"gt-perc", "oppo"}, {"ours", "gt-perc"}, {"con", "oppo"}};
    return kPairs;
}

// The runs' metrics that get intervals over successful runs, and their JSON keys (run_to_json
// writes avoidable_risk_s beside the risk it is derived from).
const std::vector<std::string>& success_metrics() {
    static const std::vector<std::string> kKeys{"total_time_s", "risk_time_s", "avoidable_risk_s",
                                                "distance_m"};
    return kKeys;
}

double metric_of(const io::Json& run, const std::string& key) { return run[key].get<double>(); }

}  // namespace

std::pair<double, double> median_p99(const std::vector<double>& v) {
    return {median(v), percentile(v, 0.99)};
}

eval::NavParams nav_params(const io::SimConfig& config) {
    eval::NavParams p = io::nav_params(config);
    p.on_sweep = io::throw_if_interrupted;  // Ctrl-C stops a run within one sweep
    return p;
}

io::Json run_to_json(const eval::NavRunResult& r, bool with_trajectory) {
    io::Json j = {{"method", r.method},
                  {"success", r.success},
                  {"reached_goal", r.reached_goal},
                  {"failure", r.failure},
                  {"total_time_s", r.time_s},
                  {"distance_m", r.distance_m},
                  {"risk_time_s", r.risk_time_s},
                  {"unavoidable_risk_s", r.unavoidable_risk_s},
                  {"collisions", r.collisions},
                  {"person_contacts", r.person_contacts},
                  {"near_misses", r.near_misses},
                  {"min_clearance_m", r.min_clearance_m},
                  {"shortest_m", r.shortest_m},
                  {"spl", r.spl},
                  {"replans", r.replans},
                  {"recoveries", r.recoveries},
                  {"final_pose_error_m", r.final_pose_error_m},
                  {"pose_ate_m", r.pose_ate_m},
                  {"stop_distance_m", r.stop_distance_m}};
    j["avoidable_risk_s"] = avoidable_of(j);
    // Contacts by kind and by who caused them; the collision monitor's cycles per action.
    auto contacts = [](const eval::ContactCounts& c) {
        return io::Json{{"robot_caused", c.robot_caused}, {"other_caused", c.other_caused}};
    };
    j["contacts"] = {{"walls", contacts(r.wall_contacts)},
                     {"furniture", contacts(r.furniture_contacts)},
                     {"people", contacts(r.people_contacts)}};
    j["robot_caused_contacts"] = r.wall_contacts.robot_caused + r.furniture_contacts.robot_caused +
                                 r.people_contacts.robot_caused;
    io::Json monitor = io::Json::object();
    for (int a = 0; a < planning::kMonitorActions; ++a)
        monitor[std::string(planning::to_string(static_cast<planning::MonitorAction>(a)))] = 0;
    for (const planning::MonitorAction a : r.monitor_actions)
        monitor[std::string(planning::to_string(a))] =
            monitor[std::string(planning::to_string(a))].get<int>() + 1;
    j["monitor_cycles"] = monitor;
    io::Json events = io::Json::array();
    for (const eval::ContactEvent& e : r.contact_events) {
        events.push_back({{"t_s", e.t_s},
                          {"kind", e.kind},
                          {"robot_caused", e.robot_caused},
                          {"toward_mps", e.toward_mps},
                          {"where_m", {e.where_m.x(), e.where_m.y()}}});
    }
    j["contact_events"] = events;
    if (!r.keyframes.empty()) {  // the online system: its keyframes, its map's sanity, its final
                                 // object map
        j["keyframes"] = r.keyframes.size();
        const eval::MapSanity& m = r.map_sanity;
        j["map_sanity"] = {
            {"object_frames", m.object_frames},  {"outside_room", m.outside_room},
            {"above_floor_0_3m", m.above_floor}, {"fast_unpushed_0_5mps", m.fast_unpushed},
            {"max_speed_mps", m.max_speed_mps},  {"max_bottom_m", m.max_bottom_m}};
        io::Json objects = io::Json::array();
        for (const ObjectEstimate& o : r.keyframes.back().objects) {
            objects.push_back({{"id", o.id},
                               {"class", std::string(to_string(o.cls))},
                               {"box_world", io::to_json(o.box_world)},
                               {"existence", o.existence}});
        }
        j["final_objects"] = objects;
    }
    if (with_trajectory) {
        io::Json traj = io::Json::array();
        // Poses to 10 um and 10 urad (full doubles made run.json twice as large for nothing).
        const auto micro = [](double x) { return std::round(x * 1e5) / 1e5; };
        for (const Pose2& p : r.trajectory)
            traj.push_back({micro(p.x_m), micro(p.y_m), micro(p.yaw_rad)});
        j["trajectory_xyyaw"] = traj;
        io::Json believed = io::Json::array();
        for (const Pose2& p : r.estimated_trajectory)
            believed.push_back({micro(p.x_m), micro(p.y_m), micro(p.yaw_rad)});
        j["estimated_trajectory_xyyaw"] = believed;
        io::Json reasons = io::Json::array();  // the collision monitor's action per control cycle
        for (const planning::MonitorAction a : r.monitor_actions)
            reasons.push_back(std::string(planning::to_string(a)));
        j["stop_reason"] = reasons;
        j["nav_state"] = r.nav_states;          // the navigator's own state per control cycle
        io::Json commands = io::Json::array();  // [v m/s, w rad/s] sent to the motors per control
                                                // cycle, to 1 mm/s and 1 mrad/s
        const auto milli = [](double x) { return std::round(x * 1e3) / 1e3; };
        for (const VelocityCommand& c : r.commands)
            commands.push_back({milli(c.v_mps), milli(c.w_radps)});
        j["command_vw"] = commands;
        io::Json risk = io::Json::array();  // time inside a true affordance zone per sweep period
        for (const double r_s : r.cycle_risk_s) risk.push_back(milli(r_s));
        j["risk_s"] = risk;
    }
    return j;
}

io::Json run_timing_json(const eval::NavRunResult& r) {
    const auto [median, p99] = median_p99(r.cycle_ms);
    io::Json j = {{"method", r.method},
                  {"cycle_ms_median", median},
                  {"cycle_ms_p99", p99},
                  {"monitor_ms_max", r.monitor_ms_max}};
    if (!r.keyframe_timing.empty()) {
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
        j["keyframe_ms_median"] = median_p99(chain).first;
        j["keyframe_ms_p99"] = median_p99(chain).second;
        j["stage_ms_median"] = {
            {"deskew", median_p99(deskew).first}, {"accumulate", median_p99(accumulate).first},
            {"ground", median_p99(ground).first}, {"detect", median_p99(detect).first},
            {"verify", median_p99(verify).first}, {"track", median_p99(track).first}};
        // Every keyframe's chain and stages (to 0.01 ms), so the summary pools the keyframes of
        // all runs: a run's own p99 is its slowest keyframe or two.
        const auto centi = [](const std::vector<double>& v) {
            io::Json a = io::Json::array();
            for (const double x : v) a.push_back(std::round(x * 100.0) / 100.0);
            return a;
        };
        j["keyframes_ms"] = {
            {"chain", centi(chain)},   {"deskew", centi(deskew)}, {"accumulate", centi(accumulate)},
            {"ground", centi(ground)}, {"detect", centi(detect)}, {"verify", centi(verify)},
            {"track", centi(track)}};
    }
    return j;
}

io::Json summarise_timing(const io::Json& timing, const std::vector<std::string>& methods) {
    io::Json out = io::Json::object();
    for (const std::string& m : methods) {
        std::vector<double> medians, p99s, kf_p99s;
        std::map<std::string, std::vector<double>> pooled;  // every keyframe of every run, by stage
        for (const io::Json& t : timing) {
            if (t["method"] != m) continue;
            medians.push_back(t["cycle_ms_median"].get<double>());
            p99s.push_back(t["cycle_ms_p99"].get<double>());
            if (t.contains("keyframe_ms_p99"))
                kf_p99s.push_back(t["keyframe_ms_p99"].get<double>());
            if (t.contains("keyframes_ms")) {
                for (const auto& [stage, values] : t["keyframes_ms"].items()) {
                    for (const io::Json& x : values) pooled[stage].push_back(x.get<double>());
                }
            }
        }
        out[m] = {{"cycle_ms_median", median(medians)}, {"cycle_ms_p99", percentile(p99s, 0.99)}};
        if (!kf_p99s.empty()) {
            // The keyframe chain over all keyframes pooled (what a robot sees: one keyframe in a
            // hundred slower than the p99), and the p99 of the runs' own p99s (near the slowest
            // keyframe of the benchmark; the statistic reported before the pooling).
            out[m]["keyframes"] = pooled["chain"].size();
            out[m]["keyframe_ms_median"] = median(pooled["chain"]);
            out[m]["keyframe_ms_p99"] = percentile(pooled["chain"], 0.99);
            out[m]["keyframe_ms_p99_of_runs_p99"] = percentile(kf_p99s, 0.99);
            io::Json stages = io::Json::object();
            for (const auto& [stage, values] : pooled) {
                if (stage != "chain")
                    stages[stage] = {{"median", median(values)}, {"p99", percentile(values, 0.99)}};
            }
            out[m]["stage_ms"] = stages;
        }
    }
    return out;
}

io::Json summarise_nav(const io::Json& header, const io::Json& runs) {
    const std::vector<std::string> methods = header["methods"].get<std::vector<std::string>>();
    const std::uint64_t seed = kBootstrapSeed ^ header["seed"].get<std::uint64_t>();
    // Per method, per scene index: the run.
    std::map<std::string, std::map<int, const io::Json*>> by_method;
    for (const io::Json& r : runs)
        by_method[r["method"].get<std::string>()][r["scene_index"].get<int>()] = &r;
    io::Json agg = io::Json::object();
    for (const std::string& m : methods) {
        int n = 0, success = 0, collisions = 0, near = 0, people = 0;
        double t = 0, risk = 0, avoidable = 0, unavoidable = 0, dist = 0, spl = 0;
        std::vector<double> pose_error, pose_ate, success_flags, collision_counts;
        std::map<std::string, std::vector<double>> values;  // over successful runs
        eval::MapSanity sanity;
        io::Json contacts = {{"walls", {{"robot_caused", 0}, {"other_caused", 0}}},
                             {"furniture", {{"robot_caused", 0}, {"other_caused", 0}}},
                             {"people", {{"robot_caused", 0}, {"other_caused", 0}}}};
        io::Json monitor = io::Json::object();
        int robot_caused = 0;
        bool online = false;
        for (const auto& [scene, rp] : by_method[m]) {
            const io::Json& r = *rp;
            ++n;
            pose_error.push_back(r["final_pose_error_m"].get<double>());
            pose_ate.push_back(r["pose_ate_m"].get<double>());
            collisions += r["collisions"].get<int>();
            people += r["person_contacts"].get<int>();
            near += r["near_misses"].get<int>();
            if (r.contains("contacts")) {
                for (auto& [kind, c] : contacts.items()) {
                    for (auto& [who, count] : c.items())
                        count = count.get<int>() + r["contacts"][kind][who].get<int>();
                }
                robot_caused += r["robot_caused_contacts"].get<int>();
                for (const auto& [action, cycles] : r["monitor_cycles"].items())
                    monitor[action] = monitor.value(action, 0) + cycles.get<int>();
            }
            spl += r["spl"].get<double>();
            success_flags.push_back(r["success"].get<bool>() ? 1.0 : 0.0);
            collision_counts.push_back(r["collisions"].get<double>());
            if (r.contains("map_sanity")) {
                online = true;
                const io::Json& s = r["map_sanity"];
                eval::MapSanity one;
                one.object_frames = s["object_frames"].get<std::size_t>();
                one.outside_room = s["outside_room"].get<std::size_t>();
                one.above_floor = s["above_floor_0_3m"].get<std::size_t>();
                one.fast_unpushed = s["fast_unpushed_0_5mps"].get<std::size_t>();
                one.max_speed_mps = s["max_speed_mps"].get<double>();
                one.max_bottom_m = s["max_bottom_m"].get<double>();
                sanity.add(one);
            }
            if (!r["success"].get<bool>()) continue;
            ++success;
            t += r["total_time_s"].get<double>();
            risk += r["risk_time_s"].get<double>();
            avoidable += r["avoidable_risk_s"].get<double>();
            unavoidable += std::max(0.0, r["unavoidable_risk_s"].get<double>());
            dist += r["distance_m"].get<double>();
            for (const std::string& key : success_metrics())
                values[key].push_back(metric_of(r, key));
        }
        const double s = std::max(success, 1);
        io::Json a = {{"runs", n},
                      {"success", success},
                      {"total_time_s_sum", t},
                      {"total_time_s_mean", t / s},
                      {"risk_time_s_sum", risk},
                      {"risk_time_s_mean", risk / s},
                      {"avoidable_risk_s_sum", avoidable},
                      {"avoidable_risk_s_mean", avoidable / s},
                      {"unavoidable_risk_s_sum", unavoidable},
                      {"distance_m_sum", dist},
                      {"distance_m_mean", dist / s},
                      {"collisions", collisions},
                      {"person_contacts", people},
                      {"near_misses", near},
                      {"contacts", contacts},
                      {"robot_caused_contacts", robot_caused},
                      {"monitor_cycles", monitor},
                      {"spl_mean", n ? spl / n : 0.0},
                      {"final_pose_error_m_median", percentile(pose_error, 0.5)},
                      {"final_pose_error_m_max", percentile(pose_error, 1.0)},
                      {"pose_ate_m_median", percentile(pose_ate, 0.5)},
                      {"pose_ate_m_max", percentile(pose_ate, 1.0)}};
        io::Json ci = {
            {"success_rate", interval_json(bootstrap_mean(success_flags, seed))},
            {"collisions_per_run", interval_json(bootstrap_mean(collision_counts, seed))}};
        for (const std::string& key : success_metrics())
            ci[key] = interval_json(bootstrap_mean(values[key], seed));
        a["interval_95"] = ci;
        if (online) {
            a["map_sanity"] = {{"object_frames", sanity.object_frames},
                               {"outside_room", sanity.outside_room},
                               {"above_floor_0_3m", sanity.above_floor},
                               {"fast_unpushed_0_5mps", sanity.fast_unpushed},
                               {"max_speed_mps", sanity.max_speed_mps},
                               {"max_bottom_m", sanity.max_bottom_m}};
        }
        agg[m] = a;
    }
    // Paired differences: the same scenes, both methods successful (success: every scene).
    io::Json paired = io::Json::array();
    for (const auto& [a, b] : compared_pairs()) {
        if (!by_method.count(a) || !by_method.count(b)) continue;
        std::map<std::string, std::vector<double>> diffs;
        std::vector<double> success_diff, a_avoid, b_avoid, a_time, b_time;
        for (const auto& [scene, ra] : by_method[a]) {
            const auto it = by_method[b].find(scene);
            if (it == by_method[b].end()) continue;
            const io::Json &x = *ra, &y = *it->second;
            success_diff.push_back((x["success"].get<bool>() ? 1.0 : 0.0) -
                                   (y["success"].get<bool>() ? 1.0 : 0.0));
            if (!x["success"].get<bool>() || !y["success"].get<bool>()) continue;
            for (const std::string& key : success_metrics())
                diffs[key].push_back(metric_of(x, key) - metric_of(y, key));
            a_avoid.push_back(x["avoidable_risk_s"].get<double>());
            b_avoid.push_back(y["avoidable_risk_s"].get<double>());
            a_time.push_back(x["total_time_s"].get<double>());
            b_time.push_back(y["total_time_s"].get<double>());
        }
        io::Json d = {{"a", a},
                      {"b", b},
                      {"scenes_both_successful", a_time.size()},
                      {"success", interval_json(bootstrap_mean(success_diff, seed))}};
        for (const std::string& key : success_metrics())
            d[key] = interval_json(bootstrap_mean(diffs[key], seed));
        auto sum = [](const std::vector<double>& v) {
            return std::accumulate(v.begin(), v.end(), 0.0);
        };
        d["avoidable_risk_ratio"] =
            sum(b_avoid) > 0.0 ? sum(a_avoid) / sum(b_avoid) : 0.0;  // a's over b's, same scenes
        d["total_time_ratio"] = sum(b_time) > 0.0 ? sum(a_time) / sum(b_time) : 0.0;
        paired.push_back(d);
    }
    io::Json out = header;
    out["aggregate"] = agg;
    out["paired"] = paired;
    out["runs"] = runs;
    return out;
}

std::string nav_table_markdown(const io::Json& summary) {
    const auto methods = summary["methods"].get<std::vector<std::string>>();
    const int scenes = summary["scenes"].get<int>();
    auto ci = [](const io::Json& i, const char* fmt) {
        char buf[128];
        std::snprintf(buf, sizeof(buf), fmt, i["mean"].get<double>(), i["lo"].get<double>(),
                      i["hi"].get<double>());
        return std::string(buf);
    };
    std::string out =
        "| method | total time [s] (sum / mean) | risk time [s] (sum / mean) | distance [m] (sum / "
        "mean) | success | collisions | person contacts "
        "| robot-caused contacts (walls / furniture / people) | other-caused contacts (walls / "
        "furniture / people) | near-misses | SPL "
        "| total time mean [95 % CI] | risk time mean [95 % CI] | avoidable risk mean [95 % CI] | "
        "unavoidable risk sum [s] | success rate [95 % CI] |\n"
        "| --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- "
        "| --- |\n";
    char line[1024];
    for (const std::string& m : methods) {
        const io::Json& a = summary["aggregate"].at(m);
        const io::Json& i = a["interval_95"];
        const io::Json& c = a["contacts"];
        auto who = [&](const char* k) {
            return std::to_string(c["walls"][k].get<int>()) + " / " +
                   std::to_string(c["furniture"][k].get<int>()) + " / " +
                   std::to_string(c["people"][k].get<int>());
        };
        std::snprintf(line, sizeof(line),
                      "| %s | %.1f / %.1f | %.1f / %.2f | %.1f / %.2f | %d/%d | %d | %d | %s | %s "
                      "| %d | %.2f | %s | %s | %s | %.1f | %s |\n",
                      m.c_str(), a["total_time_s_sum"].get<double>(),
                      a["total_time_s_mean"].get<double>(), a["risk_time_s_sum"].get<double>(),
                      a["risk_time_s_mean"].get<double>(), a["distance_m_sum"].get<double>(),
                      a["distance_m_mean"].get<double>(), a["success"].get<int>(), scenes,
                      a["collisions"].get<int>(), a["person_contacts"].get<int>(),
                      who("robot_caused").c_str(), who("other_caused").c_str(),
                      a["near_misses"].get<int>(), a["spl_mean"].get<double>(),
                      ci(i["total_time_s"], "%.1f [%.1f, %.1f]").c_str(),
                      ci(i["risk_time_s"], "%.2f [%.2f, %.2f]").c_str(),
                      ci(i["avoidable_risk_s"], "%.2f [%.2f, %.2f]").c_str(),
                      a["unavoidable_risk_s_sum"].get<double>(),
                      ci(i["success_rate"], "%.3f [%.3f, %.3f]").c_str());
        out += line;
    }
    if (!summary["paired"].empty()) {
        out +=
            "\nPaired differences (a - b) on the same scenes, where both succeeded (success: every "
            "scene); mean [95 % bootstrap CI]:\n\n"
            "| a - b | scenes | total time [s] | risk time [s] | avoidable risk [s] | distance [m] "
            "| success rate | avoidable risk a / b | total time a / b |\n"
            "| --- | --- | --- | --- | --- | --- | --- | --- | --- |\n";
        for (const io::Json& d : summary["paired"]) {
            std::snprintf(
                line, sizeof(line), "| %s - %s | %zu | %s | %s | %s | %s | %s | %.3f | %.3f |\n",
                d["a"].get<std::string>().c_str(), d["b"].get<std::string>().c_str(),
                d["scenes_both_successful"].get<std::size_t>(),
                ci(d["total_time_s"], "%+.2f [%+.2f, %+.2f]").c_str(),
                ci(d["risk_time_s"], "%+.2f [%+.2f, %+.2f]").c_str(),
                ci(d["avoidable_risk_s"], "%+.2f [%+.2f, %+.2f]").c_str(),
                ci(d["distance_m"], "%+.2f [%+.2f, %+.2f]").c_str(),
                ci(d["success"], "%+.3f [%+.3f, %+.3f]").c_str(),
                d["avoidable_risk_ratio"].get<double>(), d["total_time_ratio"].get<double>());
            out += line;
        }
    }
    return out;
}

void write_risk_time_plot(const std::filesystem::path& path, const io::Json& summary) {
    // Data space mapped onto a 10 x 6 "metre" canvas: x = total time, y = risk time.
    double t_max = 10.0, r_max = 1.0;
    for (const io::Json& r : summary["runs"]) {
        if (!r["success"].get<bool>()) continue;
        t_max = std::max(t_max, r["total_time_s"].get<double>());
        r_max = std::max(r_max, r["risk_time_s"].get<double>());
    }
    t_max = 10.0 * std::ceil(t_max / 10.0);
    r_max = 2.0 * std::ceil(r_max / 2.0);
    constexpr double W = 10.0, H = 6.0;
    io::Canvas canvas({-1.2, -1.0}, {W + 0.2, H + 1.2}, 100.0, 0.0);
    const io::Rgb axis{0.2, 0.2, 0.2}, grid{0.88, 0.88, 0.88};
    auto to_canvas = [&](double t, double r) {
        return Eigen::Vector2d(W * t / t_max, H * r / r_max);
    };
    for (int k = 0; k <= 5; ++k) {
        const double t = t_max * k / 5, r = r_max * k / 5;
        canvas.stroke_polyline({to_canvas(t, 0), to_canvas(t, r_max)}, grid, 1.0);
        canvas.stroke_polyline({to_canvas(0, r), to_canvas(t_max, r)}, grid, 1.0);
        char buf[32];
        std::snprintf(buf, sizeof(buf), "%.0f", t);
        canvas.text(to_canvas(t, 0) + Eigen::Vector2d(-0.1, -0.35), buf, 14, axis);
        std::snprintf(buf, sizeof(buf), "%.1f", r);
        canvas.text(to_canvas(0, r) + Eigen::Vector2d(-0.6, -0.05), buf, 14, axis);
    }
    canvas.stroke_polyline({to_canvas(0, r_max), to_canvas(0, 0), to_canvas(t_max, 0)}, axis, 2.0);
    canvas.text({W / 2 - 1.0, -0.85}, "total time [s]", 16, axis);
    canvas.text({-1.15, H + 0.3}, "risk time [s]", 16, axis);
    const std::map<std::string, io::Rgb> colours{{"con", {0.45, 0.45, 0.45}},
                                                 {"oppo", {0.85, 0.2, 0.15}},
                                                 {"gt-perc", {0.15, 0.45, 0.85}},
                                                 {"ours", {0.1, 0.65, 0.25}}};
    const auto methods = summary["methods"].get<std::vector<std::string>>();
    for (std::size_t k = 0; k < methods.size(); ++k) {
        const io::Rgb c =
            colours.count(methods[k]) ? colours.at(methods[k]) : io::Rgb{0.5, 0.3, 0.6};
        for (const io::Json& r : summary["runs"]) {
            if (r["method"] != methods[k] || !r["success"].get<bool>()) continue;
            canvas.dot(to_canvas(r["total_time_s"].get<double>(), r["risk_time_s"].get<double>()),
                       5.0, c);
        }
        const Eigen::Vector2d legend(0.3 + 2.4 * static_cast<double>(k), H + 0.75);
        canvas.dot(legend, 8.0, c);
        canvas.text(legend + Eigen::Vector2d(0.15, -0.08), methods[k], 16, axis);
    }
    char title[160];
    std::snprintf(title, sizeof(title), "per-scene risk vs time, %d scenes (successful runs)",
                  summary["scenes"].get<int>());
    canvas.text({W / 2 - 3.0, H + 0.3}, title, 16, axis);
    canvas.save_png(path);
}

}  // namespace makeway::apps
