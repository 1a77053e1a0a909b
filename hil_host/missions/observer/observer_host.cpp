#include "observer/observer_host.hpp"

#include <stdexcept>

#include "observer/obs_metrics.hpp"
#include "observer/obs_ref_backend.hpp"
#include "observer/observer_section.hpp"

namespace host {

namespace {

class ObserverHost final : public MissionHost {
public:
    const iface::Mission &iface() const override { return iface_mission("DETUMBLE"); }

    std::vector<std::uint8_t> boot_image(const sim::Scenario &s) const override
    {
        const obs_params_t p = sim::observer_boot_table(s);
        std::vector<std::uint8_t> img(FSW_TABLE_HDR_BYTES + OBS_TBL_PAYLOAD);
        if (obs_table_encode(&p, 1u, img.data(), static_cast<std::uint32_t>(img.size())) != img.size()) {
            throw std::invalid_argument("observer table '" + s.fsw.table + "' does not encode");
        }
        return img;
    }

    std::vector<std::string> ref_kinds() const override { return {"ref", "ref-per-axis"}; }

    std::unique_ptr<bridge::Backend> make_ref(const sim::Scenario &, const std::string &kind,
                                              const std::vector<std::uint8_t> &image) const override
    {
        const auto pl = image_payload(image);
        obs_params_t p{};
        if (obs_table_decode(pl.first, pl.second, image_revision(image), &p) != FSW_OK) {
            throw std::invalid_argument("the reference FSW cannot decode this observer table image");
        }
        if (kind != "ref" && kind != "ref-per-axis") {
            throw std::invalid_argument("unknown reference FSW '" + kind + "' for DETUMBLE (ref, ref-per-axis)");
        }
        return std::unique_ptr<bridge::Backend>(new RefObsBackend(p, kind == "ref-per-axis"));
    }

    std::unique_ptr<MissionMetrics> make_metrics(const sim::Scenario &s) const override
    {
        return std::unique_ptr<MissionMetrics>(new ObsMetrics(s));
    }
};

}  // namespace

const MissionHost &observer_host()
{
    static const ObserverHost h;
    return h;
}

}  // namespace host
