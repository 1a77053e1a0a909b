#include "@module@/@module@_host.hpp"

#include <stdexcept>

#include "@module@/@module@_section.hpp"
#include "@module@/@prefix@_metrics.hpp"
#include "@module@/@prefix@_ref_backend.hpp"

namespace host {

namespace {

class @Class@Host final : public MissionHost {
public:
    const iface::Mission &iface() const override { return iface_mission("@MISSION@"); }

    std::vector<std::uint8_t> boot_image(const sim::Scenario &s) const override
    {
        const @prefix@_params_t p = sim::@module@_boot_table(s.fsw.table);
        std::vector<std::uint8_t> img(FSW_TABLE_HDR_BYTES + @PREFIX@_TBL_PAYLOAD);
        if (@prefix@_table_encode(&p, 1u, img.data(), static_cast<std::uint32_t>(img.size())) != img.size()) {
            throw std::invalid_argument("@module@ table '" + s.fsw.table + "' does not encode");
        }
        return img;
    }

    std::vector<std::string> ref_kinds() const override { return {"ref"}; }

    std::unique_ptr<bridge::Backend> make_ref(const sim::Scenario &, const std::string &kind,
                                              const std::vector<std::uint8_t> &image) const override
    {
        if (kind != "ref") {
            throw std::invalid_argument("unknown reference FSW '" + kind + "' for @MISSION@ (ref)");
        }
        const auto pl = image_payload(image);
        @prefix@_params_t p{};
        if (@prefix@_table_decode(pl.first, pl.second, image_revision(image), &p) != FSW_OK) {
            throw std::invalid_argument("the reference FSW cannot decode this @module@ table image");
        }
        return std::unique_ptr<bridge::Backend>(new Ref@Class@Backend(p));
    }

    std::unique_ptr<MissionMetrics> make_metrics(const sim::Scenario &s) const override
    {
        return std::unique_ptr<MissionMetrics>(new @Class@Metrics(s));
    }
};

}  // namespace

const MissionHost &@module@_host()
{
    static const @Class@Host h;
    return h;
}

}  // namespace host
