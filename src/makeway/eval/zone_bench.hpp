#pragma once
// `makeway bench zones` (issue 36): affordance zones learned from K sessions of a building against
// the paper's hand-drawn zones, on where the furniture actually goes in the next sessions.
//
// Per scene (a building with a usage profile, sim/scene.hpp): sessions 0..K-1 are learned from
// (the sessions' boxes with their identities hidden: the learner matches them itself), sessions
// K..K+M-1 are predicted. Each object's zone is placed where the object stood in session K-1; its
// footprint cells in each later session are the truth. Coverage is the share of those cells inside
// the zone, for the hand-drawn zone and for the learned zone cut to the same area (its cells ranked
// by how often the footprint goes there), so neither wins by being larger; the learned zone at its
// own threshold is reported with its area.
#include <functional>
#include <string>
#include <vector>

#include "makeway/costmap/affordance.hpp"
#include "makeway/sim/scene.hpp"
#include "makeway/zones/zone_learning.hpp"

namespace makeway::eval {

/// What the zones are learned from: the sessions' true boxes (identities hidden), or the robot's
/// own labelling of its drives (`makeway label`: each training session driven, the labeller with
/// the scene's CAD models), as a user would learn them.
enum class ZoneSource { kTruth, kLabels };

struct ZoneBenchParams {
    int scenes = 6;
    ZoneSource source = ZoneSource::kTruth;
    int max_sweeps = 400;  ///< per labelled session
    /// > 0 (truth only): each training session's objects also tracked over its first
    /// `track_duration_s` (the scenes' chair pushers at work) and sampled every this many seconds,
    /// as `learn-zones --tracks` learns from a drive's object map; 0: sessions alone.
    double track_gap_s = 0.0;
    double track_duration_s = 60.0;
    std::uint64_t seed = 0;
    sim::UsageProfile usage = sim::UsageProfile::kPulledBack;
    int train_sessions = 5;  ///< K
    int test_sessions = 5;   ///< M
    double cell_m = 0.05;
    zones::ZoneLearnParams learn;
    costmap::AffordanceParams hand_drawn;
};

/// Footprint cells of later sessions and how many of them each zone holds; zone areas [cells].
struct ZoneCoverage {
    double truth_cells = 0.0;
    double in_hand_drawn = 0.0, in_learned_equal_area = 0.0, in_learned = 0.0;
    double hand_drawn_area = 0.0, learned_area = 0.0;  ///< summed over the zones placed
    std::size_t objects = 0;
    ZoneCoverage& operator+=(const ZoneCoverage& o);
    double hand_drawn() const { return truth_cells > 0 ? in_hand_drawn / truth_cells : 0.0; }
    double learned_equal_area() const {
        return truth_cells > 0 ? in_learned_equal_area / truth_cells : 0.0;
    }
    double learned() const { return truth_cells > 0 ? in_learned / truth_cells : 0.0; }
};

struct ZoneBenchScene {
    std::string name;
    ZoneCoverage chair, table;
    ZoneCoverage chair_moved, table_moved;  ///< only where the object moved (> 5 cm or 5 deg)
    zones::ClassLearning chair_learning, table_learning;
    double learn_seconds = 0.0;
    double label_seconds = 0.0;  ///< driving and labelling the training sessions (labels only)
};

struct ZoneBenchResult {
    std::vector<ZoneBenchScene> scenes;
    ZoneBenchScene total;          ///< sums over the scenes
    costmap::LearnedZones pooled;  ///< learned from every scene's K sessions together
};

/// The scenes are generated (densities cycle medium, dense; seed + i) with params.usage.
/// `progress(done, total)` after each scene.
ZoneBenchResult run_zone_bench(const ZoneBenchParams& params,
                               const std::function<void(std::size_t, std::size_t)>& progress = {});

/// Sessions 0..kProfileSessions-1 of a scene are the truth profile_zones draws.
constexpr int kProfileSessions = 24;

/// The scene's own usage profile as zones (no prior): the motions between every pair of `sessions`
/// sessions drawn by sim::make_session, identities known. The truth `bench nav --risk-zones
/// truth-profile` scores against.
costmap::LearnedZones profile_zones(const sim::Scene& scene, int sessions = kProfileSessions,
                                    const zones::ZoneLearnParams& binning = {});

/// What a robot learns of its own building before it drives there (`bench nav --zones-sessions`):
/// zones learned as `learn-zones` learns them from the boxes of `sessions` sessions of the scene
/// with their identities hidden (matched by the learner, as bench zones' truth source). They are
/// sessions kProfileSessions, kProfileSessions + 1, ...: never one that profile_zones' truth
/// holds, so the prediction is not scored on its own data. Throws std::invalid_argument for
/// sessions < 2 (one session has no motion).
costmap::LearnedZones building_zones(const sim::Scene& scene, int sessions,
                                     const zones::ZoneLearnParams& learn = {});

}  // namespace makeway::eval
