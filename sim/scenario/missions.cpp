// missions.cpp — the scenario loader with the missions of this build (the registry generated
// from missions.json: sim_missions_gen.cpp in the build tree).
#include <fstream>
#include <sstream>
#include <stdexcept>

#include "plant/plant.hpp"
#include "scenario/scenario.hpp"

namespace sim {

const MissionSection *find_section_gen(const std::string &mission);
std::vector<std::string> section_names_gen();

std::vector<std::string> mission_names() { return section_names_gen(); }

const MissionSection &mission_section(const std::string &mission)
{
    const MissionSection *s = find_section_gen(mission);
    if (s == nullptr) {
        std::string list;
        for (const std::string &n : section_names_gen()) {
            list += (list.empty() ? "" : ", ") + n;
        }
        throw std::invalid_argument("mission '" + mission + "' is not in this build (" + list + ")");
    }
    return *s;
}

Scenario parse_scenario(const std::string &yaml_text, const std::string &source_name)
{
    return parse_scenario_with(yaml_text, source_name, find_section_gen, section_names_gen());
}

Scenario load_scenario(const std::string &path)
{
    std::ifstream in(path, std::ios::binary);
    if (!in) {
        throw ScenarioError(path + ": cannot open scenario file");
    }
    std::ostringstream ss;
    ss << in.rdbuf();
    Scenario s = parse_scenario(ss.str(), path);
    // A table file is named relative to the scenario that names it.
    if (!s.fsw.table_file.empty() && s.fsw.table_file[0] != '/') {
        const std::size_t slash = path.rfind('/');
        if (slash != std::string::npos) {
            s.fsw.table_file = path.substr(0, slash + 1) + s.fsw.table_file;
        }
    }
    return s;
}

std::unique_ptr<Plant> make_plant(const Scenario &scn) { return mission_section(scn.mission).make_plant(scn); }

}  // namespace sim
