// makeway train-shape, bench shape, complete: the shape networks (issue 19).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iomanip>
#include <iostream>
#include <sstream>

#include "apps/command.hpp"
#include "apps/model_path.hpp"
#include "io/canvas.hpp"
#include "io/error.hpp"
#include "io/file_util.hpp"
#include "io/json_io.hpp"
#include "io/mesh_io.hpp"
#include "io/point_cloud_io.hpp"
#include "io/progress.hpp"
#include "io/staged_output.hpp"
#include "makeway/common/angles.hpp"
#include "makeway/eval/shape_bench.hpp"
#include "makeway/shape/shape_training.hpp"

namespace makeway::apps {

struct TrainShapeOptions {
    int scenes = 24;
    std::uint64_t seed = 0;
    std::vector<std::string> exclude_styles{"armchair", "round_table"};
    double steps_scale = 1.0;  ///< every stage's step count times this
    int threads = 2;
    std::string out = "models/shape.pt";
};

struct CompleteOptions {
    std::string model;  ///< empty: models/shape.pt
    std::string cloud;
    std::string box;  ///< "cx,cy,cz,length,width,height,yaw" in the cloud's frame
    std::string cls;
    std::string sensor = "0,0,0";  ///< where the returns were seen from, in the cloud's frame
    std::string out;
};

struct BenchShapeOptions {
    std::string model;  ///< empty: models/shape.pt
    /// The benchmark's parameters, filled by the options directly (`completion` by --pose-only);
    /// the command line leaves out the two styles models/shape.pt was trained without.
    eval::ShapeBenchParams params = [] {
        eval::ShapeBenchParams p;
        p.left_out_styles = {"armchair", "round_table"};
        return p;
    }();
    int threads = 1;
    bool pose_only = false;
    std::string out_dir = "out/bench_shape";
};

namespace fs = std::filesystem;

namespace {

io::Json loss_json(const shape::NetLoss& l) { return {{"first", l.first}, {"last", l.last}}; }

// A small flat-shaded renderer for the gallery: an oblique orthographic view (turned 35 deg about
// z, tilted 25 deg), triangles painted far to near.
struct View {
    Eigen::Matrix3d R;
    View() {
        R = Eigen::AngleAxisd(-deg_to_rad(65.0), Eigen::Vector3d::UnitX()).toRotationMatrix() *
            Eigen::AngleAxisd(deg_to_rad(-35.0), Eigen::Vector3d::UnitZ()).toRotationMatrix();
    }
    Eigen::Vector3d operator()(const Eigen::Vector3d& p) const {
        return R * p;
    }  // x right, y up, z towards the viewer
};

void draw_mesh(io::Canvas& canvas, const TriangleMesh& mesh, const Eigen::Vector2d& at,
               const View& view, const io::Rgb& colour) {
    struct Face {
        double depth;
        std::vector<Eigen::Vector2d> poly;
        double shade;
    };
    std::vector<Face> faces;
    const Eigen::Vector3d light = Eigen::Vector3d(0.3, 0.5, 1.0).normalized();
    for (const auto& t : mesh.triangles) {
        Eigen::Vector3d q[3];
        for (int k = 0; k < 3; ++k)
            q[k] = view(mesh.vertices_m[static_cast<std::size_t>(t[k])].cast<double>());
        const Eigen::Vector3d n = (q[1] - q[0]).cross(q[2] - q[0]);
        if (n.norm() < 1e-12) continue;
        Face f;
        f.depth = (q[0].z() + q[1].z() + q[2].z()) / 3;
        for (const auto& p : q) f.poly.push_back(at + p.head<2>());
        f.shade = 0.35 + 0.65 * std::abs(n.normalized().dot(light));
        faces.push_back(std::move(f));
    }
    std::sort(faces.begin(), faces.end(),
              [](const Face& a, const Face& b) { return a.depth < b.depth; });
    for (const Face& f : faces)
        canvas.fill_polygon(f.poly,
                            {colour[0] * f.shade, colour[1] * f.shade, colour[2] * f.shade});
}

void write_gallery(const fs::path& path, const std::vector<eval::ShowcaseShape>& shapes) {
    if (shapes.empty()) return;
    const double cell = 2.6;
    const int rows = static_cast<int>(shapes.size());
    io::Canvas canvas({0, -cell * rows}, {4 * cell, 0.4}, 90.0, 0.1);
    const View view;
    const char* titles[4] = {"observed returns", "F_0 fitted", "F_1 completed", "truth"};
    for (int c = 0; c < 4; ++c) canvas.text({c * cell + 0.2, 0.15}, titles[c], 16, {0.1, 0.1, 0.1});
    for (int r = 0; r < rows; ++r) {
        const eval::ShowcaseShape& s = shapes[static_cast<std::size_t>(r)];
        const double y = -cell * r - cell / 2;
        std::vector<std::pair<double, Eigen::Vector2d>> dots;
        for (const auto& p : s.partial) {
            const Eigen::Vector3d q = view(p);
            dots.emplace_back(q.z(), Eigen::Vector2d(cell / 2 + q.x(), y + q.y()));
        }
        std::sort(dots.begin(), dots.end(),
                  [](const auto& a, const auto& b) { return a.first < b.first; });
        for (const auto& [d, p] : dots) canvas.dot(p, 2.5, {0.15, 0.35, 0.75});
        draw_mesh(canvas, s.prior, {1.5 * cell, y}, view, {0.85, 0.6, 0.3});
        draw_mesh(canvas, s.completed, {2.5 * cell, y}, view, {0.3, 0.7, 0.4});
        draw_mesh(canvas, s.truth, {3.5 * cell, y}, view, {0.6, 0.6, 0.65});
        canvas.text({0.1, y + cell / 2 - 0.35}, s.name, 14, {0.2, 0.2, 0.2});
    }
    canvas.save_png(path);
}

std::string percent(double x) {
    std::ostringstream s;
    s << std::fixed << std::setprecision(1) << 100.0 * x << " %";
    return s.str();
}

std::string fixed(double x, int digits) {
    std::ostringstream s;
    s << std::fixed << std::setprecision(digits) << x;
    return s.str();
}

}  // namespace

int run_train_shape(const TrainShapeOptions& o) {
    eval::ShapeDatasetParams dp;
    dp.scenes = o.scenes;
    dp.seed = o.seed;
    dp.exclude_styles = o.exclude_styles;
    dp.threads = o.threads;
    io::ProgressBar render("render", static_cast<std::size_t>(o.scenes));
    const eval::ShapeDataset data = eval::generate_shape_dataset(
        dp, [&](int done, int) { render.update(static_cast<std::size_t>(done)); });
    render.finish();
    std::size_t per_class[2] = {0, 0};
    for (const auto& s : data.shapes) ++per_class[std::max(0, shape::shape_class_index(s.cls))];
    std::cout << "dataset: " << data.shapes.size() << " shapes (" << per_class[0] << " chairs, "
              << per_class[1] << " tables), " << data.views.size() << " views\n";
    shape::ShapeModelParams mp;
    mp.seed = o.seed;
    shape::ShapeModel model(mp);
    shape::ShapeTrainParams tp;
    tp.seed = o.seed;
    tp.threads = o.threads;
    tp.correspondence_steps =
        static_cast<int>(std::lround(tp.correspondence_steps * o.steps_scale));
    tp.sdf_steps = static_cast<int>(std::lround(tp.sdf_steps * o.steps_scale));
    tp.occupancy_steps = static_cast<int>(std::lround(tp.occupancy_steps * o.steps_scale));
    const std::size_t total =
        2u * static_cast<std::size_t>(tp.correspondence_steps + tp.sdf_steps + tp.occupancy_steps);
    io::ProgressBar bar("train", total);
    std::size_t done = 0;
    double smoothed = 0.0;
    std::string last_stage;
    const shape::ShapeTrainReport r = shape::train_shape_model(
        model, data, tp, [&](const std::string& stage, int, int, double loss) {
            if (stage != last_stage) smoothed = loss, last_stage = stage;
            smoothed = 0.95 * smoothed + 0.05 * loss;
            bar.update(++done, stage + " loss " + fixed(smoothed, 4));
        });
    bar.finish();
    model.save(o.out);
    io::Json report = {
        {"model", o.out},
        {"seed", o.seed},
        {"scenes", o.scenes},
        {"excluded_styles", o.exclude_styles},
        {"shapes", data.shapes.size()},
        {"views", data.views.size()},
        {"parameters", model.parameter_count()},
        {"seconds", r.seconds},
        {"stage_seconds",
         {{"F_n", r.stage_seconds[0]}, {"F_0", r.stage_seconds[1]}, {"F_1", r.stage_seconds[2]}}},
        {"steps",
         {{"correspondence", tp.correspondence_steps},
          {"sdf", tp.sdf_steps},
          {"occupancy", tp.occupancy_steps}}}};
    for (int c = 0; c < 2; ++c) {
        const std::string name = c == 0 ? "chair" : "table";
        report["loss"][name] = {{"F_n", loss_json(r.correspondence[c])},
                                {"F_0", loss_json(r.sdf[c])},
                                {"F_1", loss_json(r.occupancy[c])}};
    }
    io::write_json(o.out + ".json", report);
    std::cout << "wrote " << o.out << " (" << model.parameter_count() << " parameters, "
              << fixed(r.seconds / 60.0, 1) << " min of training)\n";
    return 0;
}

int run_bench_shape(const BenchShapeOptions& o) {
    const shape::ShapeModel model = load_shape_model(o.model);
    if (o.threads > 0) shape::set_threads(o.threads);
    eval::ShapeBenchParams p = o.params;
    p.completion = !o.pose_only;
    std::unique_ptr<io::ProgressBar> bar;
    std::string current;
    const eval::ShapeBenchResult r =
        eval::run_shape_bench(model, p, [&](const std::string& what, int done, int total) {
            if (what != current) {
                if (bar) bar->finish();
                bar = std::make_unique<io::ProgressBar>(what, static_cast<std::size_t>(total));
                current = what;
            }
            bar->update(static_cast<std::size_t>(done));
        });
    if (bar) bar->finish();
    io::StagedOutput staged(o.out_dir);  // summary, table and gallery: all or none
    const fs::path out = staged.staging();
    io::Json j = {{"scenes", p.scenes},
                  {"seed", p.seed},
                  {"left_out_styles", p.left_out_styles},
                  {"min_points", p.min_points}};
    std::ostringstream md;
    md << "| set | class | views | yaw <= 10 deg | centre <= 5 cm | median yaw err | median centre "
          "err | objects | Chamfer-L1 partial / F_0 / F_1 [cm] | IoU partial / F_0 / F_1 |\n"
       << "|---|---|---|---|---|---|---|---|---|---|\n";
    for (const auto& set : r.sets) {
        for (int c = 0; c < 2; ++c) {
            const std::string name = c == 0 ? "chair" : "table";
            const eval::PoseStats& ps = set.pose[c];
            const eval::CompletionStats& cs = set.completion[c];
            j["sets"][set.name][name] = {{"pose",
                                          {{"views", ps.views},
                                           {"yaw_scored", ps.yaw_scored},
                                           {"yaw_within_10deg", ps.yaw_within_10deg},
                                           {"centre_within_5cm", ps.centre_within_5cm},
                                           {"median_yaw_error_deg", ps.median_yaw_error_deg},
                                           {"median_centre_error_m", ps.median_centre_error_m},
                                           {"failed", ps.failed}}},
                                         {"completion",
                                          {{"objects", cs.objects},
                                           {"chamfer_l1_m",
                                            {{"partial", cs.chamfer_partial_m},
                                             {"F_0", cs.chamfer_prior_m},
                                             {"F_1", cs.chamfer_completed_m}}},
                                           {"iou",
                                            {{"partial", cs.iou_partial},
                                             {"F_0", cs.iou_prior},
                                             {"F_1", cs.iou_completed}}}}}};
            md << "| " << set.name << " | " << name << " | " << ps.views << " | "
               << (ps.yaw_scored
                       ? percent(ps.yaw_within_10deg) + " of " + std::to_string(ps.yaw_scored)
                       : "n/a (symmetric)")
               << " | " << percent(ps.centre_within_5cm) << " | "
               << fixed(ps.median_yaw_error_deg, 1) << " deg | "
               << fixed(100 * ps.median_centre_error_m, 1) << " cm | " << cs.objects << " | "
               << fixed(100 * cs.chamfer_partial_m, 1) << " / "
               << fixed(100 * cs.chamfer_prior_m, 1) << " / "
               << fixed(100 * cs.chamfer_completed_m, 1) << " | " << fixed(cs.iou_partial, 3)
               << " / " << fixed(cs.iou_prior, 3) << " / " << fixed(cs.iou_completed, 3) << " |\n";
        }
    }
    j["timing_ms"] = {{"F_n_and_solve_median", r.fn_ms_median},
                      {"F_n_and_solve_p90", r.fn_ms_p90},
                      {"F_1_update_median", r.f1_update_ms_median},
                      {"F_1_grid_and_mesh_median", r.f1_mesh_ms_median},
                      {"F_0_fit_median", r.f0_fit_ms_median},
                      {"threads", o.threads}};
    md << "\nPer object on " << o.threads << " thread(s): F_n + solve " << fixed(r.fn_ms_median, 1)
       << " ms median (" << fixed(r.fn_ms_p90, 1)
       << " ms p90); F_1 update (TSDF of a view + encoder) " << fixed(r.f1_update_ms_median, 1)
       << " ms; F_1 on the whole grid + isosurface " << fixed(r.f1_mesh_ms_median, 1)
       << " ms; F_0 (code fit + its field on the grid) " << fixed(r.f0_fit_ms_median, 1)
       << " ms.\n";
    io::write_json(out / "summary.json", j);
    io::write_file_atomic(out / "table.md", md.str());
    write_gallery(out / "gallery.png", r.showcase);
    staged.commit();
    std::cout << md.str();
    return 0;
}

namespace {

std::vector<double> parse_numbers(const std::string& text, std::size_t count,
                                  const std::string& what) {
    std::vector<double> v;
    std::stringstream s(text);
    std::string item;
    while (std::getline(s, item, ',')) {
        try {
            std::size_t used = 0;
            const double x = std::stod(item, &used);
            if (used != item.size() || !std::isfinite(x)) throw std::invalid_argument(item);
            v.push_back(x);
        } catch (const std::exception&) {
            throw io::FileError(what, "'" + item + "' is not a finite number");
        }
    }
    if (v.size() != count)
        throw io::FileError(what, "expected " + std::to_string(count) +
                                      " comma-separated numbers, got " + std::to_string(v.size()));
    return v;
}

}  // namespace

int run_complete(const CompleteOptions& o) {
    ObjectClass cls = ObjectClass::kChair;
    if (o.cls == "table")
        cls = ObjectClass::kTable;
    else if (o.cls != "chair")
        throw io::FileError("--class", "'" + o.cls + "' has no shape networks (chair or table)");
    const std::vector<double> b = parse_numbers(o.box, 7, "--box");
    if (!(b[3] > 0 && b[4] > 0 && b[5] > 0))
        throw io::FileError("--box", "length, width and height must be positive");
    // Furniture, seen by a LiDAR: the completion integrates rays from the sensor through the box,
    // so a sensor 1e30 m away is not slow, it never ends.
    constexpr double kMaxSize_m = 10.0, kMaxRange_m = 200.0;
    if (std::max({b[3], b[4], b[5]}) > kMaxSize_m) {
        throw io::FileError("--box", "length, width and height must be at most " +
                                         std::to_string(static_cast<int>(kMaxSize_m)) +
                                         " m (furniture)");
    }
    const std::vector<double> s = parse_numbers(o.sensor, 3, "--sensor");
    const double range =
        (Eigen::Vector3d(s[0], s[1], s[2]) - Eigen::Vector3d(b[0], b[1], b[2])).norm();
    if (range > kMaxRange_m) {
        char text[96];
        std::snprintf(text, sizeof(text), "lies %.4g m from the box (a LiDAR sees at most %.0f m)",
                      range, kMaxRange_m);
        throw io::FileError("--sensor", text);
    }
    const shape::ShapeModel model = load_shape_model(o.model);
    const PointCloud cloud = io::read_point_cloud(o.cloud).cloud;
    // The returns in the box grown by 10 cm sideways, above its lowest 5 cm (the floor's band).
    OrientedBox box;
    box.centre_m = {b[0], b[1], b[2]};
    box.size_m = {b[3], b[4], b[5]};
    box.yaw_rad = b[6];
    const double floor_z = b[2] - b[5] / 2;
    const Eigen::Matrix2d Rt = Eigen::Rotation2Dd(-box.yaw_rad).toRotationMatrix();
    std::vector<Eigen::Vector3d> inside;
    for (const auto& p : cloud.xyz) {
        const Eigen::Vector3d q = p.cast<double>();
        const Eigen::Vector2d local = Rt * (q.head<2>() - box.centre_m.head<2>());
        if (std::abs(local.x()) <= b[3] / 2 + 0.1 && std::abs(local.y()) <= b[4] / 2 + 0.1 &&
            q.z() > floor_z + 0.05 && q.z() <= floor_z + b[5] + 0.1) {
            inside.push_back(q);
        }
    }
    if (inside.size() < 10)
        throw io::FileError(o.cloud, std::to_string(inside.size()) +
                                         " returns inside the box: at least 10 are needed");
    Eigen::Vector3d origin = Eigen::Vector3d::Zero();
    for (const auto& q : inside) origin += q / static_cast<double>(inside.size());
    origin.z() = floor_z;
    std::vector<Eigen::Vector3d> gravity;
    for (const auto& q : inside) gravity.push_back(q - origin);
    const auto T = model.estimate_pose(cls, gravity);
    if (!T)
        throw io::FileError(o.cloud, "no pose: the correspondences found no consistent similarity");
    std::vector<Eigen::Vector3d> canonical;
    for (const auto& q : gravity) canonical.push_back(T->inverse_apply(q));
    const Eigen::Vector3d sensor = T->inverse_apply(Eigen::Vector3d(s[0], s[1], s[2]) - origin);
    const shape::Completion c = shape::complete_shape(model, cls, {canonical}, {sensor});
    if (c.mesh.triangles.empty()) throw io::FileError(o.cloud, "the completed shape is empty");
    TriangleMesh out = c.mesh;
    for (auto& v : out.vertices_m) v = (T->apply(v.cast<double>()) + origin).cast<float>();
    io::write_mesh(o.out, out);
    const Eigen::Vector3d centre = T->translation + origin;
    std::cout << io::dump_json({{"mesh", o.out},
                                {"points", inside.size()},
                                {"centre", {centre.x(), centre.y(), centre.z()}},
                                {"yaw_rad", T->yaw_rad()},
                                {"scale_m", T->scale},
                                {"triangles", out.triangles.size()}})
              << "\n";
    return 0;
}

// The subcommands of this file, as --help lists them.
namespace {

void declare_train_shape(CommandSpec& c, TrainShapeOptions& tr) {
    c.option("--scenes", tr.scenes, "Rooms rendered for training").range(1, 10000).show_default();
    c.option("--seed", tr.seed, "Seed of rooms, initialisation and sampling").show_default();
    c.option("--exclude-styles", tr.exclude_styles,
             "Styles left out of training (bench shape scores them apart)")
        .delimiter(',')
        .show_default();
    c.option("--steps-scale", tr.steps_scale, "Every stage's step count times this")
        .range(0.001, 100.0)
        .show_default();
    c.option("--threads", tr.threads, "Threads (torch and the targets)")
        .range(1, 256)
        .show_default();
    c.option("--out", tr.out, "Model file (.pt); a report beside it (.pt.json)").show_default();
}
const Registration<TrainShapeOptions> kTrainShape{
    "train-shape", Group::kLearning,
    "Train the shape networks (F_n correspondences + 7-DoF solve, F_0 DeepSDF prior, "
    "F_1 TSDF-to-occupancy completion) on the simulator's furniture, from a fixed seed",
    declare_train_shape, run_train_shape};

void declare_complete(CommandSpec& c, CompleteOptions& co) {
    c.option("--model", co.model, "Shape model (default: models/shape.pt)");
    c.option("--cloud", co.cloud,
             "Cloud holding the object (.pcd, .ply, .bin), ground not removed is fine")
        .required();
    c.option(
         "--box", co.box,
         "The object's box in the cloud's frame: cx,cy,cz,length,width,height,yaw (a detection)")
        .required();
    c.option("--class", co.cls, "chair or table").required();
    c.option("--sensor", co.sensor, "Where the cloud was seen from, in its frame: x,y,z")
        .show_default();
    c.option("--out", co.out, "Mesh file (.obj, .ply, .stl)").required();
}
const Registration<CompleteOptions> kComplete{
    "complete", Group::kPointClouds,
    "Pose one object with F_n and complete its shape with F_1 (F_0's code as prior); "
    "writes the mesh in the cloud's frame",
    declare_complete, run_complete};

void declare_bench_shape(CommandSpec& c, BenchShapeOptions& shape_o) {
    c.option("--model", shape_o.model, "Shape model (default: models/shape.pt)");
    c.option("--scenes", shape_o.params.scenes, "Rooms per set").range(1, 1000).show_default();
    c.option("--seed", shape_o.params.seed, "Seed of the rooms (training uses small seeds)")
        .show_default();
    c.option("--left-out", shape_o.params.left_out_styles,
             "Styles left out of training: a second set furnished only with them")
        .delimiter(',')
        .show_default();
    c.option("--threads", shape_o.threads, "Torch threads (timing is per object on these)")
        .range(1, 256)
        .show_default();
    c.option("--inlier-distance", shape_o.params.solve.inlier_distance,
             "The 7-DoF solve's inlier residual [m]")
        .range(0.001, 1.0)
        .show_default();
    c.option("--hypotheses", shape_o.params.solve.hypotheses,
             "The 7-DoF solve's minimal samples (0: the weighted least squares alone)")
        .range(0, 100000)
        .show_default();
    c.flag("--pose-only", shape_o.pose_only, "Score F_n's pose only (no completion)");
    c.option("--out", shape_o.out_dir, "Output folder").show_default();
}
const Registration<BenchShapeOptions> kBenchShape{
    "bench shape", Group::kEvaluation,
    "The shape networks on held-out rooms and on the styles left out of training: "
    "F_n pose accuracy, completion (Chamfer-L1, IoU) of the partial cloud, F_0 and F_1, "
    "timing; writes summary.json, table.md, gallery.png",
    declare_bench_shape, run_bench_shape};

}  // namespace

}  // namespace makeway::apps
