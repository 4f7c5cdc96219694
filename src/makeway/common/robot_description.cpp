#include "makeway/common/robot_description.hpp"

#include "makeway/common/param_tables.hpp"

namespace makeway {

std::vector<std::string> RobotDescription::validate() const {
    return robot_description_table().problems(*this);
}

}  // namespace makeway
