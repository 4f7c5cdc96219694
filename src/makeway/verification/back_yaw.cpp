#include "makeway/verification/back_yaw.hpp"

#include <Eigen/Eigenvalues>
#include <cmath>

#include "makeway/common/angles.hpp"
#include "makeway/verification/param_tables.hpp"
#include "makeway/verification/verifier.hpp"

namespace makeway::verification {

std::vector<std::string> BackYawParams::validate() const {
    return back_yaw_table().problems(*this);
}

BackYawResult yaw_from_back(const std::vector<Eigen::Vector3d>& segment, const OrientedBox& box,
                            std::optional<double> floor_z_m, const BackYawParams& params) {
    BackYawResult r;
    r.yaw_rad = box.yaw_rad;
    if (!params.enabled) return r;
    // The top share of the object's height above the floor, inside the box grown by the margin,
    // in the box's frame (x its facing, y across).
    const double floor = floor_z_m.value_or(box.z_min_m());
    const double top = box.z_max_m();
    const double from = top - params.top_share * (top - floor);
    const double c = std::cos(box.yaw_rad), s = std::sin(box.yaw_rad);
    const Eigen::Vector2d half =
        0.5 * box.size_m.head<2>() + Eigen::Vector2d::Constant(params.margin_m);
    std::vector<Eigen::Vector2d> back;
    for (const Eigen::Vector3d& p : segment) {
        if (!(p.z() >= from && p.z() <= top + params.margin_m)) continue;
        const Eigen::Vector2d d = p.head<2>() - box.centre_m.head<2>();
        const Eigen::Vector2d q(c * d.x() + s * d.y(), -s * d.x() + c * d.y());
        if (std::abs(q.x()) <= half.x() && std::abs(q.y()) <= half.y()) back.push_back(q);
    }
    r.points = back.size();
    if (back.size() < params.min_points) return r;
    Eigen::Vector2d mean = Eigen::Vector2d::Zero();
    for (const Eigen::Vector2d& q : back) mean += q;
    mean /= static_cast<double>(back.size());
    Eigen::Matrix2d cov = Eigen::Matrix2d::Zero();
    for (const Eigen::Vector2d& q : back) cov += (q - mean) * (q - mean).transpose();
    cov /= static_cast<double>(back.size());
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> eig(cov);  // ascending eigenvalues
    const double across = std::max(eig.eigenvalues()(0), 1e-12);
    r.elongation = eig.eigenvalues()(1) / across;
    if (!(r.elongation >= params.min_elongation)) return r;
    // The back lies along the box's y axis when the yaw is right: its axis at pi/2 + the error.
    const Eigen::Vector2d axis = eig.eigenvectors().col(1);
    double turn = wrap_angle(std::atan2(axis.y(), axis.x()) - kPi / 2);
    if (turn > kPi / 2) turn -= kPi;  // an axis has no sign: the turn nearest the box's yaw
    if (turn <= -kPi / 2) turn += kPi;
    r.turn_rad = turn;
    if (!(std::abs(turn) <= params.max_turn_rad)) return r;
    r.refined = true;
    r.yaw_rad = wrap_angle(box.yaw_rad + turn);
    return r;
}

std::vector<Detection> chairs_turned_to_their_backs(
    const PointCloud& cloud, std::vector<Detection> detections,
    const std::function<std::optional<double>(double, double)>& floor_z_at,
    const BackYawParams& params) {
    if (!params.enabled) return detections;
    std::vector<OrientedBox> chairs;
    for (const Detection& d : detections) {
        if (d.cls == ObjectClass::kChair) chairs.push_back(d.box_sensor);
    }
    const auto segments = segments_of(cloud, chairs, params.margin_m);
    std::size_t k = 0;
    for (Detection& d : detections) {
        if (d.cls != ObjectClass::kChair) continue;
        const std::optional<double> floor_z =
            floor_z_at ? floor_z_at(d.box_sensor.centre_m.x(), d.box_sensor.centre_m.y())
                       : std::nullopt;
        d.box_sensor.yaw_rad = yaw_from_back(segments[k++], d.box_sensor, floor_z, params).yaw_rad;
    }
    return detections;
}

}  // namespace makeway::verification
