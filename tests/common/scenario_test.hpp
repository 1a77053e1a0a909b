// scenario_test.hpp — a scenario text that must fail, and the fragments its message must contain
// (the file, the key, the line, the reason). Shared by the scenario tests of the core and of
// every mission's section.
#ifndef TESTS_COMMON_SCENARIO_TEST_HPP
#define TESTS_COMMON_SCENARIO_TEST_HPP

#include <cstdio>
#include <string>
#include <vector>

#include "scenario/scenario.hpp"
#include "sim_test.hpp"

inline void expect_scenario_error(const std::string &yaml, const std::vector<std::string> &fragments)
{
    try {
        (void)sim::parse_scenario(yaml, "bad.yaml");
        std::printf("  no error for:\n%s\n", yaml.c_str());
        EXPECT_TRUE(false);
    } catch (const sim::ScenarioError &e) {
        const std::string msg = e.what();
        std::printf("  -> %s\n", msg.c_str());
        for (const std::string &f : fragments) {
            if (msg.find(f) == std::string::npos) {
                std::printf("  missing '%s' in message\n", f.c_str());
                EXPECT_TRUE(false);
            }
        }
    }
}

#endif
