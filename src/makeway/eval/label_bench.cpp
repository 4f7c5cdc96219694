#include "makeway/eval/label_bench.hpp"

#include <chrono>
#include <deque>
#include <map>
#include <set>

#include "makeway/common/box_overlap.hpp"
#include "makeway/eval/keyframe_stages.hpp"
#include "makeway/eval/scene_cad.hpp"
#include "makeway/sim/route.hpp"
#include "makeway/sim/scene_dynamics.hpp"
#include "makeway/sim/scene_generator.hpp"

namespace makeway::eval {
namespace {

using labelling::PointClass;
using Clock = std::chrono::steady_clock;

PointClass truth_class(std::uint8_t label) {
    switch (static_cast<SemanticLabel>(label)) {
        case SemanticLabel::kGround:
            return PointClass::kGround;
        case SemanticLabel::kChair:
        case SemanticLabel::kTable:
            return PointClass::kMovable;
        case SemanticLabel::kPerson:
            return PointClass::kDynamic;
        default:
            return PointClass::kPermanent;
    }
}

// What the bench keeps of a keyframe's newest sweep to score the labels.
struct Sample {
    int session = 0;
    std::vector<Eigen::Vector3f>
        points_world;  ///< the session's own world (as the front end gave them)
    std::vector<std::uint8_t> label;
    std::vector<std::uint32_t> instance;
    LabelledKeyframe truth;  ///< truth boxes in the true sensor frame
    std::vector<OrientedBox>
        moving_boxes;  ///< chairs a person pulls during the session, same frame
    std::set<std::uint32_t> moving_ids;
};

}  // namespace

void drive_sessions(labelling::Labeller& labeller, const sim::Scene& base, int sessions,
                    int max_sweeps, std::uint64_t seed, const sim::OdometryNoiseParams& odometry,
                    const SessionFrameHook& on_frame) {
    for (int s = 0; s < sessions; ++s) {
        const sim::Scene scene = sim::make_session(base, s);
        const sim::RobotParams robot;
        const sim::CollisionChecker checker(scene, sim::models_of(scene), robot);
        const auto route = sim::drive_route(scene, checker, robot);
        if (!route) throw std::runtime_error("no route in " + scene.name);
        sim::SequenceParams sp;
        sp.seed = seed + static_cast<std::uint64_t>(s);
        sp.odometry = odometry;
        sim::SequenceSimulator simulator(scene, *route, sp);
        labeller.begin_session(simulator.start_pose());
        const auto feed = [&](sim::SimFrame& frame) {
            return labeller.add_sweep({frame.points_sensor, frame.stamp_s,
                                       sp.lidar.sweep_duration_s(), frame.odometry_pose,
                                       frame.odometry_end_pose});
        };
        for (int f = 0; f < max_sweeps && !simulator.reached_goal(); ++f) {
            sim::SimFrame frame = simulator.next();
            if (on_frame) {
                on_frame(s, scene, frame, feed);
            } else {
                feed(frame);
            }
        }
    }
}

std::array<double, labelling::kNumPointClasses> class_iou(
    const std::array<std::array<std::size_t, labelling::kNumPointClasses>,
                     labelling::kNumPointClasses>& confusion) {
    std::array<double, labelling::kNumPointClasses> iou{};
    for (int c = 0; c < labelling::kNumPointClasses; ++c) {
        std::size_t tp = confusion[c][c], fp = 0, fn = 0;
        for (int o = 0; o < labelling::kNumPointClasses; ++o) {
            if (o == c) continue;
            fn += confusion[c][o];
            fp += confusion[o][c];
        }
        const std::size_t d = tp + fp + fn;
        iou[c] = d ? static_cast<double>(tp) / static_cast<double>(d) : 0.0;
    }
    return iou;
}

void add_panoptic(const std::vector<std::uint32_t>& truth,
                  const std::vector<std::uint32_t>& predicted, std::size_t min_points,
                  PanopticQuality& pq) {
    std::map<std::uint32_t, std::size_t> n_truth, n_pred;
    std::map<std::pair<std::uint32_t, std::uint32_t>, std::size_t> both;
    for (std::size_t i = 0; i < truth.size() && i < predicted.size(); ++i) {
        if (truth[i]) ++n_truth[truth[i]];
        if (predicted[i]) ++n_pred[predicted[i]];
        if (truth[i] && predicted[i]) ++both[{truth[i], predicted[i]}];
    }
    std::map<std::uint32_t, bool> truth_matched, pred_matched;
    // IoU > 0.5 makes a match unique (Kirillov et al., theorem 1): no assignment problem.
    for (const auto& [key, inter] : both) {
        const std::size_t a = n_truth[key.first], b = n_pred[key.second];
        if (a < min_points || b < min_points) continue;
        const double iou = static_cast<double>(inter) / static_cast<double>(a + b - inter);
        if (iou <= 0.5) continue;
        ++pq.tp;
        pq.iou_sum += iou;
        truth_matched[key.first] = pred_matched[key.second] = true;
    }
    for (const auto& [id, n] : n_truth) {
        if (n >= min_points && !truth_matched[id]) ++pq.fn;
    }
    for (const auto& [id, n] : n_pred) {
        if (n >= min_points && !pred_matched[id]) ++pq.fp;
    }
}

LabelBenchResult run_label_bench(const LabelBenchParams& params,
                                 const std::function<void(int, int)>& progress) {
    LabelBenchResult result;
    std::vector<std::vector<Detection>> all_labels, all_still_labels;
    std::vector<std::vector<LabelledBox>> all_truth, all_still_truth;
    for (int k = 0; k < params.scenes; ++k) {
        sim::SceneGenParams g;
        g.seed = params.seed + static_cast<std::uint64_t>(k);
        g.density = k % 2 == 0 ? sim::Density::kMedium : sim::Density::kDense;
        const sim::Scene base = sim::generate_scene(g);
        LabelBenchScene row;
        row.name = base.name;
        labelling::LabelParams lp = params.label;
        const sim::SequenceParams sp_defaults;
        lp.system.T_base_sensor = sp_defaults.robot.T_robot_sensor();
        labelling::Labeller labeller(lp);
        std::vector<Sample> samples;
        double label_seconds = 0.0;
        // Truth visibility as the labeller's keyframes see it: points over the keyframe's window.
        std::deque<std::map<std::uint32_t, std::size_t>> window;
        drive_sessions(
            labeller, base, params.sessions, params.max_sweeps,
            params.seed * 7919 + static_cast<std::uint64_t>(k) * 31, params.odometry,
            [&](int s, const sim::Scene& scene, sim::SimFrame& frame,
                const std::function<pipeline::FrontEndResult(sim::SimFrame&)>& feed) {
                const auto t0 = Clock::now();
                Sample sample;
                sample.label = frame.points_sensor.label;
                sample.instance = frame.points_sensor.instance;
                std::map<std::uint32_t, std::size_t> sweep_points;
                for (std::size_t i = 0; i < sample.instance.size(); ++i) {
                    if (sample.instance[i] &&
                        sample.label[i] != static_cast<std::uint8_t>(SemanticLabel::kGround))
                        ++sweep_points[sample.instance[i]];
                }
                if (frame.index == 0) window.clear();
                window.push_back(std::move(sweep_points));
                if (window.size() > static_cast<std::size_t>(lp.system.keyframe.window))
                    window.pop_front();
                pipeline::FrontEndResult r = feed(frame);
                label_seconds += std::chrono::duration<double>(Clock::now() - t0).count();
                ++row.sweeps;
                if (!r.keyframe) return;
                ++row.keyframes;
                if (r.points_world.size() != sample.label.size())
                    throw std::logic_error("bench label: the front end reordered a sweep");
                sample.session = s;
                sample.points_world = std::move(r.points_world.xyz);
                std::map<std::uint32_t, std::size_t> points_of;
                for (const auto& counts : window) {
                    for (const auto& [id, n] : counts) points_of[id] += n;
                }
                const Isometry3 T_sensor_world = frame.T_world_sensor.inverse();
                for (const sim::ChairPusher& pusher : scene.pushers)
                    sample.moving_ids.insert(pusher.chair_id);
                for (const sim::ObjectState& o : frame.objects) {
                    const OrientedBox box = o.box_world.transformed(T_sensor_world);
                    if (sample.moving_ids.count(o.id)) sample.moving_boxes.push_back(box);
                    if (std::abs(box.centre_m.x()) > lp.range_m ||
                        std::abs(box.centre_m.y()) > lp.range_m)
                        continue;
                    const auto it =
                        std::find_if(scene.objects.begin(), scene.objects.end(),
                                     [&](const sim::SceneObject& so) { return so.id == o.id; });
                    const LabelledObject label{o.id, o.cls,
                                               it == scene.objects.end() ? "" : it->style, box,
                                               points_of[o.id]};
                    (label.points >= lp.min_points ? sample.truth.objects : sample.truth.unseen)
                        .push_back(label);
                }
                samples.push_back(std::move(sample));
            });
        const verification::CadLibrary library =
            params.cad ? scene_cad_library(base) : verification::CadLibrary{};
        const auto t0 = Clock::now();
        const labelling::LabelResult labels = labeller.finish(params.cad ? &library : nullptr);
        row.label_seconds =
            label_seconds + std::chrono::duration<double>(Clock::now() - t0).count();
        for (std::size_t s = 1; s < labels.reports.size(); ++s) {
            row.alignment_residual_m.push_back(labels.reports[s].alignment.residual_m);
            row.alignment_correction_m.push_back(labels.reports[s].alignment.correction_m);
        }
        for (const labelling::SessionReport& rep : labels.reports) {
            row.objects += rep.objects;
            row.cad_objects += rep.cad_objects;
            row.unknown_objects += rep.unknown_objects;
        }
        // Score: samples are in session order, keyframes in the same order as the labeller's.
        std::vector<std::size_t> next_keyframe(labels.sessions.size(), 0);
        std::vector<std::vector<Detection>> scene_labels, scene_still_labels;
        std::vector<std::vector<LabelledBox>> scene_truth, scene_still_truth;
        for (const Sample& sample : samples) {
            const std::vector<labelling::PointLabel> predicted =
                labeller.label_points(sample.session, sample.points_world);
            std::vector<std::uint32_t> truth_instance(sample.label.size(), 0),
                predicted_instance(sample.label.size(), 0);
            for (std::size_t i = 0; i < predicted.size(); ++i) {
                const PointClass t = truth_class(sample.label[i]);
                ++row.confusion[static_cast<std::size_t>(t)]
                               [static_cast<std::size_t>(predicted[i].cls)];
                // By motion (Thomas et al.'s definitions): what moves within the session is
                // Dynamic.
                const bool moving =
                    t == PointClass::kMovable && sample.moving_ids.count(sample.instance[i]);
                ++row.confusion_by_motion[static_cast<std::size_t>(
                    moving ? PointClass::kDynamic : t)][static_cast<std::size_t>(predicted[i].cls)];
                if (t == PointClass::kMovable) truth_instance[i] = sample.instance[i];
                if (predicted[i].instance && predicted[i].semantic != SemanticLabel::kClutter)
                    predicted_instance[i] = predicted[i].instance;
            }
            add_panoptic(truth_instance, predicted_instance, params.truth_min_points, row.panoptic);
            const labelling::LabelledSessionKeyframe& kf =
                labels.sessions[static_cast<std::size_t>(sample.session)]
                               [next_keyframe[static_cast<std::size_t>(sample.session)]++];
            std::vector<Detection> dets;
            for (const LabelledObject& o : kf.keyframe.objects) {
                Detection d;
                d.box_sensor = o.box_sensor;
                d.cls = o.cls;
                d.class_probabilities.fill(0.0);
                d.class_probabilities[static_cast<std::size_t>(o.cls)] = 1.0;
                d.score = std::min(
                    1.0, static_cast<double>(o.points) / 1000.0);  // better-seen labels first
                dets.push_back(d);
            }
            // Still objects only: the chairs pulled during the session are neither truth nor false
            // labels (a static label cannot hold an object that moves under it).
            LabelledKeyframe still = sample.truth;
            still.objects.erase(std::remove_if(still.objects.begin(), still.objects.end(),
                                               [&](const LabelledObject& o) {
                                                   return sample.moving_ids.count(o.id) > 0;
                                               }),
                                still.objects.end());
            std::vector<Detection> still_dets;
            for (const Detection& d : dets) {
                const bool on_moving = std::any_of(
                    sample.moving_boxes.begin(), sample.moving_boxes.end(),
                    [&](const OrientedBox& b) { return iou_bev(b, d.box_sensor) > 0.1; });
                if (!on_moving) still_dets.push_back(d);
            }
            scene_still_labels.push_back(std::move(still_dets));
            scene_still_truth.push_back(ground_truth_of(still));
            scene_labels.push_back(dets);
            scene_truth.push_back(ground_truth_of(sample.truth));
        }
        row.boxes = evaluate_detections(scene_labels, scene_truth);
        row.still_boxes = evaluate_detections(scene_still_labels, scene_still_truth);
        for (std::size_t i = 0; i < scene_labels.size(); ++i) {
            all_labels.push_back(std::move(scene_labels[i]));
            all_truth.push_back(std::move(scene_truth[i]));
            all_still_labels.push_back(std::move(scene_still_labels[i]));
            all_still_truth.push_back(std::move(scene_still_truth[i]));
        }
        for (int a = 0; a < labelling::kNumPointClasses; ++a) {
            for (int b = 0; b < labelling::kNumPointClasses; ++b) {
                result.confusion[a][b] += row.confusion[a][b];
                result.confusion_by_motion[a][b] += row.confusion_by_motion[a][b];
            }
        }
        result.panoptic.tp += row.panoptic.tp;
        result.panoptic.fp += row.panoptic.fp;
        result.panoptic.fn += row.panoptic.fn;
        result.panoptic.iou_sum += row.panoptic.iou_sum;
        result.scenes.push_back(std::move(row));
        if (progress) progress(k + 1, params.scenes);
    }
    result.iou = class_iou(result.confusion);
    result.iou_by_motion = class_iou(result.confusion_by_motion);
    result.boxes = evaluate_detections(all_labels, all_truth);
    result.still_boxes = evaluate_detections(all_still_labels, all_still_truth);
    return result;
}

}  // namespace makeway::eval
