#include "mission_host.hpp"

#include <cmath>
#include <cstdio>
#include <mutex>
#include <nlohmann/json.hpp>
#include <sstream>
#include <stdexcept>

extern "C" {
#include "fsw_codec.h"
}

namespace host {

const MissionHost *find_host_gen(const std::string &mission);   // host_missions_gen.cpp

namespace {

std::string mission_list()
{
    std::string l;
    for (std::size_t i = 0; i < iface::kNumMissions; ++i) {
        l += (l.empty() ? "" : ", ") + std::string(iface::kMissions[i].name);
    }
    return l;
}

}  // namespace

// ------------------------------------------------------------------------- telemetry layouts

std::size_t TlmLayout::at(const std::string &name) const
{
    const auto it = idx.find(name);
    if (it == idx.end()) {
        throw std::out_of_range("telemetry of " + std::string(m != nullptr ? m->name : "?") + " has no field '" +
                                name + "'");
    }
    return it->second;
}

const iface::Mission &iface_mission(const std::string &name)
{
    for (std::size_t i = 0; i < iface::kNumMissions; ++i) {
        if (name == iface::kMissions[i].name) {
            return iface::kMissions[i];
        }
    }
    throw std::invalid_argument("mission '" + name + "' is not in this build (" + mission_list() + ")");
}

const iface::Mission *iface_by_layout(std::uint32_t layout_version)
{
    for (std::size_t i = 0; i < iface::kNumMissions; ++i) {
        if (iface::kMissions[i].layout_version == layout_version) {
            return &iface::kMissions[i];
        }
    }
    return nullptr;
}

const TlmLayout &tlm_layout(const iface::Mission &m)
{
    // One layout per mission, built on first use; the tables are immutable afterwards.
    static std::mutex mu;
    static std::map<const iface::Mission *, std::unique_ptr<TlmLayout>> cache;
    const std::lock_guard<std::mutex> lock(mu);
    std::unique_ptr<TlmLayout> &p = cache[&m];
    if (!p) {
        p.reset(new TlmLayout());
        p->m = &m;
        for (std::size_t i = 0; i < m.n_tlm; ++i) {
            p->idx[m.tlm[i].name] = p->names.size();
            p->names.emplace_back(m.tlm[i].name);
            p->types.push_back(m.tlm[i].type);
            p->q.push_back(m.tlm[i].q);
        }
        p->bytes = m.tlm_bytes;
    }
    return *p;
}

bool decode_tlm(const TlmLayout &l, const std::uint8_t *buf, std::size_t len, std::vector<std::int64_t> &v)
{
    if (len != l.bytes) {
        return false;
    }
    fsw_rd_t r;
    fsw_rd_init(&r, buf, static_cast<std::uint32_t>(len));
    v.resize(l.types.size());
    for (std::size_t i = 0; i < l.types.size(); ++i) {
        switch (l.types[i]) {
        case 'q': v[i] = fsw_rd_i64(&r); break;
        case 'u': v[i] = static_cast<std::int64_t>(fsw_rd_u32(&r)); break;
        case 'i': v[i] = fsw_rd_i32(&r); break;
        case 'h': v[i] = static_cast<std::int64_t>(fsw_rd_u16(&r)); break;
        default: v[i] = static_cast<std::int64_t>(fsw_rd_u8(&r)); break;
        }
    }
    return !r.err && r.pos == len;
}

std::string bits_str(std::uint32_t word, const iface::Name *names, std::size_t n)
{
    char b[16];
    std::snprintf(b, sizeof b, "0x%08X", word);
    std::string parts;
    std::uint32_t named = 0u;
    for (unsigned bit = 0; bit < 32u; ++bit) {
        const std::uint32_t v = 1u << bit;
        if ((word & v) == 0u || (named & v) != 0u) {
            continue;
        }
        std::string nm = (bit < 8u) ? ("fx" + std::to_string(bit)) : ("bit" + std::to_string(bit));
        for (std::size_t i = 0; i < n; ++i) {
            const std::uint32_t m = names[i].value;
            if ((m & v) == 0u) {
                continue;
            }
            nm = names[i].name;
            if ((m & (m - 1u)) != 0u) {   // a multi-bit field (a mode, an axis index): NAME=value
                nm += "=" + std::to_string((word & m) / (m & (~m + 1u)));   // field value (mask's low bit = 1)
                named |= m;
            }
        }
        parts += (parts.empty() ? "" : " ") + nm;
    }
    return std::string(b) + (parts.empty() ? "" : " (" + parts + ")");
}

std::string mode_name(const iface::Mission &m, std::uint32_t mode)
{
    if (mode == m.mode) {
        return m.name;
    }
    for (std::size_t i = 0; i < iface::kNumExecModes; ++i) {
        if (iface::kExecModes[i].value == mode) {
            return iface::kExecModes[i].name;
        }
    }
    return "mode " + std::to_string(mode);
}

std::string describe_reason(const iface::Mission &m, std::uint32_t reason)
{
    const std::uint32_t code = reason & 0xFFu;
    const std::uint32_t detail = (reason >> 8) & 0xFFu;
    std::string cname = "reason " + std::to_string(code);
    std::string note;
    for (std::size_t i = 0; i < iface::kNumTblReasons; ++i) {
        if (iface::kTblReasons[i].value == code) {
            cname = iface::kTblReasons[i].name;
            note = iface::kTblReasons[i].note;
        }
    }
    std::ostringstream o;
    o << cname;
    const fsw_mis_desc_t *d = fsw_mis_desc(m.id);
    if ((code == FSW_TBL_R_RANGE_LO || code == FSW_TBL_R_RANGE_HI) && d != nullptr && detail < d->table->n_fields) {
        const fsw_field_lim_t &f = d->table->fields[detail];
        o << ": field " << detail << " (" << (detail < m.n_table_fields ? m.table_fields[detail] : "?") << ") "
          << (code == FSW_TBL_R_RANGE_LO ? "below" : "above") << " its allowed [" << f.min << ", " << f.max << "]";
    } else if (code == FSW_TBL_R_INVARIANT && d != nullptr && detail < d->table->n_rels) {
        const fsw_field_rel_t &rel = d->table->rels[detail];
        auto nm = [&](std::uint32_t k) { return k < m.n_table_fields ? std::string(m.table_fields[k]) : std::string("?"); };
        o << ": relation " << detail << " needs " << nm(rel.a) << " + " << rel.margin << " <= " << nm(rel.b);
    } else if (code == FSW_TBL_R_MODULE) {
        if (detail == FSW_VETO_UNDECODED) {
            o << ": the " << m.module << " module check could not decode the table";
        } else if (detail >= 1u && detail <= m.n_why) {
            o << ": the " << m.module << " module check refused it (" << m.why[detail - 1u].name << ": "
              << m.why[detail - 1u].note << ")";
        } else {
            o << ": the " << m.module << " module check refused it (detail " << detail << ")";
        }
    } else if (code == FSW_TBL_R_UPLOAD_ID || code == FSW_TBL_R_ID) {
        char id[16];
        std::snprintf(id, sizeof id, "0x%04X", m.table_id);
        o << " (" << note << "; the " << m.name << " table is " << id << ")";
    } else if (!note.empty()) {
        o << " (" << note << ")";
    }
    return o.str();
}

// ----------------------------------------------------------------------------- summaries

void Summary::add(const std::string &key, double v, const char *fmt)
{
    char b[64];
    std::snprintf(b, sizeof b, fmt, v);
    Item it;
    it.key = key;
    it.text = b;
    it.numeric = std::isfinite(v);
    it.value = v;
    items_.push_back(it);
}

void Summary::add_int(const std::string &key, std::int64_t v)
{
    Item it;
    it.key = key;
    it.text = std::to_string(v);
    it.numeric = true;
    it.integer = true;
    it.ivalue = v;
    it.value = static_cast<double>(v);
    items_.push_back(it);
}

void Summary::add_hex(const std::string &key, std::uint32_t v)
{
    char b[16];
    std::snprintf(b, sizeof b, "0x%08x", v);
    Item it;
    it.key = key;
    it.text = b;
    it.numeric = true;
    it.integer = true;
    it.ivalue = static_cast<std::int64_t>(v);
    it.value = static_cast<double>(v);
    items_.push_back(it);
}

void Summary::add_str(const std::string &key, const std::string &v)
{
    Item it;
    it.key = key;
    it.text = v;
    items_.push_back(it);
}

std::string Summary::text() const
{
    std::ostringstream o;
    for (const Item &it : items_) {
        o << it.key << " = " << it.text << "\n";
    }
    return o.str();
}

std::string Summary::json() const
{
    nlohmann::ordered_json j = nlohmann::ordered_json::object();
    for (const Item &it : items_) {
        if (it.integer) {
            j[it.key] = it.ivalue;
        } else if (it.numeric) {
            j[it.key] = it.value;
        } else {
            j[it.key] = it.text;
        }
    }
    return j.dump(1) + "\n";
}

bool Summary::has(const std::string &key) const
{
    for (const Item &it : items_) {
        if (it.key == key) {
            return true;
        }
    }
    return false;
}

double Summary::number(const std::string &key) const
{
    for (const Item &it : items_) {
        if (it.key == key && it.numeric) {
            return it.value;
        }
    }
    throw std::out_of_range("summary has no number '" + key + "'");
}

// ---------------------------------------------------------------------------- the mission

const MissionHost &mission_host(const std::string &mission)
{
    const MissionHost *h = find_host_gen(mission);
    if (h == nullptr) {
        throw std::invalid_argument("mission '" + mission + "' is not in this build (" + mission_list() + ")");
    }
    return *h;
}

fsw_cfg_t fsw_cfg(const sim::Scenario &s)
{
    const iface::Mission &m = iface_mission(s.mission);
    fsw_cfg_t c{};
    c.period_us = s.period_us;
    c.stale_max = mission_host(s.mission).stale_max();
    c.boot_mode = m.mode;
    c.mission = m.id;
    return c;
}

std::pair<const std::uint8_t *, std::uint32_t> image_payload(const std::vector<std::uint8_t> &image)
{
    if (image.size() < FSW_TABLE_HDR_BYTES) {
        throw std::invalid_argument("table image of " + std::to_string(image.size()) + " bytes is shorter than its " +
                                    std::to_string(FSW_TABLE_HDR_BYTES) + "-byte header");
    }
    return {image.data() + FSW_TABLE_HDR_BYTES, static_cast<std::uint32_t>(image.size() - FSW_TABLE_HDR_BYTES)};
}

std::uint32_t image_revision(const std::vector<std::uint8_t> &image)
{
    if (image.size() < FSW_TABLE_HDR_BYTES) {
        return 0u;
    }
    return static_cast<std::uint32_t>(image[8]) | (static_cast<std::uint32_t>(image[9]) << 8) |
           (static_cast<std::uint32_t>(image[10]) << 16) | (static_cast<std::uint32_t>(image[11]) << 24);
}

}  // namespace host
