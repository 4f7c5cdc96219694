#pragma once
// The CAD verification's configurable parameters (common/param_table.hpp).
#include "makeway/common/param_table.hpp"
#include "makeway/verification/back_yaw.hpp"
#include "makeway/verification/verifier.hpp"

namespace makeway::verification {

const ParamTable<VerifyParams>& verify_table();
const ParamTable<BackYawParams>& back_yaw_table();

}  // namespace makeway::verification
