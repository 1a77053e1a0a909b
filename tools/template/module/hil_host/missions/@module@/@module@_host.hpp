// @module@_host.hpp — the @MISSION@ mission's host class (hil_host/missions/mission_host.hpp):
// boot table images from the scenario, the double reference backend, the SIL metrics.
#ifndef HIL_MISSIONS_@PREFIX@_HOST_HPP
#define HIL_MISSIONS_@PREFIX@_HOST_HPP

#include "mission_host.hpp"

namespace host {

const MissionHost &@module@_host();

}  // namespace host

#endif
