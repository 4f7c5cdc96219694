#include "makeway/labelling/param_tables.hpp"

namespace makeway::labelling {

const ParamTable<LabelParams>& label_table() {
    using L = LabelParams;
    static const ParamTable<L> table = [] {
        ParamTable<L> t;
        t.include(
             "", [](L& l) -> OccupancyParams& { return l.occupancy; }, occupancy_table())
            .add("trace_every", &L::trace_every, closed(1, 1000), "every n-th sweep is ray traced")
            .add("trace_voxel_m", &L::trace_voxel_m, above(0.0, 10.0),
                 "a traced sweep keeps one return per voxel")
            .add("map_voxel_m", &L::map_voxel_m, above(0.0, 10.0), "session maps for clustering")
            .add_ref(
                "dbscan_eps_m", [](L& l) -> double& { return l.dbscan.eps_m; }, above(0.0, 10.0),
                "")
            .add_ref(
                "dbscan_min_points", [](L& l) -> int& { return l.dbscan.min_points; },
                closed(1, 100000), "")
            .add("dbscan_z_scale", &L::dbscan_z_scale, above(0.0, 10.0),
                 "heights scaled before clustering (< 1: vertical gaps count less)")
            .add("min_cluster_points", &L::min_cluster_points, closed(0.0, 1e9), "")
            .add("min_object_points", &L::min_object_points, closed(0.0, 1e9),
                 "an object (a fitted one: points near its model) needs this many map points")
            .add("min_object_height_m", &L::min_object_height_m, closed(0.0, 10.0),
                 "furniture-sized clusters: this tall ...")
            .add("max_object_height_m", &L::max_object_height_m, above(0.0, 10.0),
                 "... at most this tall ...")
            .add("max_object_length_m", &L::max_object_length_m, above(0.0, 100.0), "... and long")
            .add("movable_share", &L::movable_share, closed(0.0, 1.0),
                 "a model-less cluster is an object with this share of Movable points")
            .add("min_coverage", &L::min_coverage, closed(0.0, 1.0),
                 "a CAD fit must explain this share of its cluster ...")
            .add("max_seen_through", &L::max_seen_through, closed(0.0, 1.0),
                 "... and the session saw through at most this share of its observed surface")
            .add("max_splits", &L::max_splits, closed(0, 100),
                 "re-clustering rounds of what a fit leaves unexplained ...")
            .add("split_share", &L::split_share, above(0.0, 1.0),
                 "... when it is this share of the cluster ...")
            .add("split_distance_m", &L::split_distance_m, above(0.0, 2.0),
                 "... farther than this from the model")
            .add("duplicate_iou", &L::duplicate_iou, above(0.0, 1.0),
                 "a later object of the same class overlapping an earlier one (BEV IoU) is dropped")
            .add_ref(
                "verify_e_max_m", [](L& l) -> double& { return l.verify.e_max_m; }, above(0.0, 1.0),
                "CAD alignment: the verifier's e_max_m on a session's map")
            .renamed_from("cad_max_residual_m")
            .add("label_distance_m", &L::label_distance_m, above(0.0, 10.0),
                 "a point this close to an aligned model is the object's")
            .add("min_points", &L::min_points, closed(0.0, 1e9),
                 "keyframe objects with fewer points are \"unseen\"")
            .add("range_m", &L::range_m, above(0.0, 1000.0),
                 "keyframe objects farther (|x| or |y|) are not listed")
            .require([](const L& l) { return l.min_object_height_m < l.max_object_height_m; },
                     "min_object_height_m must be below max_object_height_m")
            // A bound outside its own range is reported by the range alone.
            .require(
                [](const L& l) {
                    return !(l.verify.e_max_m > 0.0) || l.verify.e_min_m < l.verify.e_max_m;
                },
                "verify_e_max_m must exceed the verifier's e_min_m");
        return t;
    }();
    return table;
}

const ParamTable<OccupancyParams>& occupancy_table() {
    using O = OccupancyParams;
    static const ParamTable<O> table = [] {
        ParamTable<O> t;
        t.add("voxel_m", &O::voxel_m, above(0.0, 10.0), "the multi-session occupancy grid")
            .add("end_margin_m", &O::end_margin_m, closed(0.0, 10.0),
                 "free space stops this short of a return ...")
            .add("range_margin", &O::range_margin, closed(0.0, 1.0),
                 "... plus this share of its range (grazing rays do not carve surfaces)")
            .add("min_free_sweeps", &O::min_free_sweeps, closed(1, 100000),
                 "movable: another session saw the voxel free in this many sweeps ...")
            .add("absent_hit_ratio", &O::absent_hit_ratio, below(0.0, 1.0),
                 "... and hit it in at most this share of them")
            .add("dynamic_min_free", &O::dynamic_min_free, closed(1, 100000),
                 "dynamic: its own session saw it free this often ...")
            .add("dynamic_hit_ratio", &O::dynamic_hit_ratio, below(0.0, 1.0),
                 "... and hit it in fewer than this share of them");
        return t;
    }();
    return table;
}

}  // namespace makeway::labelling
