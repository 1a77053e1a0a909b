#include "pd/pd_host.hpp"

#include <stdexcept>

#include "pd/pd_section.hpp"
#include "pd/pd_metrics.hpp"
#include "pd/pd_ref_backend.hpp"

namespace host {

namespace {

class PdHost final : public MissionHost {
public:
    const iface::Mission &iface() const override { return iface_mission("HOLD"); }

    std::vector<std::uint8_t> boot_image(const sim::Scenario &s) const override
    {
        const pd_table_t p = sim::pd_boot_table(s.fsw.table);
        std::vector<std::uint8_t> img(FSW_TABLE_HDR_BYTES + PD_TBL_PAYLOAD);
        if (pd_table_encode(&p, 1u, img.data(), static_cast<std::uint32_t>(img.size())) != img.size()) {
            throw std::invalid_argument("pd table '" + s.fsw.table + "' does not encode");
        }
        return img;
    }

    std::vector<std::string> ref_kinds() const override { return {"ref"}; }

    std::unique_ptr<bridge::Backend> make_ref(const sim::Scenario &, const std::string &kind,
                                              const std::vector<std::uint8_t> &image) const override
    {
        if (kind != "ref") {
            throw std::invalid_argument("unknown reference FSW '" + kind + "' for HOLD (ref)");
        }
        const auto pl = image_payload(image);
        pd_table_t p{};
        if (pd_table_decode(pl.first, pl.second, image_revision(image), &p) != FSW_OK) {
            throw std::invalid_argument("the reference FSW cannot decode this pd table image");
        }
        return std::unique_ptr<bridge::Backend>(new RefPdBackend(p));
    }

    std::unique_ptr<MissionMetrics> make_metrics(const sim::Scenario &s) const override
    {
        return std::unique_ptr<MissionMetrics>(new PdMetrics(s));
    }
};

}  // namespace

const MissionHost &pd_host()
{
    static const PdHost h;
    return h;
}

}  // namespace host
