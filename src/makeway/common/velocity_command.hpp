#pragma once
// Command to a differential-drive base, in the robot frame.

namespace makeway {

struct VelocityCommand {
    double v_mps = 0.0;    ///< forward speed
    double w_radps = 0.0;  ///< turn rate, counter-clockwise positive
};

}  // namespace makeway
