#include "makeway/pipeline/pipeline.hpp"

#include <algorithm>
#include <optional>
#include <unordered_set>

#include "makeway/common/param_table.hpp"
#include "makeway/common/stopwatch.hpp"
#include "makeway/verification/part_outlines.hpp"

namespace makeway::pipeline {
namespace {

// Every problem of the parameters, and of the ICP levels against the CAD library's.
const SystemParams& validated(const SystemParams& params, const verification::CadLibrary* library) {
    std::vector<std::string> problems = params.validate();
    if (library) {
        for (const std::string& p : library->params().validate())
            problems.push_back("cad_library." + p);
        for (const std::string& p :
             params.verify.icp.validate(library->params().voxel_sizes_m.size())) {
            problems.push_back("verification.icp." + p);
        }
    }
    throw_if_problems(problems);
    return params;
}

}  // namespace

tracking::TrackerParams tracker_params_for(const perception::ObjectDetector* detector,
                                           tracking::TrackerParams params, bool cad_verified) {
    // Misses count only where the detector can see: inside the circle its square grid contains,
    // less half a large chair so that the whole object is inside.
    if (detector) params.miss_range_m = std::min(params.sensor_range_m, detector->reach_m() - 0.5);
    if (cad_verified) {
        for (tracking::MotionPrior& m : params.motion)
            m.rest_yaw_rate_sigma_radps = params.kalman.yaw_rate_sigma_radps;
    }
    return params;
}

Pipeline::Pipeline(const SystemParams& params, const Pose2& start_pose,
                   const perception::ObjectDetector* detector,
                   const verification::CadLibrary* library)
    : params_(validated(params, library)),
      detector_(detector),
      library_(library),
      front_end_(params, start_pose),
      map_(tracker_params_for(detector, params.tracker, library && !library->models().empty())) {}

void Pipeline::set_shape_prior(const verification::ShapePrior* prior) {
    shapes_ = prior ? std::make_unique<TrackedShapes>(prior, params_.shapes) : nullptr;
}

SweepResult Pipeline::process_sweep(Sweep sweep) {
    const SteadyClock::time_point t0 = SteadyClock::now();
    std::optional<PendingKeyframe> pending;
    SweepResult out = track(std::move(sweep), &pending);
    // Keyframe: detect, verify, track.
    if (pending) {
        out.keyframe = perceive(std::move(*pending), out.timing);
        out.objects = objects();
    }
    out.timing.total_ms = ms_since(t0);
    return out;
}

SweepResult Pipeline::track(Sweep sweep, std::optional<PendingKeyframe>* pending) {
    const SteadyClock::time_point t0 = SteadyClock::now();
    SweepResult out;
    // Front end: pose from the start pose and the wheel odometry, the sweep de-skewed, and every
    // `every` sweeps a keyframe (accumulated, ground plane, ground and ceiling removed). The
    // simulator's labels and instance ids are dropped first: only what a sensor measures enters.
    const double stamp_s = sweep.stamp_s;
    sweep.points_sensor = sensor_channels_only(std::move(sweep.points_sensor));
    FrontEndResult front = front_end_.add(std::move(sweep));
    out.T_world_sensor_start = front.T_world_sensor_start;
    out.T_world_sensor_end = front.T_world_sensor_end;
    out.pose = front.pose;
    out.points_world = std::move(front.points_world);
    out.timing.deskew_ms = front.deskew_ms;
    out.timing.odometry_ms = front.odometry_ms;
    out.odometry = front.odometry;
    out.keyframe_formed = front.keyframe.has_value();
    if (front.keyframe && pending) *pending = PendingKeyframe{std::move(*front.keyframe), stamp_s};
    out.objects = objects();
    out.timing.total_ms = ms_since(t0);
    return out;
}

KeyframeResult Pipeline::perceive(PendingKeyframe pending, StageTiming& timing) {
    KeyframeResult kf = process_keyframe(std::move(pending.front), pending.stamp_s, timing);
    std::vector<ObjectEstimate> objects = kf.tracking.objects_world;
    attach_parts(objects);
    std::lock_guard<std::mutex> lock(objects_mutex_);
    objects_ = std::move(objects);
    return kf;
}

std::vector<ObjectEstimate> Pipeline::objects() const {
    std::lock_guard<std::mutex> lock(objects_mutex_);
    return objects_;
}

KeyframeResult Pipeline::process_keyframe(FrontEndKeyframe front, double stamp_s,
                                          StageTiming& timing) {
    KeyframeResult kf;
    kf.index = keyframes_++;
    kf.stamp_s = stamp_s;
    kf.T_world_keyframe = front.T_world_keyframe;
    kf.prepared = std::move(front.prepared);
    timing.accumulate_ms = front.accumulate_ms;
    timing.ground_ms = front.ground_ms;
    // Detect (eq. network heads -> peaks -> rotated NMS).
    SteadyClock::time_point t = SteadyClock::now();
    if (detector_)
        kf.detections = detector_->detect(kf.prepared.cloud_sensor, kf.prepared.ground.plane());
    timing.detect_ms = ms_since(t);
    // Verify against the CAD models: accepted boxes become the aligned model's, scored by p_exist
    // (eq. 2).
    t = SteadyClock::now();
    kf.evidence = kf.detections;
    const bool have_cad = library_ && !library_->models().empty();
    if (shapes_) shapes_->begin_keyframe(kf.T_world_keyframe);
    if (params_.verification_enabled && (have_cad || shapes_)) {
        const PreparedKeyframe& prepared = kf.prepared;
        // Objects the map verified lately: one ICP from their last fit (the full search when it
        // fails).
        const auto seeds = have_cad ? seeds_for(kf.detections, kf.T_world_keyframe, stamp_s)
                                    : std::vector<std::optional<verification::VerifySeed>>{};
        kf.verified = verification::verify_detections(
            prepared.cloud_sensor, kf.detections, have_cad ? *library_ : no_library_,
            params_.verify, [&](double x, double y) { return prepared.floor_z_at(x, y); },
            shapes_.get(), seeds);
        kf.evidence = verification::accepted_detections(
            kf.verified, verification::ScoreFrom::kExistence, params_.verify.keep_unfitted);
    } else {
        // Nothing to verify against: the network's boxes, chairs turned to their backs.
        const PreparedKeyframe& prepared = kf.prepared;
        kf.evidence = verification::chairs_turned_to_their_backs(
            prepared.cloud_sensor, kf.detections,
            [&](double x, double y) { return prepared.floor_z_at(x, y); }, params_.back_yaw);
    }
    timing.verify_ms = ms_since(t);
    // Track: associate (GIoU + Hungarian), filter, fuse class and existence (eqs. 3-5), prune.
    t = SteadyClock::now();
    // Objects stand on the floor: the keyframe's plane, in the world frame, is the tracker's z
    // prior.
    std::optional<Eigen::Vector4d> floor;
    if (kf.prepared.ground.found) {
        const Eigen::Vector3d n = kf.T_world_keyframe.linear() * kf.prepared.ground.normal;
        floor =
            Eigen::Vector4d(n.x(), n.y(), n.z(),
                            kf.prepared.ground.offset - n.dot(kf.T_world_keyframe.translation()));
    }
    kf.tracking =
        map_.update(kf.evidence, kf.T_world_keyframe, stamp_s, nullptr, floor ? &*floor : nullptr);
    if (have_cad) remember_fits(kf);  // re-verification's seeds, the objects' parts
    timing.track_ms = ms_since(t);
    // Learned shapes: each object verified against one gains this view, and its shape is completed
    // from all of its views; the next keyframe verifies it against that shape.
    if (shapes_ && !kf.verified.empty()) {
        t = SteadyClock::now();
        std::unordered_set<std::uint32_t> live;
        for (const auto& [id, track] : map_.tracks()) live.insert(id);
        kf.shapes_completed = shapes_->add_views(kf.prepared.cloud_sensor, kf.verified,
                                                 kf.tracking.track_of_detection, live);
        timing.shape_ms = ms_since(t);
    }
    return kf;
}

std::vector<std::optional<verification::VerifySeed>> Pipeline::seeds_for(
    const std::vector<Detection>& detections, const Isometry3& T_world_keyframe,
    double stamp_s) const {
    std::vector<std::optional<verification::VerifySeed>> seeds(detections.size());
    const verification::VerifyParams& p = params_.verify;
    if (fits_.empty() || p.reseed_tolerance_m <= 0.0) return seeds;
    const Isometry3 T_keyframe_world = T_world_keyframe.inverse();
    for (std::size_t i = 0; i < detections.size(); ++i) {
        const Detection& d = detections[i];
        const Eigen::Vector3d centre_world = T_world_keyframe * d.box_sensor.centre_m;
        double nearest = p.reseed_radius_m;
        const TrackFit* best = nullptr;
        for (const auto& [id, fit] : fits_) {
            if (fit.model->cls != d.cls || stamp_s - fit.stamp_s > p.reseed_max_age_s) continue;
            const Eigen::Vector3d fit_centre = fit.T_world_object * fit.model->box_object.centre_m;
            const double gap = (fit_centre - centre_world).head<2>().norm();
            if (gap <= nearest) nearest = gap, best = &fit;
        }
        if (!best) continue;
        // The fit in this keyframe's sensor frame, as the 4-DoF pose ICP optimises (the sensor
        // stands level on the robot: its yaw about the sensor's z).
        const Isometry3 T = T_keyframe_world * best->T_world_object;
        seeds[i] =
            verification::VerifySeed{best->model, {T.translation(), yaw_of(T)}, best->residual_m};
    }
    return seeds;
}

void Pipeline::remember_fits(const KeyframeResult& kf) {
    // track_of_detection is per evidence: the accepted detections first, in order (then any
    // unfitted ones kept, which have no fit).
    std::size_t k = 0;
    for (const verification::VerifiedDetection& v : kf.verified) {
        if (!v.accepted) continue;
        const std::size_t evidence = k++;
        if (evidence >= kf.tracking.track_of_detection.size() ||
            kf.tracking.track_of_detection[evidence] < 0)
            continue;
        const verification::CadModel* model = nullptr;
        for (const verification::CadModel& m : library_->models()) {
            if (m.name == v.model) model = &m;
        }
        if (!model) continue;  // a completed shape: its mesh is this keyframe's
        fits_[static_cast<std::uint32_t>(kf.tracking.track_of_detection[evidence])] =
            TrackFit{model, kf.T_world_keyframe * v.T_sensor_object, v.residual_m, kf.stamp_s};
    }
    std::erase_if(fits_, [&](const auto& entry) { return !map_.tracks().count(entry.first); });
}

void Pipeline::attach_parts(std::vector<ObjectEstimate>& objects) {
    for (ObjectEstimate& o : objects) {
        const auto fit = fits_.find(o.id);
        if (fit == fits_.end()) continue;
        const verification::CadModel* model = fit->second.model;
        auto outlines = part_outlines_.find(model);
        if (outlines == part_outlines_.end()) {
            outlines =
                part_outlines_
                    .emplace(model, verification::part_outlines(
                                        model->levels.empty() ? std::vector<Eigen::Vector3d>{}
                                                              : model->levels.back().points_object,
                                        params_.navigator.monitor.body))
                    .first;
        }
        // The fit where the map's box is now: the tracker has moved the object since, or smoothed
        // the fit's box.
        const Isometry3& T = fit->second.T_world_object;
        const Eigen::Vector2d shift =
            o.box_world.centre_m.head<2>() - (T * model->box_object.centre_m).head<2>();
        for (const Polygon2& part : outlines->second) {
            Polygon2 world;
            world.reserve(part.size());
            for (const Eigen::Vector2d& q : part)
                world.push_back((T * Eigen::Vector3d(q.x(), q.y(), 0.0)).head<2>() + shift);
            o.parts_world.push_back(std::move(world));
        }
    }
}

}  // namespace makeway::pipeline
