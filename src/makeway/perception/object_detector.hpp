#pragma once
// What the pipeline needs of a 3D detector: boxes from a ground-filtered keyframe, and how far it
// sees. The neural network (detector.hpp, its torch code in the networks' module) is one; tests
// and other detectors can be others, without libtorch.
#include <Eigen/Core>
#include <optional>
#include <vector>

#include "makeway/common/detection.hpp"
#include "makeway/common/point_cloud.hpp"

namespace makeway::perception {

class ObjectDetector {
  public:
    virtual ~ObjectDetector() = default;
    /// Detections in the cloud's (sensor) frame; the cloud is ground- and ceiling-filtered.
    /// `ground_plane_sensor`: the keyframe's fitted floor (n . p + d = 0), when one was found; a
    /// detector that normalises its input for the sensor's mounting (levelling.hpp) needs it.
    virtual std::vector<Detection> detect(
        const PointCloud& cloud_sensor,
        const std::optional<Eigen::Vector4d>& ground_plane_sensor) const = 0;
    /// Without a floor: the cloud as the sensor gave it.
    std::vector<Detection> detect(const PointCloud& cloud_sensor) const {
        return detect(cloud_sensor, std::nullopt);
    }
    /// Half the side of the square around the sensor that the detector looks at [m].
    virtual double reach_m() const = 0;
    /// Whether detect() reads the points' intensity (a source may then leave it out).
    virtual bool uses_intensity() const { return true; }
};

}  // namespace makeway::perception
