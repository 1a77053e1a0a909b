#include "relay/relay_host.hpp"

#include <stdexcept>

#include "relay/relay_section.hpp"
#include "relay/rly_metrics.hpp"

namespace host {

namespace {

class RelayHost final : public MissionHost {
public:
    const iface::Mission &iface() const override { return iface_mission("RELAY"); }

    std::vector<std::uint8_t> boot_image(const sim::Scenario &s) const override
    {
        const rly_params_t p = sim::relay_boot_table(s.fsw.table);
        std::vector<std::uint8_t> img(FSW_TABLE_HDR_BYTES + RLY_TBL_PAYLOAD);
        if (rly_table_encode(&p, 1u, img.data(), static_cast<std::uint32_t>(img.size())) != img.size()) {
            throw std::invalid_argument("relay table '" + s.fsw.table + "' does not encode");
        }
        return img;
    }

    // No double-precision flight backend: the relay's reference is the tick law and copy in sim/relay
    // (rly_ref), proven against the flight code bit for bit in the golden tests instead.
    std::vector<std::string> ref_kinds() const override { return {}; }

    std::unique_ptr<bridge::Backend> make_ref(const sim::Scenario &, const std::string &kind,
                                              const std::vector<std::uint8_t> &) const override
    {
        throw std::invalid_argument("RELAY has no reference FSW backend ('" + kind + "'): fly the flight code");
    }

    std::unique_ptr<MissionMetrics> make_metrics(const sim::Scenario &s) const override
    {
        return std::unique_ptr<MissionMetrics>(new RelayMetrics(s));
    }
};

}  // namespace

const MissionHost &relay_host()
{
    static const RelayHost h;
    return h;
}

}  // namespace host
