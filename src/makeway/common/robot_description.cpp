#include "makeway/common/robot_description.hpp"

namespace makeway {

std::vector<std::string> RobotDescription::validate() const {
    std::vector<std::string> p;
    if (!(length_m > 0.05 && length_m < 5.0)) p.push_back("length_m must be in (0.05, 5)");
    if (!(width_m > 0.05 && width_m < 5.0)) p.push_back("width_m must be in (0.05, 5)");
    if (!(lidar_height_m > 0.0 && lidar_height_m < 3.0)) p.push_back("lidar_height_m must be in (0, 3)");
    if (!(body_height_m > 0.0 && body_height_m < 3.0)) p.push_back("body_height_m must be in (0, 3)");
    if (!(ground_clearance_m >= 0.0 && ground_clearance_m < body_height_m)) p.push_back("ground_clearance_m must be in [0, body_height_m)");
    if (!(max_v_mps > 0.0 && max_v_mps <= 5.0)) p.push_back("max_v_mps must be in (0, 5]");
    if (!(max_w_radps > 0.0 && max_w_radps <= 10.0)) p.push_back("max_w_radps must be in (0, 10]");
    if (!(max_acc_mps2 > 0.0 && max_acc_mps2 <= 20.0)) p.push_back("max_acc_mps2 must be in (0, 20]");
    if (!(max_ang_acc_radps2 > 0.0 && max_ang_acc_radps2 <= 50.0)) p.push_back("max_ang_acc_radps2 must be in (0, 50]");
    return p;
}

}  // namespace makeway
