#pragma once
// Learning affordance zones from observations of one building's furniture (issue 36): the same
// object matched across sessions, its motion between two observations expressed in its own frame
// at the earlier one, and the motions of each class binned into the weighted motions of a learned
// zone (costmap/learned_zone.hpp, where the zone itself is defined).
//
// Input is what the robot's own labelling gives (`makeway label`'s objects.json: every object of
// every session in the first session's frame, its class, and whether a CAD model fixed its facing);
// identities are not given, they are found: per pair of sessions, objects of one class are matched
// by the least total centre distance (Hungarian) among pairs whose footprints differ by at most
// `max_size_difference_m` and whose centres lie within `match_gate_m`.
#include <string>
#include <vector>

#include "makeway/common/oriented_box.hpp"
#include "makeway/common/semantic_label.hpp"
#include "makeway/costmap/learned_zone.hpp"

namespace makeway::zones {

/// One object as one session saw it.
struct SessionObject {
    int place = 0;    ///< one labelled place (one reference frame): only its sessions are compared
    int session = 0;  ///< sessions are compared pairwise; the numbers only tell them apart
    ObjectClass cls = ObjectClass::kChair;
    OrientedBox box_world;  ///< yaw = the object's forward (+x)
    /// Whether +x is the object's front (a CAD fit): a chair's PCA box may face backwards, and
    /// such chairs are left out (tables are symmetric and always used).
    bool facing_known = true;
};

struct ZoneLearnParams {
    double match_gate_m = 1.5;           ///< farther apart: not the same object
    double max_size_difference_m = 0.3;  ///< |dl| + |dw| of matched footprints at most this
    /// Matches less sure than this are left out. A match's confidence is how much nearer its
    /// partner is than the next candidate: 1 - d / d_next (1 when no other candidate is in the
    /// gate), on both sides, the lower of the two.
    double min_match_confidence = 0.0;
    double bin_m = 0.05;   ///< motions are binned to this ...
    double bin_deg = 5.0;  ///< ... and this, into the zone's weighted motions
    /// Symmetry: a chair is mirrored left to right (each motion counts half as itself, half
    /// mirrored); a table also front to back (quarters).
    bool symmetric = true;
    /// Each match counts both ways (a -> b and b -> a: a chair seen pulled out is as likely to be
    /// pushed back as a tucked one is to be pulled out); false: only from the lower session number
    /// to the higher (sessions numbered in time order).
    bool both_directions = true;
    costmap::LearnedZones zone;  ///< kernel, threshold and prior strength written with the zones
    std::vector<std::string> validate() const;
};

/// One matched pair of observations.
struct ObjectMotion {
    ObjectClass cls = ObjectClass::kChair;
    int place = 0, from_session = 0, to_session = 0;
    Pose2 motion;  ///< the later pose in the earlier object's frame
    double confidence = 1.0;
};

struct ClassLearning {
    std::size_t observations = 0;    ///< object observations of the class (all sessions)
    std::size_t motions = 0;         ///< motions used (both directions of each match, and tracked)
    std::size_t tracked = 0;         ///< of them: within-session motions of tracks
    std::size_t unmatched = 0;       ///< observations left without a partner in some other session
    std::size_t unsure = 0;          ///< matches below min_match_confidence
    std::size_t facing_unknown = 0;  ///< chairs left out: no CAD facing
    double mean_confidence = 0.0;    ///< over the matches used
    double moved_share = 0.0;        ///< motions of more than 5 cm or 5 deg
};

struct ZoneLearning {
    std::vector<ObjectMotion> motions;  ///< every match used, both directions
    ClassLearning chair, table;
    costmap::LearnedZones zones;
};

/// One object of the object map at one time (`makeway run`'s objects/ frames): the tracker's
/// identity, no matching needed.
struct TrackedObject {
    int place = 0;  ///< one recorded drive
    std::uint32_t track = 0;
    double stamp_s = 0.0;
    ObjectClass cls = ObjectClass::kChair;
    OrientedBox box_world;
};

/// Within-session motions of tracked objects: each track sampled every `gap_s` (its first
/// observation, then the first one at least gap_s later, ...), one motion per pair of consecutive
/// samples (confidence 1: the tracker's identity). A chair pushed and pulled while the robot
/// watches moves between samples; one that stands gives motions of (nearly) nothing.
std::vector<ObjectMotion> track_motions(const std::vector<TrackedObject>& objects, double gap_s);

/// Every pair of distinct sessions of a place (both ways unless params.both_directions is false):
/// the motion from one observation to the next of the same object; `more` (track_motions) joins
/// them as they are. Throws std::invalid_argument for invalid params.
ZoneLearning learn_zones(const std::vector<SessionObject>& objects, const ZoneLearnParams& params,
                         const std::vector<ObjectMotion>& more = {});

/// The weighted, binned motions of a list of motions (symmetrised as the params say).
costmap::ClassZone bin_motions(const std::vector<Pose2>& motions, ObjectClass cls,
                               const ZoneLearnParams& params);

}  // namespace makeway::zones
