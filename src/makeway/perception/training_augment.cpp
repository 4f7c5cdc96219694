#include "makeway/perception/training_augment.hpp"

#include <cmath>

#include "makeway/common/angles.hpp"

namespace makeway::perception {

void augment_sample(PointCloud& cloud, LabelledBoxes& boxes, Rng& rng) {
    const double a = uniform(rng, -kPi, kPi);
    const bool flip = bernoulli(rng, 0.5);
    const float c = static_cast<float>(std::cos(a)), s = static_cast<float>(std::sin(a));
    const double keep = uniform(rng, 0.6, 1.0);
    const double max_range = bernoulli(rng, 0.3) ? uniform(rng, 4.0, 8.0) : 1e9;
    std::vector<std::size_t> kept;
    for (std::size_t i = 0; i < cloud.size(); ++i) {
        Eigen::Vector3f& p = cloud.xyz[i];
        if (flip) p.y() = -p.y();
        p = Eigen::Vector3f(c * p.x() - s * p.y(), s * p.x() + c * p.y(), p.z());
        if (uniform(rng, 0, 1) < keep && p.head<2>().norm() <= max_range) kept.push_back(i);
    }
    cloud = cloud.select(kept);
    LabelledBoxes out;
    for (auto [cls, b] : boxes) {
        if (flip) b.centre_m.y() = -b.centre_m.y(), b.yaw_rad = -b.yaw_rad;
        const Eigen::Vector2d xy = b.centre_m.head<2>();
        b.centre_m.head<2>() = Eigen::Vector2d(std::cos(a) * xy.x() - std::sin(a) * xy.y(),
                                               std::sin(a) * xy.x() + std::cos(a) * xy.y());
        b.yaw_rad = wrap_angle(b.yaw_rad + a);
        if (b.centre_m.head<2>().norm() <= max_range) out.emplace_back(cls, b);
    }
    boxes = out;
}

}  // namespace makeway::perception
