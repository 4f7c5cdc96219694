#pragma once
// `makeway bench sessions`: the paper's claim that perception improves from session to session.
// A detector trained without some styles (the left-out set) meets rooms furnished with them: each
// round drives new rooms in several sessions, auto-labels them (labelling::Labeller with the rooms'
// CAD models, no simulator truth), fine-tunes the detector on everything labelled so far plus a
// replay of its original training styles (so that it does not forget them), and scores it: the
// network's mAP on held-out scenes of the left-out styles, and on held-out scenes of the styles it
// was trained on (which must not drop).
#include <functional>
#include <string>
#include <vector>

#include "makeway/labelling/labeller.hpp"
#include "makeway/perception/detector.hpp"
#include "makeway/sim/sequence.hpp"

namespace makeway::eval {

struct SessionBenchParams {
    int rounds = 2;
    int scenes_per_round = 4;
    int sessions = 3;
    int max_sweeps = 300;  ///< per session
    std::uint64_t seed = 0;
    /// The styles the detector never saw: the default detector's two (armchair, round table) and
    /// two of the wider world (lounge chair, pedestal cafe table).
    std::vector<std::string> left_out_styles{"armchair", "round_table", "lounge_chair",
                                             "pedestal_table"};
    int eval_scenes = 3;      ///< held-out scenes per set (seeds from 1,000,000)
    int replay_scenes = 16;   ///< simulated scenes of the trained styles mixed into fine-tuning
    int keyframe_stride = 2;  ///< every n-th auto-labelled keyframe is trained on
    perception::TrainParams train;  ///< fine-tuning (epochs, learning rate)
    labelling::LabelParams label;
    SessionBenchParams();
};

struct SessionRound {
    int round = 0;                                             ///< 0: before any auto-labels
    std::size_t labelled_keyframes = 0, labelled_objects = 0;  ///< trained on so far (auto-labels)
    double left_out_map_25 = 0.0, left_out_map_50 = 0.0;
    double held_out_map_25 = 0.0, held_out_map_50 = 0.0;
    double label_seconds = 0.0, train_seconds = 0.0;
};

/// `detector` is fine-tuned in place. `progress(what)` names each step as it starts.
std::vector<SessionRound> run_session_bench(
    perception::Detector& detector, const SessionBenchParams& params,
    const std::function<void(const std::string&)>& progress = {});

}  // namespace makeway::eval
