// reader.hpp — checked reading of a YAML scenario: every value range-checked, every message naming
// the file, the key and the line. The core parser (scenario.cpp) and every mission's section
// parser (sim/<module>/<module>_section.cpp) use it, so a scenario reads alike whatever it flies.
#ifndef SIM_SCENARIO_READER_HPP
#define SIM_SCENARIO_READER_HPP

#include <yaml-cpp/yaml.h>

#include <array>
#include <cstdint>
#include <initializer_list>
#include <string>
#include <vector>

#include "scenario/scenario.hpp"

namespace sim {

class Reader {
public:
    explicit Reader(std::string source) : source_(std::move(source)) {}

    [[noreturn]] void fail(const std::string &key, const YAML::Node &node, const std::string &what) const;
    [[noreturn]] void fail_file(const std::string &what) const;

    // Unknown keys are errors: a misspelt optional key would otherwise silently keep its default.
    // Duplicate keys are errors too (yaml-cpp 0.7 silently keeps the first).
    void check_keys(const YAML::Node &map, const std::string &prefix, const std::vector<std::string> &allowed) const;
    void check_keys(const YAML::Node &map, const std::string &prefix, std::initializer_list<const char *> allowed) const;
    // A key that another part of the scenario owns is refused with the reason given.
    void refuse(const YAML::Node &root, std::initializer_list<const char *> keys, const std::string &why) const;

    static std::string join(const std::string &prefix, const std::string &k);

    double number(const YAML::Node &n, const std::string &key, double lo, double hi) const;
    std::int64_t integer(const YAML::Node &n, const std::string &key, std::int64_t lo, std::int64_t hi) const;
    std::uint64_t unsigned64(const YAML::Node &n, const std::string &key) const;
    std::array<double, 2> pair(const YAML::Node &n, const std::string &key, double lo, double hi) const;
    std::array<double, 3> triple(const YAML::Node &n, const std::string &key, double lo, double hi) const;
    std::string text(const YAML::Node &n, const std::string &key) const;
    // One of the listed words, or an error that lists them.
    std::string choice(const YAML::Node &n, const std::string &key, std::initializer_list<const char *> words) const;

    const std::string &source() const { return source_; }

private:
    std::string source_;
};

}  // namespace sim

#endif
