// pd_host.hpp — the HOLD mission's host class (hil_host/missions/mission_host.hpp):
// boot table images from the scenario, the double reference backend, the SIL metrics.
#ifndef HIL_MISSIONS_PD_HOST_HPP
#define HIL_MISSIONS_PD_HOST_HPP

#include "mission_host.hpp"

namespace host {

const MissionHost &pd_host();

}  // namespace host

#endif
