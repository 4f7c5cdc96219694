#include "io/config_reader.hpp"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cmath>

#include "io/error.hpp"
#include "io/file_util.hpp"

namespace makeway::io {
namespace {

// Edit distance, for "did you mean" suggestions on misspelt keys.
std::size_t edit_distance(std::string_view a, std::string_view b) {
    std::vector<std::size_t> row(b.size() + 1);
    for (std::size_t j = 0; j <= b.size(); ++j) row[j] = j;
    for (std::size_t i = 1; i <= a.size(); ++i) {
        std::size_t diag = row[0];
        row[0] = i;
        for (std::size_t j = 1; j <= b.size(); ++j) {
            const std::size_t up = row[j];
            row[j] = std::min({row[j] + 1, row[j - 1] + 1, diag + (a[i - 1] != b[j - 1])});
            diag = up;
        }
    }
    return row[b.size()];
}

}  // namespace

struct YamlSection::Impl {
    YAML::Node node;
};

YamlSection::YamlSection(const YAML::Node& node, std::string prefix,
                         std::vector<std::string>& problems)
    : impl_(new Impl{node}), prefix_(std::move(prefix)), problems_(problems) {
    if (node && !node.IsNull() && !node.IsMap()) {
        problems_.push_back(prefix_ + ": must be a mapping of keys to values");
        impl_->node = YAML::Node();
    }
}

YamlSection::~YamlSection() { delete impl_; }

template <typename T>
void YamlSection::read_scalar(const char* key, T& value, const char* type_name) {
    known_keys_.emplace_back(key);
    if (!impl_->node || !impl_->node.IsMap()) return;
    const YAML::Node& node = impl_->node;
    const YAML::Node v = node[key];
    if (!v) return;
    try {
        if (!v.IsScalar()) throw YAML::Exception(YAML::Mark::null_mark(), "not a scalar");
        value = v.as<T>();
    } catch (const YAML::Exception&) {
        problems_.push_back(prefix_ + "." + key + ": must be " + type_name);
        return;
    }
    if constexpr (std::is_floating_point_v<T>) {
        if (std::isnan(value) || (!allow_infinity_ && !std::isfinite(value))) {
            problems_.push_back(prefix_ + "." + key + (allow_infinity_ ? ": must be a number or .inf" : ": must be finite"));
        }
    }
}

namespace {

// An enumeration written as one of its names ("must be a or b" otherwise).
template <typename E>
void read_choice(YamlSection& s, const char* key, E& value, const std::vector<std::pair<std::string, E>>& names) {
    std::string name;
    for (const auto& [n, v] : names) {
        if (v == value) name = n;
    }
    s.read(key, name);
    for (const auto& [n, v] : names) {
        if (n == name) {
            value = v;
            return;
        }
    }
    std::string list;
    for (std::size_t i = 0; i < names.size(); ++i) list += (i == 0 ? "" : i + 1 == names.size() ? " or " : ", ") + names[i].first;
    s.add_validation({std::string(key) + ": must be " + list});
}

}  // namespace

void YamlSection::read(const char* key, double& value) { read_scalar(key, value, "a number"); }
void YamlSection::read_or_infinity(const char* key, double& value) {
    double v = value;
    allow_infinity_ = true;
    read_scalar(key, v, "a number or .inf");
    allow_infinity_ = false;
    if (!std::isnan(v)) value = v;
}
void YamlSection::read(const char* key, int& value) { read_scalar(key, value, "an integer"); }
void YamlSection::read(const char* key, std::uint64_t& value) {
    read_scalar(key, value, "a non-negative integer");
}
void YamlSection::read(const char* key, bool& value) { read_scalar(key, value, "true or false"); }
void YamlSection::read(const char* key, std::string& value) { read_scalar(key, value, "a string"); }

void YamlSection::read(const char* key, std::uint32_t& value) {
    read_scalar(key, value, "a non-negative integer");
}

void YamlSection::read(const char* key, Eigen::Vector2d& value) {
    known_keys_.emplace_back(key);
    if (!impl_->node || !impl_->node.IsMap()) return;
    const YAML::Node& node = impl_->node;
    const YAML::Node v = node[key];
    if (!v) return;
    try {
        if (!v.IsSequence() || v.size() != 2) throw YAML::Exception(YAML::Mark::null_mark(), "");
        value = Eigen::Vector2d(v[0].as<double>(), v[1].as<double>());
    } catch (const YAML::Exception&) {
        problems_.push_back(prefix_ + "." + key + ": must be a pair of numbers [a, b]");
        return;
    }
    if (!value.allFinite()) problems_.push_back(prefix_ + "." + key + ": must be finite");
}

YAML::Node YamlSection::take(const char* key) {
    known_keys_.emplace_back(key);
    if (!impl_->node || !impl_->node.IsMap()) return YAML::Node();
    const YAML::Node& node = impl_->node;
    const YAML::Node v = node[key];
    return v ? v : YAML::Node();
}

void YamlSection::problem(const std::string& message) { problems_.push_back(prefix_ + ": " + message); }

void YamlSection::add_validation(const std::vector<std::string>& messages) {
    for (const auto& m : messages) problems_.push_back(prefix_ + "." + m);
}

void YamlSection::finish() {
    if (!impl_->node || !impl_->node.IsMap()) return;
    for (const auto& kv : impl_->node) {
        const std::string key = kv.first.as<std::string>("");
        if (std::find(known_keys_.begin(), known_keys_.end(), key) != known_keys_.end()) continue;
        std::string msg = prefix_ + "." + key + ": unknown key";
        const auto best = std::min_element(known_keys_.begin(), known_keys_.end(),
                                           [&](const auto& a, const auto& b) {
                                               return edit_distance(key, a) < edit_distance(key, b);
                                           });
        if (best != known_keys_.end() && edit_distance(key, *best) <= 2) {
            msg += " (did you mean '" + *best + "'?)";
        }
        problems_.push_back(msg);
    }
}

std::string join_problems(const std::vector<std::string>& problems) {
    std::string msg = problems.size() == 1 ? std::string() : std::to_string(problems.size()) + " problems: ";
    for (std::size_t i = 0; i < problems.size(); ++i) msg += (i ? "; " : "") + problems[i];
    return msg;
}

namespace {

// The online system's sections; each Params struct's validate() reports under its section.
void read_system(const YAML::Node& root, pipeline::SystemParams& sys, std::vector<std::string>& problems) {
    {
        YamlSection s(root["lidar_odometry"], "lidar_odometry", problems);
        odometry::OdometryParams& o = sys.odometry;
        s.read("enabled", sys.lidar_odometry);
        s.read("voxel_m", o.map.voxel_m);
        s.read("max_points_per_voxel", o.map.max_points_per_voxel);
        s.read("planarity", o.map.planarity);
        s.read("source_voxel_m", o.source_voxel_m);
        s.read("insert_voxel_m", o.insert_voxel_m);
        s.read("min_range_m", o.min_range_m);
        s.read("max_range_m", o.max_range_m);
        s.read("min_height_m", o.min_height_m);
        s.read("map_radius_m", o.map_radius_m);
        s.read("max_iterations", o.max_iterations);
        s.read("initial_threshold_m", o.initial_threshold_m);
        s.read("min_threshold_m", o.min_threshold_m);
        s.read("max_threshold_m", o.max_threshold_m);
        s.read("residual_sigma_m", o.residual_sigma_m);
        s.read("wheel_sigma_m", o.wheel_sigma_m);
        s.read("wheel_sigma_per_m", o.wheel_sigma_per_m);
        s.read("wheel_sigma_rad", o.wheel_sigma_rad);
        s.read("wheel_sigma_per_rad", o.wheel_sigma_per_rad);
        s.read("deskew", o.deskew);
        s.finish();
        if (sys.lidar_odometry) s.add_validation(o.validate());
    }
    {
        YamlSection s(root["perception"], "perception", problems);
        pipeline::KeyframeParams& k = sys.keyframe;
        s.read("keyframe_window", k.window);
        s.read("keyframe_every", k.every);
        s.read("deskew", k.deskew);
        s.read("ground_inlier_distance_m", k.ground.inlier_distance_m);
        s.read("ground_iterations", k.ground.iterations);
        s.read("ground_max_tilt_deg", k.ground.max_tilt_deg);
        s.read("ground_voxel_m", k.ground.voxel_m);
        s.read("ground_min_sensor_height_m", k.ground.min_sensor_height_m);
        s.read("ground_seed", k.ground.seed);
        s.read("ground_band_m", k.ground_filter.ground_band_m);
        s.read("ceiling_height_m", k.ground_filter.ceiling_height_m);
        s.finish();
        s.add_validation(k.validate());
    }
    {
        YamlSection s(root["verification"], "verification", problems);
        verification::VerifyParams& v = sys.verify;
        s.read("enabled", sys.verification);
        s.read("box_margin_m", v.box_margin_m);
        s.read("max_size_mismatch", v.max_size_mismatch);
        s.read("max_models", v.max_models);
        s.read("refined_candidates", v.refined_candidates);
        s.read("reseed_tolerance_m", v.reseed_tolerance_m);
        s.read("reseed_radius_m", v.reseed_radius_m);
        s.read("reseed_max_age_s", v.reseed_max_age_s);
        s.read("min_yaw_margin", v.min_yaw_margin);
        s.read("e_min_m", v.e_min_m);
        s.read("e_max_m", v.e_max_m);
        s.read("approx_e_max_m", v.approx_e_max_m);
        s.read("shape_e_max_m", v.shape_e_max_m);
        s.read("shape_match_distance_m", sys.shapes.match_distance_m);
        s.read("shape_max_views", sys.shapes.max_views);
        s.read("shape_view_margin_m", sys.shapes.view_margin_m);
        s.read("min_points", v.min_points);
        s.read("num_threads", v.num_threads);
        s.finish();
        s.add_validation(v.validate());
        s.add_validation(sys.shapes.validate());
    }
    {
        YamlSection s(root["tracking"], "tracking", problems);
        tracking::TrackerParams& t = sys.tracker;
        if (const YAML::Node classes = s.take("classes"); classes && !classes.IsNull()) {
            t.tracked_classes.fill(false);
            const bool is_list = classes.IsSequence() && classes.size() > 0;
            if (!is_list) s.add_validation({"classes: must be a list of class names, e.g. [chair, table]"});
            for (std::size_t i = 0; is_list && i < classes.size(); ++i) {
                const auto cls = parse_object_class(classes[i].IsScalar() ? classes[i].Scalar() : "");
                if (cls) t.tracked_classes[static_cast<std::size_t>(*cls)] = true;
                else s.add_validation({"classes: unknown class '" + (classes[i].IsScalar() ? classes[i].Scalar() : "?") + "' (the map knows chair, table)"});
            }
        }
        s.read("min_score", t.min_score);
        read_choice(s, "score_transform", t.score_transform, {{"none", tracking::ScoreTransform::kNone}, {"sigmoid", tracking::ScoreTransform::kSigmoid}});
        read_choice(s, "out_of_range", t.out_of_range, {{"freeze", tracking::OutOfRange::kFreeze}, {"drop", tracking::OutOfRange::kDrop}});
        s.read_or_infinity("max_unobserved_s", t.max_unobserved_s);
        s.read_or_infinity("max_floor_gap_m", t.max_floor_gap_m);
        s.read("merge_iou", t.merge_iou);
        s.read_or_infinity("motion_gate_sigma", t.motion_gate_sigma);
        for (ObjectClass c : kAllObjectClasses) {
            tracking::MotionPrior& m = t.motion[static_cast<std::size_t>(c)];
            const std::string name(to_string(c));
            const std::string decay = name + "_velocity_decay_s", speed = name + "_max_speed_mps", planar = name + "_planar",
                              displacement = name + "_min_displacement_m", window = name + "_motion_window_s";
            s.read_or_infinity(decay.c_str(), m.velocity_decay_s);
            s.read(speed.c_str(), m.max_speed_mps);
            s.read(planar.c_str(), m.planar);
            s.read(displacement.c_str(), m.min_displacement_m);
            s.read(window.c_str(), m.motion_window_s);
        }
        s.read("accel_sigma_mps2", t.kalman.accel_sigma_mps2);
        s.read("position_sigma_mps", t.kalman.position_sigma_mps);
        s.read("yaw_rate_sigma_radps", t.kalman.yaw_rate_sigma_radps);
        s.read("size_sigma_mps", t.kalman.size_sigma_mps);
        s.read("meas_position_sigma_m", t.kalman.meas_position_sigma_m);
        s.read("meas_yaw_sigma_rad", t.kalman.meas_yaw_sigma_rad);
        s.read("meas_size_sigma_m", t.kalman.meas_size_sigma_m);
        s.read("initial_velocity_sigma_mps", t.kalman.initial_velocity_sigma_mps);
        s.read("heading_votes_to_turn", t.kalman.heading_votes_to_turn);
        s.read("min_giou", t.min_giou);
        s.read("sensor_range_m", t.sensor_range_m);
        s.read("association_gate_m", t.association_gate_m);
        s.read("max_centre_distance_m", t.max_centre_distance_m);
        s.read("min_hits", t.min_hits);
        s.read("max_misses", t.max_misses);
        s.read("min_existence", t.min_existence);
        s.read("existence_grace_frames", t.existence_grace_frames);
        s.read("same_view_m", t.same_view_m);
        s.read("same_view_period_s", t.same_view_period_s);
        s.finish();
        s.add_validation(t.validate());
    }
    pipeline::NavigatorParams& n = sys.navigator;
    {
        YamlSection s(root["costmap"], "costmap", problems);
        s.read("low_obstacle_range_m", n.obstacle.low_mark_range_m);
        s.read("low_obstacle_min_returns", n.obstacle.low_min_returns);
        s.read("low_obstacle_min_share", n.obstacle.low_min_share);
        s.read("mark_range_m", n.obstacle.mark_range_m);
        s.read("clear_range_m", n.obstacle.clear_range_m);
        s.read("inflation_cost_scaling", n.inflation.cost_scaling);
        s.finish();
        s.add_validation(n.obstacle.validate());
        s.add_validation(n.inflation.validate());
    }
    {
        YamlSection s(root["planning"], "planning", problems);
        s.read("astar_cost_weight", n.astar.cost_weight);
        s.read("astar_allow_unknown", n.astar.allow_unknown);
        s.read("dwa_horizon_s", n.dwa.horizon_s);
        s.read("dwa_lookahead_m", n.dwa.lookahead_m);
        s.read("dwa_plan_envelope", n.dwa.plan_envelope);
        s.read("dwa_envelope_margin", n.dwa.envelope_margin);
        s.read("replan_period_s", n.replan_period_s);
        s.read("blocked_lookahead_m", n.blocked_lookahead_m);
        s.read("blocked_ignore_m", n.blocked_ignore_m);
        s.read("turn_target_index", n.turn_target_index);
        s.read("turn_rate_radps", n.turn_rate_radps);
        s.read("stuck_progress_m", n.stuck_progress_m);
        s.read("stuck_timeout_s", n.stuck_timeout_s);
        s.read("backup_speed_mps", n.backup_speed_mps);
        s.read("backup_duration_s", n.backup_duration_s);
        s.read("standstill_timeout_s", n.standstill_timeout_s);
        s.read("standstill_v_mps", n.standstill_v_mps);
        s.read("standstill_w_radps", n.standstill_w_radps);
        s.read("waypoint_tolerance_m", n.waypoint_tolerance_m);
        s.read("goal_tolerance_m", n.goal_tolerance_m);
        s.read("plan_to_tolerance", n.plan_to_tolerance);
        s.read("give_up_s", n.give_up_s);
        s.read("detour_ahead_m", n.detour_ahead_m);
        s.read("detour_radius_m", n.detour_radius_m);
        s.read("detour_memory_s", n.detour_memory_s);
        s.read("max_detours", n.max_detours);
        s.finish();
        s.add_validation(n.astar.validate());
        s.add_validation(n.dwa.validate());
        s.add_validation(n.validate_policy());
    }
    {
        YamlSection s(root["collision_monitor"], "collision_monitor", problems);
        planning::CollisionMonitorParams& m = n.monitor;
        s.read("enabled", m.enabled);
        s.read("latency_s", m.latency_s);
        s.read("min_points", m.min_points);
        s.read("stop_padding_m", m.stop_padding_m);
        s.read("slowdown_padding_m", m.slowdown_padding_m);
        s.read("slowdown_time_s", m.slowdown_time_s);
        s.read("slowdown_ratio", m.slowdown_ratio);
        s.read("time_before_collision_s", m.time_before_collision_s);
        s.read("simulation_time_step_s", m.simulation_time_step_s);
        s.read("dynamic_speed_mps", m.dynamic_speed_mps);
        s.read("dynamic_history", m.dynamic_history);
        s.read("dynamic_min_seen", m.dynamic_min_seen);
        s.read("low_edge_support", m.low_edge_support);
        s.read("dynamic_cluster_m", m.dynamic_cluster_m);
        s.read("dynamic_cluster_min_new", m.dynamic_cluster_min_new);
        s.read("dynamic_min_height_m", m.dynamic_min_height_m);
        s.read("dynamic_memory_s", m.dynamic_memory_s);
        s.read("dynamic_memory_range_m", m.dynamic_memory_range_m);
        s.read("dynamic_memory_min_new", m.dynamic_memory_min_new);
        s.read("dynamic_personal_space_m", m.dynamic_personal_space_m);
        s.read("personal_space_object_margin_m", m.personal_space_object_margin_m);
        s.read("min_scale", m.min_scale);
        s.read("lowest_beam_deg", m.lowest_beam_deg);
        s.read("blind_memory_s", m.blind_memory_s);
        s.read("object_footprints", m.object_footprints);
        s.read("object_moving_mps", m.object_moving_mps);
        s.read("object_lead_s", m.object_lead_s);
        s.read("max_range_m", m.max_range_m);
        s.read("recovery_after_s", m.recovery_after_s);
        s.read("backup_speed_mps", m.backup_speed_mps);
        s.read("backup_distance_m", m.backup_distance_m);
        s.read("rotate_speed_radps", m.rotate_speed_radps);
        s.read("rotate_angle_rad", m.rotate_angle_rad);
        s.finish();
        s.add_validation(m.validate());
    }
}

// The automatic annotation's section (labelling/labeller.hpp documents each parameter).
void read_labelling(const YAML::Node& node, labelling::LabelParams& l, std::vector<std::string>& problems) {
    YamlSection s(node, "labelling", problems);
    s.read("voxel_m", l.occupancy.voxel_m);
    s.read("end_margin_m", l.occupancy.end_margin_m);
    s.read("range_margin", l.occupancy.range_margin);
    s.read("min_free_sweeps", l.occupancy.min_free_sweeps);
    s.read("absent_hit_ratio", l.occupancy.absent_hit_ratio);
    s.read("dynamic_min_free", l.occupancy.dynamic_min_free);
    s.read("dynamic_hit_ratio", l.occupancy.dynamic_hit_ratio);
    s.read("trace_every", l.trace_every);
    s.read("trace_voxel_m", l.trace_voxel_m);
    s.read("map_voxel_m", l.map_voxel_m);
    s.read("dbscan_eps_m", l.dbscan.eps_m);
    s.read("dbscan_min_points", l.dbscan.min_points);
    s.read("dbscan_z_scale", l.dbscan_z_scale);
    s.read("min_cluster_points", l.min_cluster_points);
    s.read("min_object_points", l.min_object_points);
    s.read("min_object_height_m", l.min_object_height_m);
    s.read("max_object_height_m", l.max_object_height_m);
    s.read("max_object_length_m", l.max_object_length_m);
    s.read("movable_share", l.movable_share);
    s.read("min_coverage", l.min_coverage);
    s.read("max_seen_through", l.max_seen_through);
    s.read("max_splits", l.max_splits);
    s.read("split_share", l.split_share);
    s.read("split_distance_m", l.split_distance_m);
    s.read("duplicate_iou", l.duplicate_iou);
    s.read("cad_max_residual_m", l.verify.e_max_m);
    s.read("label_distance_m", l.label_distance_m);
    s.read("min_points", l.min_points);
    s.read("range_m", l.range_m);
    s.finish();
    labelling::LabelParams without_system = l;  // the system's sections report their own problems
    without_system.system = pipeline::SystemParams{};
    s.add_validation(without_system.validate());
}

}  // namespace

namespace {

YAML::Node parse_yaml_root(std::string_view yaml_text) {
    YAML::Node root;
    try {
        root = YAML::Load(std::string(yaml_text));
    } catch (const YAML::Exception& e) {
        throw FormatError("YAML syntax error at line " + std::to_string(e.mark.line + 1) + ": " +
                          e.msg);
    }
    if (root && !root.IsNull() && !root.IsMap()) {
        throw FormatError("the top level must be a mapping of section names");
    }
    return root;
}

void report_unknown_sections(const YAML::Node& root, std::vector<std::string>& problems) {
    std::vector<std::string> sections{"robot",        "affordance", "lidar_odometry",   "perception", "verification",
                                      "tracking",     "costmap",    "planning",         "collision_monitor",
                                      "labelling"};
    sections.insert(sections.end(), kSimulatorSections.begin(), kSimulatorSections.end());
    if (!root.IsMap()) return;
    for (const auto& kv : root) {
        const std::string name = kv.first.as<std::string>("");
        if (std::find(sections.begin(), sections.end(), name) == sections.end()) {
            problems.push_back(name + ": unknown section");
        }
    }
}

void read_config_sections(const YAML::Node& const_root, Config& cfg, std::vector<std::string>& problems) {
    {
        YamlSection s(const_root["robot"], "robot", problems);
        RobotDescription& r = cfg.robot;
        s.read("length_m", r.length_m);
        s.read("width_m", r.width_m);
        s.read("body_height_m", r.body_height_m);
        s.read("ground_clearance_m", r.ground_clearance_m);
        s.read("lidar_height_m", r.lidar_height_m);
        s.read("max_v_mps", r.max_v_mps);
        s.read("max_w_radps", r.max_w_radps);
        s.read("max_acc_mps2", r.max_acc_mps2);
        s.read("max_ang_acc_radps2", r.max_ang_acc_radps2);
        s.finish();
        s.add_validation(r.validate());
    }
    {
        YamlSection s(const_root["affordance"], "affordance", problems);
        costmap::AffordanceParams& a = cfg.affordance;
        s.read("min_existence", a.min_existence);
        {
            YamlSection c(s.take("chair"), "affordance.chair", problems);
            c.read("forward_back_m", a.chair.forward_back_m);
            c.read("side_m", a.chair.side_m);
            c.read("peak_cost", a.chair.peak_cost);
            c.read("edge_cost", a.chair.edge_cost);
            c.finish();
        }
        {
            YamlSection t(s.take("table"), "affordance.table", problems);
            t.read("sides_m", a.table.sides_m);
            t.read("ends_m", a.table.ends_m);
            t.read("square_tolerance_m", a.table.square_tolerance_m);
            t.read("peak_cost", a.table.peak_cost);
            t.read("edge_cost", a.table.edge_cost);
            t.finish();
        }
        s.finish();
        s.add_validation(a.validate());
    }
    read_system(const_root, cfg.system, problems);
    read_labelling(const_root["labelling"], cfg.labelling, problems);
    cfg.system.navigator.affordance = cfg.affordance;
}

}  // namespace

namespace detail {

void parse_into(std::string_view yaml_text, Config& config, const MoreSections& more) {
    const YAML::Node root = parse_yaml_root(yaml_text);
    std::vector<std::string> problems;
    report_unknown_sections(root, problems);
    read_config_sections(root, config, problems);
    if (more) more(root, problems);
    if (!problems.empty()) throw FormatError(join_problems(problems));
}

void load_into(const std::filesystem::path& path, Config& config, const MoreSections& more) {
    const std::string text = read_file(path, /*allow_empty=*/true);
    try {
        parse_into(text, config, more);
    } catch (const FormatError& e) {
        throw FileError(path.string(), e.what());
    }
}

}  // namespace detail

Config parse_config(std::string_view yaml_text) {
    Config config;
    detail::parse_into(yaml_text, config, {});
    return config;
}

Config load_config(const std::filesystem::path& path) {
    Config config;
    if (!path.empty()) detail::load_into(path, config, {});
    return config;
}

pipeline::SystemParams online_system_params(const Config& config, const Isometry3* T_base_sensor) {
    pipeline::SystemParams p = config.system;
    p.navigator.affordance = config.affordance;
    p.navigator.affordance_layer = true;
    pipeline::apply_robot(config.robot, p, T_base_sensor);
    return p;
}

}  // namespace makeway::io
