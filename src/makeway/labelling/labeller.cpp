#include "makeway/labelling/labeller.hpp"

#include <algorithm>
#include <chrono>
#include <deque>
#include <map>
#include <stdexcept>

#include "makeway/common/angles.hpp"
#include "makeway/common/box_overlap.hpp"
#include "makeway/common/param_table.hpp"
#include "makeway/common/voxel_thin.hpp"
#include "makeway/labelling/object_rules.hpp"
#include "makeway/labelling/upright_box.hpp"

namespace makeway::labelling {
namespace {

using Clock = std::chrono::steady_clock;
double seconds_since(Clock::time_point t0) {
    return std::chrono::duration<double>(Clock::now() - t0).count();
}

// Every keyframe's points of `keyframes` in one frame (T * T_world_keyframe each), in one
// allocation: grown point by point, a session's map was a tenth of a labelling run's page faults
// under ASan (each regrowth a fresh mapping).
template <class Keyframes>
std::vector<Eigen::Vector3d> keyframes_in(const Keyframes& keyframes, const Isometry3& T) {
    std::size_t n = 0;
    for (const auto& k : keyframes) n += k.cloud_sensor.size();
    std::vector<Eigen::Vector3d> out;
    out.reserve(n);
    for (const auto& k : keyframes) {
        const Isometry3 T_k = T * k.T_world_keyframe;
        for (const Eigen::Vector3f& p : k.cloud_sensor.xyz) out.push_back(T_k * p.cast<double>());
    }
    return out;
}

}  // namespace

struct Labeller::Impl {
    struct TracedSweep {
        Eigen::Vector3d origin;
        std::vector<Eigen::Vector3f> points_world;  ///< in the session's own world
    };
    struct KeyframeRecord {
        Isometry3 T_world_keyframe;  ///< in the session's own world
        PointCloud cloud_sensor;
        std::optional<Eigen::Vector4d> plane_sensor;
        double stamp_s = 0.0;
    };
    struct Session {
        Pose2 start;
        std::unique_ptr<pipeline::FrontEnd> front_end;
        std::vector<TracedSweep> traced;
        std::vector<KeyframeRecord> keyframes;
        std::size_t sweeps = 0;
        Isometry3 T_ref = Isometry3::Identity();
        std::optional<Eigen::Vector4d> floor_ref;  ///< the floor plane in the reference frame
    };
    struct Object {
        LabelledWorldObject info;
        const verification::CadModel* model = nullptr;
        Isometry3 T_object_world = Isometry3::Identity();
    };

    LabelParams params;
    std::vector<Session> sessions;
    std::unique_ptr<MultiSessionOccupancy> occupancy;
    std::vector<Object> objects;
    std::vector<std::vector<std::size_t>> objects_of;  ///< per session: indices into objects
    std::vector<verification::CadLibrary>
        single_models;  ///< the library split into one-model libraries

    bool finished = false;
    double seconds_front_end = 0.0;

    double height_of(const Session& s, const Eigen::Vector3d& p) const {
        return s.floor_ref ? s.floor_ref->head<3>().dot(p) + s.floor_ref->w() : p.z();
    }
    double floor_z_at(const Session& s, double x, double y) const {
        if (!s.floor_ref || std::abs(s.floor_ref->z()) < 1e-6) return 0.0;
        const Eigen::Vector4d& f = *s.floor_ref;
        return -(f.x() * x + f.y() * y + f.w()) / f.z();
    }

    PointLabel label_point(int session, const Eigen::Vector3d& p) const {
        const Session& s = sessions[static_cast<std::size_t>(session)];
        const double h = height_of(s, p);
        if (h < params.system.keyframe.ground_filter.ground_band_m)
            return {PointClass::kGround, SemanticLabel::kGround, 0};
        for (std::size_t index : objects_of[static_cast<std::size_t>(session)]) {
            const Object& o = objects[index];
            const double margin = o.model ? params.label_distance_m : params.unknown_box_margin_m;
            if (!o.info.box_world.contains(p, margin)) continue;
            if (o.model) {
                double d2 = 0.0;
                const Eigen::Vector3d q = o.T_object_world * p;
                if (o.model->levels.back().nearest(q, params.label_distance_m, &d2) ==
                    verification::ModelLevel::kNone)
                    continue;
            }
            return {PointClass::kMovable,
                    o.info.cls ? to_semantic_label(*o.info.cls) : SemanticLabel::kClutter,
                    o.info.id};
        }
        if (h > params.system.keyframe.ground_filter.ceiling_height_m)
            return {PointClass::kPermanent, SemanticLabel::kCeiling, 0};
        switch (occupancy->classify(session, p)) {
            case PointClass::kDynamic:
                return {PointClass::kDynamic, SemanticLabel::kPerson, 0};
            case PointClass::kMovable:
                return {PointClass::kMovable, SemanticLabel::kClutter, 0};
            default:
                return {PointClass::kPermanent, SemanticLabel::kStructure, 0};
        }
    }

    // Share of the model's surface (finest level at T_world_object) that `session` saw through:
    // free in at least min_free_sweeps sweeps and never hit; over the surface it observed at all.
    double seen_through(int session, const verification::CadModel& model,
                        const Isometry3& T_world_object) const {
        std::size_t observed = 0, through = 0;
        for (const Eigen::Vector3d& q : model.levels.back().points_object) {
            const MultiSessionOccupancy::Evidence e =
                occupancy->evidence(session, T_world_object * q);
            if (e.hits + e.free == 0) continue;
            ++observed;
            through += e.hits == 0 && e.free >= params.occupancy.min_free_sweeps;
        }
        return observed ? static_cast<double>(through) / static_cast<double>(observed) : 0.0;
    }

    void align(LabelResult& result, const LabelProgress& progress);
    void trace(const LabelProgress& progress);
    void find_objects(int session, const verification::CadLibrary* library,
                      const UnknownClassifier& classify_unknown, SessionReport& report);
    void label_keyframes(LabelResult& result, const LabelProgress& progress);
};

Labeller::Labeller(const LabelParams& params) : impl_(std::make_unique<Impl>()) {
    throw_if_problems(params.validate());
    impl_->params = params;
}
Labeller::~Labeller() = default;

void Labeller::begin_session(const Pose2& start_pose) {
    if (impl_->finished) throw std::logic_error("labeller: begin_session after finish");
    Impl::Session s;
    s.start = start_pose;
    s.front_end = std::make_unique<pipeline::FrontEnd>(impl_->params.system, start_pose);
    impl_->sessions.push_back(std::move(s));
}

pipeline::FrontEndResult Labeller::add_sweep(pipeline::Sweep sweep) {
    if (impl_->sessions.empty() || impl_->finished)
        throw std::logic_error("labeller: add_sweep outside a session");
    const auto t0 = Clock::now();
    Impl::Session& s = impl_->sessions.back();
    const double stamp_s = sweep.stamp_s;
    sweep.points_sensor = pipeline::sensor_channels_only(std::move(sweep.points_sensor));
    pipeline::FrontEndResult r = s.front_end->add(std::move(sweep));
    if (s.sweeps % static_cast<std::size_t>(impl_->params.trace_every) == 0) {
        Impl::TracedSweep t;
        // The sweep's rays start where the sensor was mid-sweep (it moves a few cm in 0.1 s).
        t.origin =
            0.5 * (r.T_world_sensor_start.translation() + r.T_world_sensor_end.translation());
        std::vector<Eigen::Vector3d> pts;
        pts.reserve(r.points_world.size());
        for (const Eigen::Vector3f& p : r.points_world.xyz) pts.push_back(p.cast<double>());
        for (const Eigen::Vector3d& p : voxel_thin(pts, impl_->params.trace_voxel_m))
            t.points_world.push_back(p.cast<float>());
        s.traced.push_back(std::move(t));
    }
    if (r.keyframe) {
        Impl::KeyframeRecord k;
        k.T_world_keyframe = r.keyframe->T_world_keyframe;
        k.cloud_sensor = r.keyframe->prepared.cloud_sensor;
        if (r.keyframe->prepared.ground.found) {
            const auto& g = r.keyframe->prepared.ground;
            k.plane_sensor = Eigen::Vector4d(g.normal.x(), g.normal.y(), g.normal.z(), g.offset);
        }
        k.stamp_s = stamp_s;
        s.keyframes.push_back(std::move(k));
    }
    ++s.sweeps;
    impl_->seconds_front_end += seconds_since(t0);
    return r;
}

const Isometry3& Labeller::T_reference_session(int session) const {
    return impl_->sessions.at(static_cast<std::size_t>(session)).T_ref;
}

void Labeller::Impl::align(LabelResult& result, const LabelProgress& progress) {
    auto session_map = [&](const Session& s, const Isometry3& T) {
        return voxel_thin(keyframes_in(s.keyframes, T), params.align.voxel_m);
    };
    odometry::VoxelMap reference;
    reference.add(session_map(sessions.front(), Isometry3::Identity()));
    for (std::size_t i = 0; i < sessions.size(); ++i) {
        Session& s = sessions[i];
        if (i > 0) {
            result.reports[i].alignment =
                align_session(reference, session_map(s, Isometry3::Identity()), params.align);
            s.T_ref = result.reports[i].alignment.T_reference_session;
        }
        for (const KeyframeRecord& k : s.keyframes) {
            if (!k.plane_sensor) continue;
            const Isometry3 T = s.T_ref * k.T_world_keyframe;
            const Eigen::Vector3d n = T.linear() * k.plane_sensor->head<3>();
            s.floor_ref =
                Eigen::Vector4d(n.x(), n.y(), n.z(), k.plane_sensor->w() - n.dot(T.translation()));
            break;
        }
        if (progress) progress("align", i + 1, sessions.size());
    }
}

void Labeller::Impl::trace(const LabelProgress& progress) {
    Eigen::AlignedBox3d bounds;
    for (const Session& s : sessions) {
        for (const TracedSweep& t : s.traced) {
            bounds.extend(s.T_ref * t.origin);
            for (const Eigen::Vector3f& p : t.points_world) {
                const Eigen::Vector3d q = s.T_ref * p.cast<double>();
                if ((q - s.T_ref * t.origin).norm() <= params.occupancy.max_range_m)
                    bounds.extend(q);
            }
        }
    }
    if (bounds.isEmpty()) throw std::invalid_argument("labelling: the sessions hold no points");
    occupancy = std::make_unique<MultiSessionOccupancy>(params.occupancy, bounds,
                                                        static_cast<int>(sessions.size()));
    std::size_t total = 0, done = 0;
    for (const Session& s : sessions) total += s.traced.size();
    std::vector<Eigen::Vector3f> pts;
    for (std::size_t i = 0; i < sessions.size(); ++i) {
        const Session& s = sessions[i];
        const Eigen::Isometry3f Tf = s.T_ref.cast<float>();
        for (const TracedSweep& t : s.traced) {
            pts.clear();
            for (const Eigen::Vector3f& p : t.points_world) pts.push_back(Tf * p);
            occupancy->add_sweep(static_cast<int>(i), s.T_ref * t.origin, pts);
            if (progress && (++done % 20 == 0 || done == total))
                progress("ray tracing", done, total);
        }
    }
}

void Labeller::Impl::find_objects(int session, const verification::CadLibrary* library,
                                  const UnknownClassifier& classify_unknown,
                                  SessionReport& report) {
    const Session& s = sessions[static_cast<std::size_t>(session)];
    const std::vector<Eigen::Vector3d> map =
        voxel_thin(keyframes_in(s.keyframes, s.T_ref), params.map_voxel_m);
    // Step 2 on the map: Dynamic points are not objects' (a walker would join a chair's cluster).
    std::vector<Eigen::Vector3d> points;
    std::vector<char> movable;
    for (const Eigen::Vector3d& p : map) {
        const PointClass c = occupancy->classify(session, p);
        if (c == PointClass::kDynamic) continue;
        points.push_back(p);
        movable.push_back(c == PointClass::kMovable);
    }
    // Step 4: clusters, split again where a fit or the furniture size says two things touch.
    std::deque<Cluster> queue;
    const auto enqueue = [&](std::vector<Cluster> clusters) {
        report.clusters += clusters.size();
        for (Cluster& c : clusters) queue.push_back(std::move(c));
    };
    enqueue(cluster_points(points, movable, 0, params));
    const bool have_models = library && !library->models().empty();
    if (have_models && single_models.size() != library->models().size()) {
        single_models.clear();
        for (std::size_t i = 0; i < library->models().size(); ++i)
            single_models.push_back(library->only(i));
    }
    const SeenThrough through = [&](const verification::CadModel& model,
                                    const Isometry3& T_world_object) {
        return seen_through(session, model, T_world_object);
    };
    while (!queue.empty()) {
        const Cluster c = std::move(queue.front());
        queue.pop_front();
        const std::size_t n = c.points_world.size();
        const double share = static_cast<double>(c.movable_count()) / static_cast<double>(n);
        Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
        for (const Eigen::Vector3d& p : c.points_world) centroid += p;
        centroid /= static_cast<double>(n);
        const double floor_z = floor_z_at(s, centroid.x(), centroid.y());
        const OrientedBox box_world = upright_pca_box(c.points_world, floor_z);
        if (!furniture_sized(box_world, floor_z, params)) {
            // A wall with chairs against it: its Movable points may still be objects of their own.
            if (const auto part = movable_part(c, params))
                enqueue(
                    cluster_points(*part, std::vector<char>(part->size(), 1), c.depth + 1, params));
            continue;
        }
        // Step 5: the CAD model that fits best (object_rules.hpp: residual, explained share, free
        // space).
        const std::optional<CadFit> best =
            have_models ? fit_cad_model(c, box_world, floor_z, single_models, through, params)
                        : std::nullopt;
        Object o;
        o.info.session = session;
        o.info.map_points = n;
        o.info.movable_share = share;
        if (best) {
            o.model = best->model;
            o.T_object_world = best->verified.T_sensor_object.inverse();
            if (auto rest = unexplained_rest(c, *best, params))
                enqueue(cluster_points(rest->points_world, rest->movable, rest->depth, params));
            o.info.cls = best->verified.detection.cls;
            o.info.box_world = best->verified.box_sensor;  // the verifier's frame was the world
            o.info.model = best->verified.model;
            o.info.class_source = "cad";
            o.info.residual_m = best->verified.residual_m;
            o.info.seen_through = best->seen_through;
            o.info.T_world_object = best->verified.T_sensor_object;
        } else if (share >= params.movable_share && n >= params.min_object_points) {
            o.info.box_world = box_world;
            if (classify_unknown) o.info.cls = classify_unknown(session, box_world, c.points_world);
            o.info.class_source = o.info.cls ? "detector" : "unknown";
        } else {
            continue;  // Permanent: it never moved and no model explains it
        }
        // The same object twice (a cluster and a piece split off a neighbour): the first stays.
        // Only within a class: a chair tucked under its table overlaps the table from above.
        const bool duplicate =
            std::any_of(objects.begin(), objects.end(), [&](const Object& other) {
                return other.info.session == session && other.info.cls == o.info.cls &&
                       iou_bev(other.info.box_world, o.info.box_world) > params.duplicate_iou;
            });
        if (duplicate) continue;
        o.info.id = static_cast<std::uint32_t>(objects.size() + 1);
        objects_of[static_cast<std::size_t>(session)].push_back(objects.size());
        report.cad_objects += o.model != nullptr;
        report.unknown_objects += !o.info.cls;
        objects.push_back(std::move(o));
        ++report.objects;
    }
}

void Labeller::Impl::label_keyframes(LabelResult& result, const LabelProgress& progress) {
    std::size_t total = 0, done = 0;
    for (const Session& s : sessions) total += s.keyframes.size();
    result.sessions.resize(sessions.size());
    for (std::size_t si = 0; si < sessions.size(); ++si) {
        const Session& s = sessions[si];
        for (const KeyframeRecord& k : s.keyframes) {
            const Isometry3 T_ref_kf = s.T_ref * k.T_world_keyframe;
            LabelledSessionKeyframe out;
            out.keyframe.sequence = static_cast<std::uint32_t>(si);
            out.keyframe.stamp_s = k.stamp_s;
            out.keyframe.T_world_sensor = T_ref_kf;
            out.keyframe.ground_plane_sensor = k.plane_sensor;
            std::vector<std::size_t> keep;
            std::map<std::uint32_t, std::size_t> points_of;
            for (std::size_t i = 0; i < k.cloud_sensor.size(); ++i) {
                const PointLabel l = label_point(static_cast<int>(si),
                                                 T_ref_kf * k.cloud_sensor.xyz[i].cast<double>());
                const bool unknown_object =
                    l.instance != 0 && l.semantic == SemanticLabel::kClutter;
                if (unknown_object)
                    continue;  // left out of training: neither object nor background
                keep.push_back(i);
                out.point_labels.push_back(static_cast<std::uint32_t>(l.semantic) |
                                           (l.instance << 16));
                out.point_classes.push_back(l.cls);
                ++result.point_class_counts[static_cast<std::size_t>(l.cls)];
                if (l.instance) ++points_of[l.instance];
            }
            out.keyframe.cloud_sensor = k.cloud_sensor.select(keep);
            const Isometry3 T_kf_ref = T_ref_kf.inverse();
            for (const Object& o : objects) {
                if (o.info.session != static_cast<int>(si) || !o.info.cls) continue;
                const OrientedBox box = o.info.box_world.transformed(T_kf_ref);
                if (std::abs(box.centre_m.x()) > params.range_m ||
                    std::abs(box.centre_m.y()) > params.range_m)
                    continue;
                const LabelledObject label{o.info.id, *o.info.cls, o.info.model, box,
                                           points_of[o.info.id]};
                (label.points >= params.min_points ? out.keyframe.objects : out.keyframe.unseen)
                    .push_back(label);
            }
            result.sessions[si].push_back(std::move(out));
            if (progress) progress("labels", ++done, total);
        }
    }
}

LabelResult Labeller::finish(const verification::CadLibrary* library,
                             const UnknownClassifier& classify_unknown,
                             const LabelProgress& progress) {
    Impl& m = *impl_;
    if (m.finished) throw std::logic_error("labeller: finish called twice");
    if (m.sessions.empty()) throw std::invalid_argument("labelling: no sessions");
    for (std::size_t i = 0; i < m.sessions.size(); ++i) {
        if (m.sessions[i].keyframes.empty()) {
            throw std::invalid_argument(
                "labelling: session " + std::to_string(i + 1) + " has no keyframe (fewer than " +
                std::to_string(m.params.system.keyframe.every) + " sweeps)");
        }
    }
    m.finished = true;
    LabelResult result;
    result.seconds_front_end = m.seconds_front_end;
    result.reports.resize(m.sessions.size());
    for (std::size_t i = 0; i < m.sessions.size(); ++i) {
        result.reports[i].sweeps = m.sessions[i].sweeps;
        result.reports[i].keyframes = m.sessions[i].keyframes.size();
        result.reports[i].traced_sweeps = m.sessions[i].traced.size();
    }
    auto t0 = Clock::now();
    m.align(result, progress);
    result.seconds_align = seconds_since(t0);
    t0 = Clock::now();
    m.trace(progress);
    result.seconds_trace = seconds_since(t0);
    t0 = Clock::now();
    m.objects_of.assign(m.sessions.size(), {});
    for (std::size_t i = 0; i < m.sessions.size(); ++i) {
        m.find_objects(static_cast<int>(i), library, classify_unknown, result.reports[i]);
        if (progress) progress("objects", i + 1, m.sessions.size());
    }
    result.seconds_objects = seconds_since(t0);
    t0 = Clock::now();
    m.label_keyframes(result, progress);
    result.seconds_points = seconds_since(t0);
    for (const Impl::Object& o : m.objects) result.objects.push_back(o.info);
    for (Impl::Session& s : m.sessions) s.traced.clear();  // the occupancy map holds what they said
    return result;
}

std::vector<PointLabel> Labeller::label_points(
    int session, const std::vector<Eigen::Vector3f>& points_session_world) const {
    const Impl& m = *impl_;
    if (!m.finished) throw std::logic_error("labeller: label_points before finish");
    const Isometry3& T = m.sessions.at(static_cast<std::size_t>(session)).T_ref;
    std::vector<PointLabel> out;
    out.reserve(points_session_world.size());
    for (const Eigen::Vector3f& p : points_session_world)
        out.push_back(m.label_point(session, T * p.cast<double>()));
    return out;
}

}  // namespace makeway::labelling
