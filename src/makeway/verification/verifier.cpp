#include "makeway/verification/verifier.hpp"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <exception>
#include <limits>
#include <mutex>
#include <numeric>
#include <stdexcept>
#include <system_error>
#include <thread>

#include "makeway/common/angles.hpp"
#include "makeway/verification/param_tables.hpp"

namespace makeway::verification {

// Cells of the floor-plane buckets segments are cut from: about a chair, so a box reads 3 x 3 to
// 5 x 5 cells.
constexpr double kBucket_m = 0.5;

std::vector<std::string> VerifyParams::validate() const {
    std::vector<std::string> p = verify_table().problems(*this);
    if (candidate_iterations < 0 || candidate_iterations > 100)
        p.push_back("candidate_iterations must be in [0, 100]");
    return p;
}

namespace {

// Whether p lies in the box grown by margin (the cheap test first; NaN fails it).
struct SegmentTest {
    SegmentTest(const OrientedBox& box, double margin)
        : centre(box.centre_m),
          c(std::cos(box.yaw_rad)),
          s(std::sin(box.yaw_rad)),
          half(0.5 * box.size_m + Eigen::Vector3d::Constant(margin)),
          reach2(half.head<2>().squaredNorm()) {}
    bool operator()(const Eigen::Vector3d& p) const {
        const Eigen::Vector3d d = p - centre;
        if (!(d.head<2>().squaredNorm() <= reach2)) return false;  // cheap reject (and NaN)
        return std::abs(c * d.x() + s * d.y()) <= half.x() &&
               std::abs(-s * d.x() + c * d.y()) <= half.y() && std::abs(d.z()) <= half.z();
    }
    Eigen::Vector3d centre;
    double c, s;
    Eigen::Vector3d half;
    double reach2;
};

// A keyframe's points bucketed on the floor plane, so that each detection's segment reads the
// cells its box reaches instead of the whole cloud (twenty detections read a keyframe of a few
// hundred thousand points twenty times otherwise). Indices ascend within a cell, and a segment
// gathered from cells is sorted back into the cloud's order: the same points in the same order
// as the scan of the whole cloud, so every fit is the same to the bit.
class PlaneBuckets {
  public:
    PlaneBuckets(const PointCloud& cloud, double cell_m) {
        Eigen::Vector2d lo = Eigen::Vector2d::Constant(std::numeric_limits<double>::infinity());
        Eigen::Vector2d hi = -lo;
        for (const Eigen::Vector3f& p : cloud.xyz) {
            if (!std::isfinite(p.x()) || !std::isfinite(p.y())) continue;
            lo = lo.cwiseMin(p.head<2>().cast<double>());
            hi = hi.cwiseMax(p.head<2>().cast<double>());
        }
        if (!(lo.x() <= hi.x())) return;  // no finite point: every segment is empty
        // At most 2,000 cells a side: a stray return kilometres out grows the cells instead.
        cell_m_ = std::max(cell_m, (hi - lo).maxCoeff() / 2000.0);
        origin_ = lo;
        nx_ = static_cast<std::int64_t>((hi.x() - lo.x()) / cell_m_) + 1;
        ny_ = static_cast<std::int64_t>((hi.y() - lo.y()) / cell_m_) + 1;
        start_.assign(static_cast<std::size_t>(nx_ * ny_) + 1, 0);
        std::vector<std::int64_t> cell_of(cloud.xyz.size(), -1);
        for (std::size_t i = 0; i < cloud.xyz.size(); ++i) {
            const Eigen::Vector3f& p = cloud.xyz[i];
            if (!std::isfinite(p.x()) || !std::isfinite(p.y())) continue;
            cell_of[i] = cell(p.x(), p.y());
            ++start_[static_cast<std::size_t>(cell_of[i]) + 1];
        }
        for (std::size_t k = 1; k < start_.size(); ++k) start_[k] += start_[k - 1];
        index_.resize(start_.back());
        std::vector<std::uint32_t> fill(start_.begin(), start_.end() - 1);
        for (std::size_t i = 0; i < cloud.xyz.size(); ++i) {
            if (cell_of[i] >= 0)
                index_[fill[static_cast<std::size_t>(cell_of[i])]++] =
                    static_cast<std::uint32_t>(i);
        }
    }

    std::vector<Eigen::Vector3d> segment(const PointCloud& cloud, const OrientedBox& box,
                                         double margin) const {
        const SegmentTest inside(box, margin);
        std::vector<std::uint32_t> hits;
        if (nx_ > 0 && std::isfinite(inside.reach2) && inside.centre.allFinite()) {
            // A hair wider than the reach: the exact test below decides, the cells only must not
            // miss a point it would keep.
            const double r = std::sqrt(inside.reach2) * (1.0 + 1e-9) + 1e-9;
            const auto clamp_x = [&](double x) {
                return static_cast<std::int64_t>(std::clamp(std::floor((x - origin_.x()) / cell_m_),
                                                            0.0, static_cast<double>(nx_ - 1)));
            };
            const auto clamp_y = [&](double y) {
                return static_cast<std::int64_t>(std::clamp(std::floor((y - origin_.y()) / cell_m_),
                                                            0.0, static_cast<double>(ny_ - 1)));
            };
            for (std::int64_t iy = clamp_y(inside.centre.y() - r);
                 iy <= clamp_y(inside.centre.y() + r); ++iy) {
                for (std::int64_t ix = clamp_x(inside.centre.x() - r);
                     ix <= clamp_x(inside.centre.x() + r); ++ix) {
                    const auto k = static_cast<std::size_t>(iy * nx_ + ix);
                    for (std::uint32_t j = start_[k]; j < start_[k + 1]; ++j) {
                        if (inside(cloud.xyz[index_[j]].cast<double>())) hits.push_back(index_[j]);
                    }
                }
            }
        }
        std::sort(hits.begin(), hits.end());
        std::vector<Eigen::Vector3d> out;
        out.reserve(hits.size());
        for (const std::uint32_t i : hits) out.push_back(cloud.xyz[i].cast<double>());
        return out;
    }

  private:
    std::int64_t cell(float x, float y) const {
        const auto ix = std::min<std::int64_t>(
            static_cast<std::int64_t>((static_cast<double>(x) - origin_.x()) / cell_m_), nx_ - 1);
        const auto iy = std::min<std::int64_t>(
            static_cast<std::int64_t>((static_cast<double>(y) - origin_.y()) / cell_m_), ny_ - 1);
        return iy * nx_ + ix;
    }
    Eigen::Vector2d origin_ = Eigen::Vector2d::Zero();
    double cell_m_ = 1.0;
    std::int64_t nx_ = 0, ny_ = 0;
    std::vector<std::uint32_t> start_;  ///< per cell, its first entry in index_ (and one past)
    std::vector<std::uint32_t> index_;  ///< point indices, cell by cell, ascending in each
};

// The cloud a detection's segment comes from: scanned whole, or through its buckets.
struct CloudView {
    const PointCloud& cloud;
    const PlaneBuckets* buckets = nullptr;
    std::vector<Eigen::Vector3d> segment(const OrientedBox& box, double margin) const {
        return buckets ? buckets->segment(cloud, box, margin) : segment_points(cloud, box, margin);
    }
};

}  // namespace

std::vector<Eigen::Vector3d> segment_points(const PointCloud& cloud, const OrientedBox& box,
                                            double margin) {
    std::vector<Eigen::Vector3d> out;
    const SegmentTest inside(box, margin);
    for (const auto& p : cloud.xyz) {
        if (inside(p.cast<double>())) out.push_back(p.cast<double>());
    }
    return out;
}

std::vector<std::vector<Eigen::Vector3d>> segments_of(const PointCloud& cloud,
                                                      const std::vector<OrientedBox>& boxes,
                                                      double margin) {
    std::vector<std::vector<Eigen::Vector3d>> out;
    if (boxes.empty()) return out;
    const PlaneBuckets buckets(cloud, kBucket_m);
    for (const OrientedBox& box : boxes) out.push_back(buckets.segment(cloud, box, margin));
    return out;
}

double existence_probability(double e, double e_min, double e_max) {
    return std::clamp(1.0 - 0.5 * (e - e_min) / (e_max - e_min), 0.5, 1.0);  // eq. (2)
}

namespace {

// The model and its fit: the pose, the model's box there, the residual acceptance is judged on.
void take_fit(VerifiedDetection& out, const CadModel& model, const IcpResult& fit) {
    out.model = model.name;
    out.residual_m = fit.residual_m;
    out.iterations = fit.iterations;
    out.converged = fit.converged;
    out.T_sensor_object = fit.pose.matrix();
    out.box_sensor = model.box_object.transformed(out.T_sensor_object);
}

VerifiedDetection verify_with_cad(const std::vector<Eigen::Vector3d>& segment, const Detection& det,
                                  const CadLibrary& library, const VerifyParams& params,
                                  std::optional<double> floor_z_m) {
    VerifiedDetection out;
    out.detection = det;
    out.segment_points = segment.size();
    const auto models = library.models_of(det.cls);
    if (models.empty()) {
        out.reason = "no CAD model for class " + std::string(to_string(det.cls));
        return out;
    }
    if (segment.size() < params.min_points) {
        out.reason = "segment has " + std::to_string(segment.size()) + " points (< " +
                     std::to_string(params.min_points) + ")";
        return out;
    }
    // Models whose size agrees with the detected box (length and width compared unordered: the yaw
    // may be off by pi/2): a large model would otherwise explain clutter around a small object.
    auto size_mismatch = [&](const CadModel* m) {
        const Eigen::Vector3d a = m->box_object.size_m, b = det.box_sensor.size_m.cwiseMax(1e-3);
        const double straight =
            std::max({std::abs(std::log(a.x() / b.x())), std::abs(std::log(a.y() / b.y()))});
        const double turned =
            std::max({std::abs(std::log(a.x() / b.y())), std::abs(std::log(a.y() / b.x()))});
        return std::max(std::min(straight, turned), std::abs(std::log(a.z() / b.z())));
    };
    // Closest in size first; a room's library may hold many variants of one style, and only the
    // `max_models` closest are worth the alignments.
    std::vector<std::pair<double, const CadModel*>> by_size;
    for (const CadModel* m : models) by_size.emplace_back(size_mismatch(m), m);
    std::stable_sort(by_size.begin(), by_size.end(),
                     [](const auto& a, const auto& b) { return a.first < b.first; });
    std::vector<const CadModel*> sized;
    for (const auto& [mismatch, m] : by_size) {
        if (mismatch <= params.max_size_mismatch &&
            static_cast<int>(sized.size()) < params.max_models)
            sized.push_back(m);
    }
    if (sized.empty()) sized.push_back(by_size.front().second);
    // The four yaw candidates of every model, ranked by their residual after a short coarse
    // alignment; the best two are refined fully and the lower final residual wins.
    struct Candidate {
        const CadModel* model;
        Pose4 pose;
        double e;
    };
    std::vector<Candidate> candidates;
    const LevelledSegment levelled =
        thin_to_levels(segment, *sized.front());  // every model has the library's levels
    const std::vector<Eigen::Vector3d>& coarse = levelled.per_level_sensor.front();
    for (const CadModel* m : sized) {
        for (int k = 0; k < 4; ++k) {
            Pose4 init;
            init.yaw_rad = wrap_angle(det.box_sensor.yaw_rad + k * kPi / 2);
            // Put the model's box centre on the detection's box centre.
            init.t_m = det.box_sensor.centre_m -
                       make_T_xyz_yaw({0, 0, 0}, init.yaw_rad).linear() * m->box_object.centre_m;
            init.t_m.z() =
                floor_z_m.value_or(det.box_sensor.z_min_m());  // the object stands on the floor
            Pose4 pose = init;
            if (params.candidate_iterations > 0) {
                IcpParams short_run = params.icp;
                short_run.iterations.assign(short_run.iterations.size(),
                                            params.candidate_iterations);
                pose = align(levelled, *m, init, short_run, 0, 0, FinalResidual::kSkip).pose;
            }
            // Ranked on every point: a back rest seen by few points is what tells the yaw flips
            // apart.
            candidates.push_back(
                {m, pose,
                 geometric_residual(coarse, *m, 0, pose, params.icp.max_correspondence_m.front())});
        }
    }
    std::sort(candidates.begin(), candidates.end(),
              [](const auto& a, const auto& b) { return a.e < b.e; });
    const CadModel* best_model = nullptr;
    double best_e = std::numeric_limits<double>::infinity();
    Pose4 best_pose;
    const int levels = static_cast<int>(sized.front()->levels.size());
    const int rank_level =
        std::max(0, levels - 2);  // candidates compete at the second-finest level
    const std::vector<Eigen::Vector3d>& ranked_points =
        levelled.per_level_sensor[static_cast<std::size_t>(rank_level)];
    std::vector<Candidate> refined;
    for (std::size_t i = 0;
         i < std::min<std::size_t>(candidates.size(),
                                   static_cast<std::size_t>(params.refined_candidates));
         ++i) {
        const IcpResult r = align(levelled, *candidates[i].model, candidates[i].pose, params.icp, 0,
                                  rank_level, FinalResidual::kSkip);
        // Ranked on every point: a back rest seen by few points tells the yaw flips apart.
        const double e = geometric_residual(
            ranked_points, *candidates[i].model, rank_level, r.pose,
            params.icp.max_correspondence_m[static_cast<std::size_t>(rank_level)]);
        refined.push_back({candidates[i].model, r.pose, e});
        if (e < best_e) best_e = e, best_pose = r.pose, best_model = candidates[i].model;
    }
    // A rival orientation that fits almost as well: the yaw is a guess (one side of a chair seen).
    // Turns that map the winning model onto itself (a table's half turn) are not rivals.
    double rival_e = std::numeric_limits<double>::infinity();
    for (const Candidate& c : refined) {
        const double turn = angle_diff(c.pose.yaw_rad, best_pose.yaw_rad);
        if (std::abs(turn) < kPi / 4) continue;
        const auto k = static_cast<std::size_t>((std::lround(turn / (kPi / 2)) % 4 + 4) % 4);
        if (!best_model->quarter_turn_symmetric[k]) rival_e = std::min(rival_e, c.e);
    }
    out.yaw_margin = rival_e / std::max(best_e, 1e-9) - 1.0;
    // Only the winner is refined at the finest level; acceptance uses its trimmed residual.
    take_fit(out, *best_model,
             align(levelled, *best_model, best_pose, params.icp,
                   rank_level + 1 < levels ? rank_level + 1 : rank_level));
    const bool approximate =
        out.residual_m > params.e_max_m && out.residual_m <= params.approx_e_max_m;
    if (out.residual_m > params.e_max_m && !approximate) {
        out.reason = "residual " + std::to_string(out.residual_m) + " m above e_max" +
                     (params.approx_e_max_m > 0.0 ? " and approx_e_max" : "");
        return out;
    }
    if (out.yaw_margin < params.min_yaw_margin) {
        out.reason = "ambiguous yaw: another orientation fits within " +
                     std::to_string(100.0 * out.yaw_margin) + " %";
        return out;
    }
    out.accepted = true;
    out.approximate = approximate;
    out.p_exist = approximate
                      ? std::clamp(det.score, 0.0, 1.0)
                      : existence_probability(out.residual_m, params.e_min_m, params.e_max_m);
    if (approximate) {
        // The model is not the object: its orientation is what the fit gives; its extent (a model
        // 30 % narrower fits into a corner of the scan) is not. The network's box, turned.
        const double turn = angle_diff(out.box_sensor.yaw_rad, det.box_sensor.yaw_rad);
        OrientedBox box = det.box_sensor;
        box.yaw_rad = out.box_sensor.yaw_rad;
        if (std::abs(std::abs(turn) - kPi / 2) < kPi / 4) std::swap(box.size_m.x(), box.size_m.y());
        out.box_sensor = box;
    }
    return out;
}

// One ICP from an earlier fit of the same object: most objects stand where they stood, and their
// model and yaw are known; the full search (every model, four yaw candidates, four refined) is
// for objects seen anew or turned since. The seed's own residual bounds the answer, so a chair
// turned half round, whose old yaw still fits it loosely, goes to the full search.
std::optional<VerifiedDetection> verify_from_seed(const std::vector<Eigen::Vector3d>& segment,
                                                  const Detection& det, const VerifySeed& seed,
                                                  const VerifyParams& params) {
    if (segment.size() < params.min_points) return std::nullopt;
    const IcpResult fit = align(segment, *seed.model, seed.pose, params.icp,
                                1);  // a seed is within the 4 cm level's reach
    if (!(fit.residual_m <= std::min(params.e_max_m, seed.residual_m + params.reseed_tolerance_m)))
        return std::nullopt;
    VerifiedDetection out;
    out.detection = det;
    out.segment_points = segment.size();
    take_fit(out, *seed.model, fit);
    out.yaw_margin = std::numeric_limits<double>::infinity();  // no rival tried
    out.accepted = true;
    out.from_seed = true;
    out.p_exist = existence_probability(fit.residual_m, params.e_min_m, params.e_max_m);
    return out;
}

// verify_detection() on the detection's segment, cut from the view before.
VerifiedDetection verify_segment(const CloudView& view, const std::vector<Eigen::Vector3d>& segment,
                                 const Detection& det, const CadLibrary& library,
                                 const VerifyParams& params, std::optional<double> floor_z_m,
                                 const ShapePrior* prior, const VerifySeed* seed) {
    if (seed && seed->model && params.reseed_tolerance_m > 0.0 && params.min_yaw_margin <= 0.0) {
        if (auto seeded = verify_from_seed(segment, det, *seed, params)) return std::move(*seeded);
    }
    VerifiedDetection cad = verify_with_cad(segment, det, library, params, floor_z_m);
    if (cad.accepted || !prior || cad.segment_points < params.min_points) return cad;
    // No CAD model fits: the prior's model of this object, verified the same way from its pose.
    const double floor_z = floor_z_m.value_or(det.box_sensor.z_min_m());
    auto estimate = prior->estimate(segment, det.cls, floor_z);
    if (!estimate || estimate->mesh_object.triangles.empty()) {
        cad.reason += "; shape prior: no estimate";
        return cad;
    }
    CadLibrary own(library.params());
    own.add(kCompletedShapeModel, det.cls, estimate->mesh_object);
    Detection seeded = det;
    seeded.box_sensor = own.models().front().box_object.transformed(estimate->T_sensor_object);
    VerifyParams shape_params = params;
    shape_params.e_max_m = std::max(params.shape_e_max_m, params.e_min_m + 1e-6);
    shape_params.approx_e_max_m = 0.0;  // the completed shape is the object's own: no second level
    VerifiedDetection shaped = verify_with_cad(view.segment(seeded.box_sensor, params.box_margin_m),
                                               seeded, own, shape_params, floor_z);
    shaped.detection = det;
    if (!shaped.accepted) {
        cad.reason += "; completed shape: " + shaped.reason;
        return cad;
    }
    shaped.shape = std::move(*estimate);
    return shaped;
}

}  // namespace

VerifiedDetection verify_detection(const PointCloud& cloud, const Detection& det,
                                   const CadLibrary& library, const VerifyParams& params,
                                   std::optional<double> floor_z_m, const ShapePrior* prior,
                                   const VerifySeed* seed) {
    const CloudView view{cloud};
    return verify_segment(view, view.segment(det.box_sensor, params.box_margin_m), det, library,
                          params, floor_z_m, prior, seed);
}

std::vector<VerifiedDetection> verify_detections(
    const PointCloud& cloud, const std::vector<Detection>& detections, const CadLibrary& library,
    const VerifyParams& params,
    const std::function<std::optional<double>(double, double)>& floor_z_at, const ShapePrior* prior,
    const std::vector<std::optional<VerifySeed>>& seeds) {
    if (!seeds.empty() && seeds.size() != detections.size()) {
        throw std::invalid_argument("verify_detections: " + std::to_string(seeds.size()) +
                                    " seeds for " + std::to_string(detections.size()) +
                                    " detections");
    }
    std::vector<VerifiedDetection> out(detections.size());
    const PlaneBuckets buckets(cloud, kBucket_m);
    const CloudView view{cloud, &buckets};
    std::vector<std::vector<Eigen::Vector3d>> segments(detections.size());
    for (std::size_t i = 0; i < detections.size(); ++i)
        segments[i] = view.segment(detections[i].box_sensor, params.box_margin_m);
    auto verify_one = [&](std::size_t i) {
        const Detection& d = detections[i];
        const std::optional<double> floor_z =
            floor_z_at ? floor_z_at(d.box_sensor.centre_m.x(), d.box_sensor.centre_m.y())
                       : std::nullopt;
        const VerifySeed* seed = seeds.empty() || !seeds[i] ? nullptr : &*seeds[i];
        out[i] = verify_segment(view, segments[i], d, library, params, floor_z, prior, seed);
        segments[i] = {};
    };
    if (params.num_threads <= 1 || detections.size() < 2) {
        for (std::size_t i = 0; i < detections.size(); ++i) verify_one(i);
        return out;
    }
    // The largest segments first (their fits take longest): the threads then end together
    // instead of one finishing a large table alone while the other waits.
    std::vector<std::size_t> order(detections.size());
    std::iota(order.begin(), order.end(), std::size_t{0});
    std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
        return segments[a].size() > segments[b].size();
    });
    std::atomic<std::size_t> next{0};
    std::exception_ptr failure;
    std::mutex failure_mutex;
    auto work = [&] {
        try {
            for (std::size_t k = next++; k < order.size(); k = next++) verify_one(order[k]);
        } catch (...) {
            const std::lock_guard<std::mutex> lock(failure_mutex);
            if (!failure) failure = std::current_exception();
            next = detections.size();  // the others stop after their current detection
        }
    };
    std::vector<std::thread> helpers;
    const std::size_t n_helpers =
        std::min<std::size_t>(static_cast<std::size_t>(params.num_threads), detections.size()) - 1;
    try {
        for (std::size_t h = 0; h < n_helpers; ++h) helpers.emplace_back(work);
    } catch (const std::system_error&) {
        // No more threads to be had: those started and this one share the work.
    }
    work();
    for (std::thread& t : helpers) t.join();
    if (failure) std::rethrow_exception(failure);
    return out;
}

std::vector<Detection> accepted_detections(const std::vector<VerifiedDetection>& verified,
                                           ScoreFrom score, bool keep_unfitted) {
    std::vector<Detection> out;
    for (const VerifiedDetection& v : verified) {
        if (!v.accepted) continue;
        Detection d = v.detection;
        d.box_sensor = v.box_sensor;
        if (score == ScoreFrom::kExistence) d.score = v.p_exist;
        out.push_back(d);
    }
    // After the accepted ones, so that their indices stay those of the accepted fits.
    if (keep_unfitted) {
        for (const VerifiedDetection& v : verified) {
            if (!v.accepted) out.push_back(v.detection);
        }
    }
    return out;
}

}  // namespace makeway::verification
