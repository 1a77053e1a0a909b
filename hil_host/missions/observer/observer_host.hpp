// observer_host.hpp — the DETUMBLE mission's host class (hil_host/missions/mission_host.hpp):
// boot table images from the scenario, the double reference backend, the SIL metrics.
#ifndef HIL_MISSIONS_OBSERVER_HOST_HPP
#define HIL_MISSIONS_OBSERVER_HOST_HPP

#include "mission_host.hpp"

namespace host {

const MissionHost &observer_host();

}  // namespace host

#endif
