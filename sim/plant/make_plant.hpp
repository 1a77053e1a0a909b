// make_plant — the plant a scenario names (scenario.plant): "sail" (spec 10) or "cw" (spec 50).
#ifndef SIM_PLANT_MAKE_PLANT_HPP
#define SIM_PLANT_MAKE_PLANT_HPP

#include <memory>

#include "plant/plant.hpp"
#include "scenario/scenario.hpp"

namespace sim {

// Throws std::invalid_argument for a plant this build does not know.
std::unique_ptr<Plant> make_plant(const Scenario &scn);

}  // namespace sim

#endif
