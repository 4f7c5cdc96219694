#include "makeway/eval/shape_dataset.hpp"

#include <tbb/global_control.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <map>
#include <stdexcept>

#include "makeway/common/random.hpp"
#include "makeway/eval/detection_dataset.hpp"
#include "makeway/shape/mesh_sdf.hpp"
#include "makeway/sim/lidar.hpp"
#include "makeway/sim/robot.hpp"
#include "makeway/sim/scene_dynamics.hpp"
#include "makeway/sim/scene_generator.hpp"
#include "makeway/sim/world.hpp"

namespace makeway::eval {

namespace {

// Free places to look from: the scene's own poses, then random floor points clear of every box.
std::vector<Pose2> viewpoints(const sim::Scene& scene, const std::vector<sim::ObjectModel>& models,
                              int count, Rng& rng) {
    std::vector<Pose2> out{scene.start, scene.waypoint, scene.goal};
    for (int tries = 0; static_cast<int>(out.size()) < count && tries < 2000; ++tries) {
        const Eigen::Vector2d xy(
            uniform(rng, scene.floor_min_m.x() + 0.5, scene.floor_max_m.x() - 0.5),
            uniform(rng, scene.floor_min_m.y() + 0.5, scene.floor_max_m.y() - 0.5));
        bool clear = true;
        for (std::size_t i = 0; i < scene.objects.size() && clear; ++i) {
            const Isometry2 T = to_isometry(scene.objects[i].pose);
            const Eigen::Vector2d local = T.inverse() * xy;
            const Eigen::Vector3d half =
                models[i].box_object.size_m / 2 + Eigen::Vector3d::Constant(0.3);
            clear = std::abs(local.x() - models[i].box_object.centre_m.x()) > half.x() ||
                    std::abs(local.y() - models[i].box_object.centre_m.y()) > half.y();
        }
        for (const auto& w : scene.walls) {
            if (!clear) break;
            const Eigen::Vector2d d = w.b_m - w.a_m;
            const double t =
                std::clamp((xy - w.a_m).dot(d) / std::max(1e-9, d.squaredNorm()), 0.0, 1.0);
            clear = (w.a_m + t * d - xy).norm() > 0.4;
        }
        if (clear) out.push_back({xy.x(), xy.y(), uniform(rng, -M_PI, M_PI)});
    }
    out.resize(std::min<std::size_t>(out.size(), static_cast<std::size_t>(count)));
    return out;
}

shape::Similarity3 truth_of(const Pose2& pose, const OrientedBox& box_object,
                            const Eigen::Vector3d& gravity_origin) {
    shape::Similarity3 T;
    T.scale = 0.5 * box_object.size_m.norm();
    T.rotation = Eigen::AngleAxisd(pose.yaw_rad, Eigen::Vector3d::UnitZ()).toRotationMatrix();
    T.translation = T.rotation * box_object.centre_m + Eigen::Vector3d(pose.x_m, pose.y_m, 0.0) -
                    gravity_origin;
    return T;
}

void fill_targets(shape::ShapeExample& shape, std::vector<Eigen::Vector3d>& surface,
                  const TriangleMesh& mesh, const OrientedBox& box, const ShapeDatasetParams& p,
                  std::uint64_t seed) {
    const double scale = 0.5 * box.size_m.norm();
    const shape::MeshSdf sdf(mesh, box.centre_m, 1.0 / scale);
    surface = sdf.sample_surface(static_cast<std::size_t>(p.surface_samples), seed);
    const auto near =
        sdf.sample_surface(static_cast<std::size_t>(p.sdf_samples + p.occupancy_samples), seed + 1);
    Rng rng = make_rng(seed, 77);
    auto uniform_point = [&] {
        return Eigen::Vector3d(uniform(rng, -1.1, 1.1), uniform(rng, -1.1, 1.1),
                               uniform(rng, -1.1, 1.1));
    };
    auto jitter = [&](const Eigen::Vector3d& q, double s) {
        return Eigen::Vector3d(
            q + Eigen::Vector3d(normal(rng, 0, s), normal(rng, 0, s), normal(rng, 0, s)));
    };
    for (int i = 0; i < p.sdf_samples; ++i) {
        const Eigen::Vector3d q =
            i % 5 == 4 ? uniform_point()
                       : jitter(near[static_cast<std::size_t>(i)], i % 5 < 2 ? 0.01 : 0.04);
        shape.sdf_points.push_back(q.cast<float>());
        shape.sdf.push_back(static_cast<float>(sdf.signed_distance(q)));
    }
    for (int i = 0; i < p.occupancy_samples; ++i) {
        const Eigen::Vector3d q =
            i % 2 ? uniform_point()
                  : jitter(near[static_cast<std::size_t>(p.sdf_samples + i)], 0.03);
        shape.occupancy_points.push_back(q.cast<float>());
        shape.occupied.push_back(sdf.inside(q) ? 1 : 0);
    }
    std::vector<Eigen::Vector3d> probe(
        surface.begin(), surface.begin() + std::min<std::ptrdiff_t>(
                                               200, static_cast<std::ptrdiff_t>(surface.size())));
    shape.symmetry_yaws = shape::detect_symmetry_yaws(
        probe, [&](const Eigen::Vector3d& q) { return sdf.unsigned_distance(q); });
}

}  // namespace

ShapeDataset generate_shape_dataset(const ShapeDatasetParams& p,
                                    const std::function<void(int, int)>& progress) {
    DatasetParams styles;
    styles.all_styles = true;
    styles.exclude_styles = p.exclude_styles;
    styles.only_styles = p.only_styles;
    ShapeDataset out;
    std::map<std::pair<std::string, std::uint64_t>, int> shape_index;
    Rng rng = make_rng(p.seed, 4242);
    const sim::RobotParams robot;
    for (int k = 0; k < p.scenes; ++k) {
        sim::SceneGenParams g;
        g.seed = p.seed * 1000 + 7 + static_cast<std::uint64_t>(k);
        g.density = k % 2 ? sim::Density::kDense : sim::Density::kMedium;
        g.people = false;
        sim::Scene scene = sim::generate_scene(g);
        restyle_scene(scene, styles);
        const std::vector<sim::ObjectModel> models = sim::models_of(scene);
        sim::World world(scene, models);
        const auto places = viewpoints(scene, models, p.viewpoints_per_scene, rng);
        for (std::size_t v = 0; v < places.size(); ++v) {
            const Isometry3 T_world_sensor = lift_to_3d(places[v]) * robot.T_robot_sensor();
            const PointCloud cloud = sim::simulate_sweep(
                world, {}, [&](double) { return T_world_sensor; }, 0.0, g.seed, v);
            std::vector<Eigen::Vector3d> world_pts(cloud.size());
            for (std::size_t i = 0; i < cloud.size(); ++i)
                world_pts[i] = T_world_sensor * cloud.xyz[i].cast<double>();
            const Eigen::Vector3d sensor = T_world_sensor.translation();
            for (std::size_t o = 0; o < scene.objects.size(); ++o) {
                const sim::SceneObject& obj = scene.objects[o];
                std::vector<Eigen::Vector3d> own;
                for (std::size_t i = 0; i < cloud.size(); ++i) {
                    if (cloud.instance[i] == obj.id && world_pts[i].z() > p.ground_band_m)
                        own.push_back(world_pts[i]);
                }
                if (own.size() < p.min_points) continue;
                Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
                for (const auto& q : own) centroid += q / static_cast<double>(own.size());
                const Eigen::Vector3d origin(centroid.x(), centroid.y(), 0.0);
                shape::ShapeView view;
                view.origin = sensor - origin;
                view.truth = truth_of(obj.pose, models[o].box_object, origin);
                const double share = uniform(rng, 0.0, p.max_outlier_share);
                for (const auto& q : own) {
                    if (bernoulli(rng, share)) {  // a depth outlier on the same ray
                        const Eigen::Vector3d moved =
                            sensor + (q - sensor) * uniform(rng, 0.7, 1.3);
                        view.points.push_back(moved - origin);
                        view.outlier.push_back((moved - q).norm() > 0.05 ? 1 : 0);
                    } else {
                        view.points.push_back(q - origin);
                        view.outlier.push_back(0);
                    }
                }
                // Everything else inside the object's box grown by 10 cm: what a detector's box
                // hands verification along with the object.
                const Isometry3 T_obj = lift_to_3d(obj.pose);
                const Eigen::Vector3d half =
                    models[o].box_object.size_m / 2 + Eigen::Vector3d(0.1, 0.1, 0.0);
                for (std::size_t i = 0; i < cloud.size(); ++i) {
                    if (cloud.instance[i] == obj.id || world_pts[i].z() <= p.ground_band_m)
                        continue;
                    const Eigen::Vector3d local =
                        T_obj.inverse() * world_pts[i] - models[o].box_object.centre_m;
                    if ((local.cwiseAbs().array() <= half.array()).all()) {
                        view.points.push_back(world_pts[i] - origin);
                        view.outlier.push_back(1);
                    }
                }
                const auto key = std::make_pair(obj.style, obj.model_seed);
                auto it = shape_index.find(key);
                if (it == shape_index.end()) {
                    it = shape_index.emplace(key, static_cast<int>(out.shapes.size())).first;
                    shape::ShapeExample ex;
                    ex.cls = obj.cls;
                    ex.style = obj.style;
                    out.shapes.push_back(std::move(ex));
                    out.scale_m.push_back(0.5 * models[o].box_object.size_m.norm());
                    out.mesh_object.push_back(models[o].mesh_object);
                    out.box_object.push_back(models[o].box_object);
                }
                view.shape = it->second;
                out.own_points_of_view.push_back(own.size());
                out.scene_of_view.push_back(k);
                out.object_of_view.push_back(obj.id);
                out.views.push_back(std::move(view));
            }
        }
        if (progress) progress(k + 1, p.scenes);
    }
    // Targets per shape: the costly part (a winding number per sample), in parallel.
    out.surface.resize(out.shapes.size());
    std::unique_ptr<tbb::global_control> limit;
    if (p.threads > 0)
        limit = std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism,
                                                      static_cast<std::size_t>(p.threads));
    tbb::parallel_for(std::size_t{0}, out.shapes.size(), [&](std::size_t s) {
        fill_targets(out.shapes[s], out.surface[s], out.mesh_object[s], out.box_object[s], p,
                     p.seed * 7919 + s);
    });
    return out;
}

}  // namespace makeway::eval
