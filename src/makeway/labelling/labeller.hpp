#pragma once
// The paper's automatic annotation ("Data Annotation", six steps) over recorded sessions of one
// place: (1) each session's sweeps through the online system's front end (LiDAR odometry with the
// wheels, keyframes, ground plane) and the session aligned to the first session's map; (2) every
// point classified Ground / Permanent / Movable / Dynamic by ray tracing through the multi-session
// occupancy map; (3) DBSCAN on each session's map without its Ground and Dynamic points; (4) an
// upright PCA box per cluster; (5) the verification stage's 4-DoF ICP aligns every CAD model to
// the cluster, keeping the yaw, the model's box and class (a cluster the best model leaves half
// unexplained is split and its rest clustered again); clusters that fit no model keep their PCA
// box, and a class from `classify_unknown` (the previous session's detector) when one is given,
// else stay unknown and out of training; (6) every keyframe point labelled by its distance to the
// aligned model's surface (beyond label_distance_m: not the object's).
//
// Input is what a robot records: sweeps with per-point time and wheel odometry, each session's
// start pose. Any other channel of the sweeps (a simulator's labels) is dropped on entry.
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "makeway/common/labelled_keyframe.hpp"
#include "makeway/labelling/dbscan.hpp"
#include "makeway/labelling/occupancy.hpp"
#include "makeway/labelling/session_align.hpp"
#include "makeway/pipeline/front_end.hpp"
#include "makeway/verification/cad_library.hpp"
#include "makeway/verification/verifier.hpp"

namespace makeway::labelling {

struct LabelParams {
    pipeline::SystemParams system;  ///< the front end's (odometry, keyframes, ground removal)
    SessionAlignParams align;
    OccupancyParams occupancy;
    int trace_every = 1;          ///< every n-th sweep is ray traced
    double trace_voxel_m = 0.05;  ///< a traced sweep keeps one return per voxel
    double map_voxel_m = 0.04;    ///< session maps (clustering) keep one point per voxel
    DbscanParams dbscan{0.10, 6};
    double dbscan_z_scale = 1.0;  ///< heights are scaled by this before clustering
    std::size_t min_cluster_points = 25;
    /// An object needs this many map points (a fitted one: this many within label_distance_m of
    /// its model): the fragments a moved or pulled chair leaves behind fit a stool's small model.
    std::size_t min_object_points = 120;
    double min_object_height_m = 0.25;  ///< a cluster lower than this, ...
    double max_object_height_m = 1.7;   ///< ... taller or ...
    double max_object_length_m = 3.2;   ///< ... longer is not furniture
    /// A cluster is an object when at least this share of its points is Movable, or when a CAD
    /// model fits it (furniture that stayed put in every session is found by its shape).
    double movable_share = 0.2;
    verification::VerifyParams
        verify;                 ///< the CAD alignment (size mismatch relaxed: clusters are rough)
    int max_splits = 3;         ///< re-clustering rounds of what a fitted model leaves over
    double split_share = 0.25;  ///< a fit leaving this share of the cluster unexplained splits it
    double split_distance_m = 0.12;  ///< points this close to the fitted model are the object's own
    double min_coverage = 0.3;       ///< a fit must explain this share of the cluster's points
    /// ... and the session must not have seen through more than this share of the model's observed
    /// surface (rays that passed where the fitted model would stand: it is not there).
    double max_seen_through = 0.45;
    double duplicate_iou =
        0.2;  ///< a later object overlapping an earlier one of its class (BEV IoU) is dropped
    double label_distance_m =
        0.06;  ///< step 6: a point this close to the aligned model is the object's
    double unknown_box_margin_m =
        0.05;                     ///< points of a model-less object: inside its box grown by this
    std::size_t min_points = 20;  ///< a keyframe object with fewer points is "unseen"
    double range_m = 20.0;        ///< keyframe objects farther (|x| or |y|) are not listed
    LabelParams();
    std::vector<std::string> validate() const;
};

/// An object of one session in the reference frame.
struct LabelledWorldObject {
    std::uint32_t id = 0;  ///< unique over all sessions (instance label of its points)
    int session = 0;
    std::optional<ObjectClass> cls;  ///< none: unknown (left out of training)
    OrientedBox box_world;
    std::string model;         ///< the aligned CAD model (empty: PCA box only)
    std::string class_source;  ///< "cad", "detector" or "unknown"
    double residual_m = 0.0;   ///< the CAD fit's
    double seen_through =
        0.0;  ///< share of the fitted model's observed surface the session saw through
    std::size_t map_points = 0;  ///< the cluster's points in the session map
    double movable_share = 0.0;
    Isometry3 T_world_object = Isometry3::Identity();  ///< the model's pose (with a model)
};

struct LabelledSessionKeyframe {
    LabelledKeyframe keyframe;  ///< cloud (unknown objects' points removed), objects, pose
    /// Per point of keyframe.cloud_sensor: SemanticLabel in the low 16 bits, instance id in the
    /// high 16 (SemanticKITTI's layout); and the point's class.
    std::vector<std::uint32_t> point_labels;
    std::vector<PointClass> point_classes;
};

struct SessionReport {
    std::size_t sweeps = 0, keyframes = 0, traced_sweeps = 0;
    SessionAlignment alignment;  ///< identity for the first session
    std::size_t objects = 0, cad_objects = 0, unknown_objects = 0, clusters = 0;
};

struct LabelResult {
    std::vector<std::vector<LabelledSessionKeyframe>> sessions;
    std::vector<SessionReport> reports;
    std::vector<LabelledWorldObject> objects;
    std::array<std::size_t, kNumPointClasses> point_class_counts{};  ///< over the keyframe clouds
    double seconds_front_end = 0.0, seconds_align = 0.0, seconds_trace = 0.0, seconds_objects = 0.0,
           seconds_points = 0.0;
};

struct PointLabel {
    PointClass cls = PointClass::kPermanent;
    SemanticLabel semantic = SemanticLabel::kStructure;
    std::uint32_t instance = 0;
};

/// The class of a model-less cluster by other means (a detector of an earlier round): the cluster's
/// box and points in the reference frame; nullopt when it does not know.
using UnknownClassifier = std::function<std::optional<ObjectClass>(
    int session, const OrientedBox& box_world, const std::vector<Eigen::Vector3d>& points_world)>;
/// (stage, done, total) for progress bars.
using LabelProgress = std::function<void(const std::string&, std::size_t, std::size_t)>;

class Labeller {
  public:
    explicit Labeller(
        const LabelParams& params);  ///< throws std::invalid_argument listing every problem
    ~Labeller();

    /// Sessions are fed one after the other, sweeps in time order. The first session's start pose
    /// defines the reference frame; later ones start at their own start pose in it.
    void begin_session(const Pose2& start_pose);
    /// Runs the front end (channels other than intensity, ring and time are dropped first) and
    /// keeps what the later steps need. Returns the front end's result (its points_world in the
    /// sweep's point order, before the session's alignment).
    pipeline::FrontEndResult add_sweep(pipeline::Sweep sweep);

    /// Steps 1-6. `library`: the room's CAD models (none: every object keeps its PCA box).
    LabelResult finish(const verification::CadLibrary* library,
                       const UnknownClassifier& classify_unknown = {},
                       const LabelProgress& progress = {});

    /// After finish(): the label of points of `session` given in that session's own world frame
    /// (as add_sweep returned them), by the same rules as the keyframes' points.
    std::vector<PointLabel> label_points(
        int session, const std::vector<Eigen::Vector3f>& points_session_world) const;
    /// After finish(): the alignment of `session` into the reference frame.
    const Isometry3& T_reference_session(int session) const;

  private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

}  // namespace makeway::labelling
