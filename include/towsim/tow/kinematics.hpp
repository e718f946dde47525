// Kinematics of the tow point O_r at one instant.
#pragma once

#include <vector>

#include "towsim/model/types.hpp"

namespace towsim {

/// Position, velocity and acceleration at one instant.
struct TowKinematics {
  Vec3 pos, vel, acc;  // [m], [m/s], [m/s^2], R_g
};

}  // namespace towsim
