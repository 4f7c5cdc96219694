// The demo: the longest end-to-end path that exists so far. A seeded layout of chairs and tables,
// a labelled surface cloud, every point-cloud format written and read back, noisy "detections"
// scored against the truth with rotated 3D IoU/GIoU, and a top-down picture.
#include <cstring>
#include <filesystem>
#include <iostream>

#include "apps/commands.hpp"
#include "io/config_reader.hpp"
#include "io/json_io.hpp"
#include "io/point_cloud_io.hpp"
#include "io/top_down_png.hpp"
#include "makeway/common/angles.hpp"
#include "makeway/common/box_overlap.hpp"

namespace makeway::apps {
namespace {

template <typename T>
bool same_bits(const std::vector<T>& a, const std::vector<T>& b) {
    return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(T)) == 0;
}

bool same_cloud(const PointCloud& a, const PointCloud& b, bool xyzi_only) {
    const bool xyzi = same_bits(a.xyz, b.xyz) && same_bits(a.intensity, b.intensity);
    if (xyzi_only) return xyzi;
    return xyzi && same_bits(a.ring, b.ring) && same_bits(a.time_s, b.time_s) &&
           same_bits(a.label, b.label) && same_bits(a.instance, b.instance);
}

OrientedBox perturbed(const OrientedBox& truth, Rng& rng) {
    OrientedBox d = truth;
    for (int k = 0; k < 3; ++k) {
        d.centre_m[k] += normal(rng, 0.0, 0.05);
        d.size_m[k] *= 1.0 + normal(rng, 0.0, 0.05);
    }
    d.yaw_rad = wrap_angle(d.yaw_rad + normal(rng, 0.0, deg_to_rad(5.0)));
    return d;
}

}  // namespace

int run_demo(const DemoOptions& options) {
    const io::Config cfg = options.config.empty() ? io::Config{} : io::load_config(options.config);
    const std::filesystem::path out = options.out_dir;

    // Scene: chairs and tables on the floor, and the surface points a sensor could see.
    const std::vector<LabelledBox> boxes = random_object_layout(cfg.layout);
    Rng rng = make_rng(cfg.layout.seed, /*stream=*/2);
    const PointCloud cloud = sample_box_surfaces(boxes, cfg.sampling, rng);

    // Formats: write every format, read each back, check the values bit for bit.
    io::Json files = io::Json::object();
    bool exact = true;
    for (const char* name : {"scene.pcd", "scene.ply", "scene.bin"}) {
        const auto path = out / name;
        io::write_point_cloud(path, cloud, {.pcd = io::PcdEncoding::kBinaryCompressed});
        const io::CloudFile back = io::read_point_cloud(path);
        const bool same = same_cloud(cloud, back.cloud, back.info.format == "kitti_bin");
        exact &= same;
        files[name] = {{"bytes", std::filesystem::file_size(path)}, {"round_trip_exact", same}};
    }

    // Boxes: noisy copies of the truth, as a detector would give, scored with IoU and GIoU.
    Rng det_rng = make_rng(cfg.layout.seed, /*stream=*/3);
    io::Json objects = io::Json::array();
    double iou_sum = 0.0, giou_sum = 0.0;
    for (const LabelledBox& lb : boxes) {
        const OrientedBox det = perturbed(lb.box, det_rng);
        const BoxOverlap o = box_overlap_3d(lb.box, det);
        iou_sum += o.iou;
        giou_sum += o.giou;
        objects.push_back({{"class", std::string(to_string(lb.label))},
                           {"truth", io::to_json(lb.box)},
                           {"detection", io::to_json(det)},
                           {"iou_3d", o.iou},
                           {"giou_3d", o.giou}});
    }
    const double n = std::max<double>(1.0, static_cast<double>(boxes.size()));

    io::write_top_down_png(out / "top_down.png", cloud, boxes,
                           {.title = "makeway demo: " + std::to_string(boxes.size()) +
                                     " objects, " + std::to_string(cloud.size()) + " points"});
    io::Json summary = {{"seed", cfg.layout.seed},
                        {"objects", boxes.size()},
                        {"points", cloud.size()},
                        {"files", files},
                        {"all_round_trips_exact", exact},
                        {"mean_iou_3d", iou_sum / n},
                        {"mean_giou_3d", giou_sum / n},
                        {"boxes", objects}};
    io::write_json(out / "summary.json", summary);

    std::cout << "makeway demo: " << boxes.size() << " objects, " << cloud.size() << " points\n"
              << "  round trips pcd/ply/bin exact: " << (exact ? "yes" : "NO") << "\n"
              << "  noisy boxes vs truth: mean IoU " << iou_sum / n << ", mean GIoU "
              << giou_sum / n << "\n"
              << "  wrote " << (out / "summary.json").string() << ", "
              << (out / "top_down.png").string() << "\n";
    return exact ? 0 : 1;
}

}  // namespace makeway::apps
