#include "impulse/impulse_host.hpp"

#include <stdexcept>

#include "impulse/imp_metrics.hpp"
#include "impulse/imp_ref_backend.hpp"
#include "impulse/impulse_section.hpp"

namespace host {

namespace {

class ImpulseHost final : public MissionHost {
public:
    const iface::Mission &iface() const override { return iface_mission("RENDEZVOUS"); }

    std::vector<std::uint8_t> boot_image(const sim::Scenario &s) const override
    {
        const imp_params_t p = sim::impulse_boot_table(s);
        std::vector<std::uint8_t> img(FSW_TABLE_HDR_BYTES + IMP_TBL_PAYLOAD);
        if (imp_table_encode(&p, 1u, img.data(), static_cast<std::uint32_t>(img.size())) != img.size()) {
            throw std::invalid_argument("impulse table '" + s.fsw.table + "' does not encode");
        }
        return img;
    }

    std::vector<std::string> ref_kinds() const override { return {"ref"}; }

    std::unique_ptr<bridge::Backend> make_ref(const sim::Scenario &, const std::string &kind,
                                              const std::vector<std::uint8_t> &image) const override
    {
        if (kind != "ref") {
            throw std::invalid_argument("unknown reference FSW '" + kind + "' for RENDEZVOUS (ref)");
        }
        const auto pl = image_payload(image);
        imp_params_t p{};
        if (imp_table_decode(pl.first, pl.second, image_revision(image), &p) != FSW_OK) {
            throw std::invalid_argument("the reference FSW cannot decode this impulse table image");
        }
        return std::unique_ptr<bridge::Backend>(new RefImpBackend(p));
    }

    std::unique_ptr<MissionMetrics> make_metrics(const sim::Scenario &s) const override
    {
        return std::unique_ptr<MissionMetrics>(new ImpMetrics(s));
    }
};

}  // namespace

const MissionHost &impulse_host()
{
    static const ImpulseHost h;
    return h;
}

}  // namespace host
