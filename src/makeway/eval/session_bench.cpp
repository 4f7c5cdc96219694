#include "makeway/eval/session_bench.hpp"

#include <chrono>

#include "makeway/eval/detection_dataset.hpp"
#include "makeway/eval/detection_eval.hpp"
#include "makeway/eval/label_bench.hpp"
#include "makeway/eval/scene_cad.hpp"
#include "makeway/sim/scene_generator.hpp"

namespace makeway::eval {
namespace {

using Clock = std::chrono::steady_clock;
double since(Clock::time_point t0) {
    return std::chrono::duration<double>(Clock::now() - t0).count();
}

void score(const perception::Detector& detector, const SessionBenchParams& p, SessionRound& round) {
    DetectionEvalParams ep;
    ep.scenes = p.eval_scenes;
    ep.left_out_styles = p.left_out_styles;
    ep.max_keyframes_per_scene = 30;
    ep.latency_keyframes = 1;
    const DetectionEvalResult r = run_detection_eval(detector, ep);
    round.left_out_map_25 = r.left_out.network.map_25;
    round.left_out_map_50 = r.left_out.network.map_50;
    round.held_out_map_25 = r.held_out.network.map_25;
    round.held_out_map_50 = r.held_out.network.map_50;
}

}  // namespace

SessionBenchParams::SessionBenchParams() {
    train.epochs = 6;
    train.learning_rate = 5e-4;  // fine-tuning: a quarter of training's peak
    train.batch_size = 8;
}

std::vector<SessionRound> run_session_bench(
    perception::Detector& detector, const SessionBenchParams& p,
    const std::function<void(const std::string&)>& progress) {
    auto say = [&](const std::string& what) {
        if (progress) progress(what);
    };
    std::vector<SessionRound> rounds(1);
    say("round 0: scoring the detector as given");
    score(detector, p, rounds[0]);
    // The replay: the trained styles, simulated and labelled by the simulator, as in training.
    say("replay data of the trained styles");
    DatasetParams replay_params;
    replay_params.scenes = p.replay_scenes;
    replay_params.seed = p.seed;
    replay_params.exclude_styles = p.left_out_styles;
    const std::vector<LabelledKeyframe> replay = generate_detection_dataset(replay_params);
    std::vector<LabelledKeyframe> auto_labels;
    labelling::LabelParams lp = p.label;
    lp.system.T_base_sensor = sim::RobotParams{}.T_robot_sensor();
    for (int r = 1; r <= p.rounds; ++r) {
        SessionRound round;
        round.round = r;
        auto t0 = Clock::now();
        for (int k = 0; k < p.scenes_per_round; ++k) {
            say("round " + std::to_string(r) + ": labelling room " + std::to_string(k + 1) +
                " of " + std::to_string(p.scenes_per_round));
            sim::SceneGenParams g;
            g.seed = 2'000'000 + p.seed + static_cast<std::uint64_t>(100 * r + k);
            g.density = k % 2 == 0 ? sim::Density::kMedium : sim::Density::kDense;
            sim::Scene base = sim::generate_scene(g);
            DatasetParams styles;
            styles.only_styles = p.left_out_styles;
            restyle_scene(base, styles);
            labelling::Labeller labeller(lp);
            try {
                drive_sessions(labeller, base, p.sessions, p.max_sweeps, g.seed * 7919, {});
            } catch (const std::runtime_error&) {
                continue;  // the restyled room has no route for the robot: another room next round
            }
            const verification::CadLibrary library = scene_cad_library(base);
            const labelling::LabelResult labels = labeller.finish(&library);
            std::size_t n = 0;
            for (const auto& session : labels.sessions) {
                for (const labelling::LabelledSessionKeyframe& kf : session) {
                    if (n++ % static_cast<std::size_t>(p.keyframe_stride) == 0)
                        auto_labels.push_back(kf.keyframe);
                }
            }
        }
        round.label_seconds = since(t0);
        for (const LabelledKeyframe& kf : auto_labels) round.labelled_objects += kf.objects.size();
        round.labelled_keyframes = auto_labels.size();
        say("round " + std::to_string(r) + ": fine-tuning on " +
            std::to_string(auto_labels.size()) + " auto-labelled and " +
            std::to_string(replay.size()) + " replayed keyframes");
        t0 = Clock::now();
        std::vector<perception::TrainingSample> samples;
        const std::vector<const std::vector<LabelledKeyframe>*> sets{&auto_labels, &replay};
        for (const std::vector<LabelledKeyframe>* set : sets) {
            for (const LabelledKeyframe& kf : *set) {
                perception::TrainingSample s;
                s.cloud_sensor = &kf.cloud_sensor;
                for (const LabelledObject& o : kf.objects)
                    s.boxes.emplace_back(o.cls, o.box_sensor);
                samples.push_back(std::move(s));
            }
        }
        perception::TrainParams tp = p.train;
        tp.seed = p.seed + static_cast<std::uint64_t>(r);
        perception::train_detector(detector, samples, tp);
        round.train_seconds = since(t0);
        say("round " + std::to_string(r) + ": scoring");
        score(detector, p, round);
        rounds.push_back(round);
    }
    return rounds;
}

}  // namespace makeway::eval
