#include "makeway/common/box_sampling.hpp"

#include <cmath>
#include <string>

#include "makeway/common/angles.hpp"
#include "makeway/common/box_overlap.hpp"

namespace makeway {
namespace {

// A face of the unit box: fixed axis and sign; the two other axes span it.
struct Face {
    int axis;
    double sign;
};
constexpr Face kFaces[] = {{0, 1.0}, {0, -1.0}, {1, 1.0}, {1, -1.0}, {2, 1.0}, {2, -1.0}};

}  // namespace

PointCloud sample_box_surfaces(const std::vector<LabelledBox>& boxes,
                               const BoxSamplingParams& params, Rng& rng) {
    PointCloud cloud;
    for (const LabelledBox& lb : boxes) {
        const Isometry3 T_frame_box = lb.box.T_frame_box();
        const Eigen::Vector3d half = 0.5 * lb.box.size_m;
        for (const Face& face : kFaces) {
            if (params.skip_bottom && face.axis == 2 && face.sign < 0.0) continue;
            const int u = (face.axis + 1) % 3;
            const int v = (face.axis + 2) % 3;
            const double area = lb.box.size_m[u] * lb.box.size_m[v];
            const auto n = static_cast<std::size_t>(std::llround(area * params.points_per_m2));
            for (std::size_t i = 0; i < n; ++i) {
                Eigen::Vector3d p_box;
                p_box[face.axis] = face.sign * half[face.axis];
                p_box[u] = uniform(rng, -half[u], half[u]);
                p_box[v] = uniform(rng, -half[v], half[v]);
                for (int k = 0; k < 3; ++k) p_box[k] += normal(rng, 0.0, params.noise_m);
                cloud.xyz.push_back((T_frame_box * p_box).cast<float>());
                cloud.intensity.push_back(static_cast<float>(10 * face.axis + (face.sign > 0)));
                cloud.ring.push_back(0);
                cloud.time_s.push_back(0.0f);
                cloud.label.push_back(static_cast<std::uint8_t>(lb.label));
                cloud.instance.push_back(lb.instance);
            }
        }
    }
    return cloud;
}

}  // namespace makeway

namespace makeway {
namespace {

std::string range_problem(const char* name, double value, double lo, double hi) {
    if (std::isfinite(value) && value >= lo && value <= hi) return {};
    return std::string(name) + " must be in [" + std::to_string(lo) + ", " + std::to_string(hi) +
           "] (got " + std::to_string(value) + ")";
}

void add_if(std::vector<std::string>& problems, std::string problem) {
    if (!problem.empty()) problems.push_back(std::move(problem));
}

}  // namespace

std::vector<std::string> ObjectLayoutParams::validate() const {
    std::vector<std::string> p;
    add_if(p, range_problem("num_objects", num_objects, 1, 1000));
    add_if(p, range_problem("room_size_m", room_size_m, 2.0, 200.0));
    add_if(p, range_problem("table_share", table_share, 0.0, 1.0));
    return p;
}

std::vector<std::string> validate(const BoxSamplingParams& params) {
    std::vector<std::string> p;
    add_if(p, range_problem("points_per_m2", params.points_per_m2, 1.0, 1e6));
    add_if(p, range_problem("noise_m", params.noise_m, 0.0, 1.0));
    return p;
}

std::vector<LabelledBox> random_object_layout(const ObjectLayoutParams& params) {
    Rng rng = make_rng(params.seed, /*stream=*/1);
    std::vector<LabelledBox> out;
    const double half_room = 0.5 * params.room_size_m;
    constexpr int kTriesPerObject = 200;
    for (int k = 0; k < params.num_objects; ++k) {
        const bool table = bernoulli(rng, params.table_share);
        for (int attempt = 0; attempt < kTriesPerObject; ++attempt) {
            LabelledBox lb;
            lb.label = table ? SemanticLabel::kTable : SemanticLabel::kChair;
            lb.instance = static_cast<std::uint32_t>(out.size() + 1);
            lb.box.size_m = table ? Eigen::Vector3d(uniform(rng, 1.0, 2.0), uniform(rng, 0.6, 0.9),
                                                    uniform(rng, 0.70, 0.78))
                                  : Eigen::Vector3d(uniform(rng, 0.45, 0.6), uniform(rng, 0.45, 0.6),
                                                    uniform(rng, 0.8, 1.0));
            const double reach = 0.5 * lb.box.size_m.head<2>().norm();
            lb.box.centre_m = {uniform(rng, -half_room + reach, half_room - reach),
                               uniform(rng, -half_room + reach, half_room - reach),
                               0.5 * lb.box.size_m.z()};
            lb.box.yaw_rad = uniform(rng, -kPi, kPi);
            bool free = true;
            for (const auto& other : out) free &= iou_bev(lb.box, other.box) == 0.0;
            if (free) {
                out.push_back(lb);
                break;
            }
        }
    }
    return out;
}

}  // namespace makeway
