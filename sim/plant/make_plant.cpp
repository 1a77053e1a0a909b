#include "plant/make_plant.hpp"

#include <stdexcept>

#include "cw_sil_plant.hpp"
#include "plant/sail_plant.hpp"

namespace sim {

std::unique_ptr<Plant> make_plant(const Scenario &scn)
{
    if (scn.plant == "sail") {
        return std::unique_ptr<Plant>(new SailPlant(scn));
    }
    if (scn.plant == "cw") {
        return std::unique_ptr<Plant>(new CwSilPlant(scn));
    }
    throw std::invalid_argument("scenario '" + scn.name + "': no SIL plant '" + scn.plant + "' in this build");
}

}  // namespace sim
