#include "respin/respin_host.hpp"

#include <stdexcept>

#include "respin/respin_section.hpp"
#include "respin/rsp_metrics.hpp"
#include "respin/rsp_ref_backend.hpp"

namespace host {

namespace {

class RespinHost final : public MissionHost {
public:
    const iface::Mission &iface() const override { return iface_mission("RESPIN"); }

    std::vector<std::uint8_t> boot_image(const sim::Scenario &s) const override
    {
        const rsp_params_t p = sim::respin_boot_table(s.fsw.table);
        std::vector<std::uint8_t> img(FSW_TABLE_HDR_BYTES + RSP_TBL_PAYLOAD);
        if (rsp_table_encode(&p, 1u, img.data(), static_cast<std::uint32_t>(img.size())) != img.size()) {
            throw std::invalid_argument("respin table '" + s.fsw.table + "' does not encode");
        }
        return img;
    }

    std::vector<std::string> ref_kinds() const override { return {"ref"}; }

    std::unique_ptr<bridge::Backend> make_ref(const sim::Scenario &, const std::string &kind,
                                              const std::vector<std::uint8_t> &image) const override
    {
        if (kind != "ref") {
            throw std::invalid_argument("unknown reference FSW '" + kind + "' for RESPIN (ref)");
        }
        const auto pl = image_payload(image);
        rsp_params_t p{};
        if (rsp_table_decode(pl.first, pl.second, image_revision(image), &p) != FSW_OK) {
            throw std::invalid_argument("the reference FSW cannot decode this respin table image");
        }
        return std::unique_ptr<bridge::Backend>(new RefRespinBackend(p));
    }

    std::unique_ptr<MissionMetrics> make_metrics(const sim::Scenario &s) const override
    {
        return std::unique_ptr<MissionMetrics>(new RespinMetrics(s));
    }
};

}  // namespace

const MissionHost &respin_host()
{
    static const RespinHost h;
    return h;
}

}  // namespace host
