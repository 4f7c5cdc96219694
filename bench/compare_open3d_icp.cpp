// Side-by-side comparison of makeway's 4-DoF point-to-plane ICP with Open3D's point-to-plane ICP
// (benchmark only; Open3D is not a runtime dependency). Same inputs: the verification benchmark's
// simulated keyframes and corrupted ground-truth boxes, the object's own CAD model, the same
// voxel-thinned segment per level, the same model points and normals per level, the same
// correspondence distances, iteration caps and Cauchy scales. Two comparisons:
//   icp:    one alignment from the detection's own yaw (noise, no flip), 3 levels coarse to fine
//   verify: boxes with yaw flips; makeway's verify_detection against Open3D run from all four yaw
//           candidates, keeping the lowest inlier RMSE
// Run on one core: OMP_NUM_THREADS=1 (Open3D parallelises correspondences with OpenMP).
#include <open3d/geometry/PointCloud.h>
#include <open3d/pipelines/registration/Registration.h>
#include <open3d/pipelines/registration/RobustKernel.h>
#include <open3d/pipelines/registration/TransformationEstimation.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <optional>
#include <string>

#include "makeway/common/angles.hpp"
#include "makeway/common/random.hpp"
#include "makeway/common/statistics.hpp"
#include "makeway/eval/verify_bench.hpp"
#include "makeway/sim/furniture.hpp"

namespace {

using namespace makeway;
namespace reg = open3d::pipelines::registration;

struct Arm {
    std::vector<double> yaw_err_deg, centre_err_m, ms;
    void add(double yaw_deg, double centre_m, double t_ms) {
        yaw_err_deg.push_back(yaw_deg), centre_err_m.push_back(centre_m), ms.push_back(t_ms);
    }
};

double share_within(const std::vector<double>& v, double limit) {
    return v.empty() ? 0.0
                     : static_cast<double>(std::count_if(v.begin(), v.end(),
                                                         [&](double x) { return x <= limit; })) /
                           v.size();
}

double ms_since(std::chrono::steady_clock::time_point t0) {
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

// Open3D, 3 levels with the same budget as makeway's IcpParams; returns T_sensor_object.
reg::RegistrationResult open3d_align(const verification::LevelledSegment& seg,
                                     const std::vector<open3d::geometry::PointCloud>& targets,
                                     const Isometry3& T_sensor_object_init,
                                     const verification::IcpParams& p,
                                     const verification::CadModel& model) {
    Eigen::Matrix4d T_object_sensor = T_sensor_object_init.inverse().matrix();
    reg::RegistrationResult r;
    for (std::size_t level = 0; level < targets.size(); ++level) {
        open3d::geometry::PointCloud source;
        source.points_ = seg.per_level_sensor[level];
        const double c = std::max(p.cauchy_scale_m, model.levels[level].voxel_m);
        r = reg::RegistrationICP(
            source, targets[level], p.max_correspondence_m[level], T_object_sensor,
            reg::TransformationEstimationPointToPlane(std::make_shared<reg::CauchyLoss>(c)),
            reg::ICPConvergenceCriteria(1e-6, 1e-6, p.iterations[level]));
        T_object_sensor = r.transformation_;
    }
    return r;
}

}  // namespace

int main(int argc, char** argv) {
    const int scenes = argc > 1 ? std::atoi(argv[1]) : 6;
    const verification::IcpParams icp;
    const verification::VerifyParams vp;
    Rng rng = make_rng(0, 900);
    Arm ours_icp, o3d_icp, ours_verify, o3d_verify;
    for (int k = 0; k < scenes; ++k) {
        const eval::BenchKeyframe kf = eval::simulate_bench_keyframe(0, k);
        std::map<std::uint32_t, std::size_t> points_of;
        for (std::uint32_t id : kf.cloud_sensor.instance) ++points_of[id];
        for (std::size_t i = 0; i < kf.scene.objects.size(); ++i) {
            const sim::SceneObject& o = kf.scene.objects[i];
            if (points_of[o.id] < 100) continue;
            verification::CadLibrary lib;
            lib.add(o.style, o.cls,
                    sim::make_furniture(*sim::parse_furniture_style(o.style), o.model_seed)
                        .mesh_object);
            const verification::CadModel& model = lib.models().front();
            std::vector<open3d::geometry::PointCloud> targets(model.levels.size());
            for (std::size_t l = 0; l < model.levels.size(); ++l) {
                targets[l].points_ = model.levels[l].points_object;
                targets[l].normals_ = model.levels[l].normals_object;
            }
            const Isometry3 T_sensor_object = kf.T_world_sensor.inverse() * lift_to_3d(o.pose);
            const OrientedBox truth = kf.models[i].box_object.transformed(T_sensor_object);
            Detection det;
            det.cls = o.cls;
            det.box_sensor = truth;
            det.box_sensor.centre_m +=
                Eigen::Vector3d(normal(rng, 0, 0.06), normal(rng, 0, 0.06), normal(rng, 0, 0.03));
            const double noise = normal(rng, 0, deg_to_rad(5.0));
            const int flip = static_cast<int>(uniform_int(rng, 0, 3));
            const double floor_z = kf.floor_z_m(det.box_sensor.centre_m);
            const auto score = [&](Arm& arm, const Isometry3& T, double ms) {
                const auto e = eval::yaw_error_deg(o.style, yaw_of(T), yaw_of(T_sensor_object));
                if (!e) return;
                const OrientedBox b = model.box_object.transformed(T);
                arm.add(*e, (b.centre_m - truth.centre_m).head<2>().norm(), ms);
            };
            const std::vector<Eigen::Vector3d> segment =
                verification::segment_points(kf.cloud_sensor, det.box_sensor, vp.box_margin_m);
            auto initial = [&](double yaw) {
                verification::Pose4 init;
                init.yaw_rad = wrap_angle(yaw);
                init.t_m =
                    det.box_sensor.centre_m -
                    make_T_xyz_yaw({0, 0, 0}, init.yaw_rad).linear() * model.box_object.centre_m;
                init.t_m.z() = floor_z;
                return init;
            };
            // icp: from the detection's own yaw.
            {
                const auto init = initial(truth.yaw_rad + noise);
                auto t0 = std::chrono::steady_clock::now();
                const verification::LevelledSegment seg =
                    verification::thin_to_levels(segment, model);
                const verification::IcpResult r = verification::align(seg, model, init, icp);
                score(ours_icp, r.pose.matrix(), ms_since(t0));
                t0 = std::chrono::steady_clock::now();
                const verification::LevelledSegment seg2 =
                    verification::thin_to_levels(segment, model);
                const reg::RegistrationResult o3 =
                    open3d_align(seg2, targets, init.matrix(), icp, model);
                score(o3d_icp, Isometry3(Eigen::Matrix4d(o3.transformation_.inverse())),
                      ms_since(t0));
            }
            // verify: with a yaw flip, from all four candidates.
            {
                det.box_sensor.yaw_rad = wrap_angle(truth.yaw_rad + noise + flip * kPi / 2);
                auto t0 = std::chrono::steady_clock::now();
                const verification::VerifiedDetection v =
                    verification::verify_detection(kf.cloud_sensor, det, lib, vp, floor_z);
                score(ours_verify, v.T_sensor_object, ms_since(t0));
                t0 = std::chrono::steady_clock::now();
                const verification::LevelledSegment seg = verification::thin_to_levels(
                    verification::segment_points(kf.cloud_sensor, det.box_sensor, vp.box_margin_m),
                    model);
                reg::RegistrationResult best;
                double best_rmse = 1e9;
                for (int c = 0; c < 4; ++c) {
                    const reg::RegistrationResult r = open3d_align(
                        seg, targets, initial(det.box_sensor.yaw_rad + c * kPi / 2).matrix(), icp,
                        model);
                    if (r.fitness_ > 0 && r.inlier_rmse_ < best_rmse)
                        best_rmse = r.inlier_rmse_, best = r;
                }
                score(o3d_verify, Isometry3(Eigen::Matrix4d(best.transformation_.inverse())),
                      ms_since(t0));
            }
        }
        std::fprintf(stderr, "\rscene %d/%d", k + 1, scenes);
    }
    std::fprintf(stderr, "\n");
    std::printf(
        "| comparison | implementation | objects | yaw within 10 deg | median yaw error [deg] | "
        "median centre error [m] | median ms | time ratio |\n");
    std::printf("| --- | --- | --- | --- | --- | --- | --- | --- |\n");
    const auto row = [](const char* what, const char* who, const Arm& a, const Arm& ref) {
        std::printf("| %s | %s | %zu | %.3f | %.2f | %.3f | %.3f | %.2f |\n", what, who,
                    a.ms.size(), share_within(a.yaw_err_deg, 10.0), median(a.yaw_err_deg),
                    median(a.centre_err_m), median(a.ms), median(a.ms) / median(ref.ms));
    };
    row("icp, own yaw", "makeway (4-DoF)", ours_icp, ours_icp);
    row("icp, own yaw", "Open3D (6-DoF)", o3d_icp, ours_icp);
    row("4 yaw candidates", "makeway verify", ours_verify, ours_verify);
    row("4 yaw candidates", "Open3D best RMSE", o3d_verify, ours_verify);
    return 0;
}
