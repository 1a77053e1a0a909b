"""Byte comparison of two SIL logs, channel by channel, message by message (spec 00 §5.2).

    python -m tools.sil compare LOG_A LOG_B [--channel GNC_TLM] [--channel GNC_CMD] [--dedup]

Exit code 0 iff every listed channel carries the same number of messages with identical payload
bytes (the LCM-encoded message, fingerprint included) in the same order.
"""
from . import lcmio

DEFAULT_CHANNELS = ("GNC_TLM", "GNC_CMD")


def payloads(path, channels, dedup=False):
    out = {c: [] for c in channels}
    for _, ch, data in lcmio.events(path):
        lst = out.get(ch)
        if lst is None:
            continue
        if dedup and lst and lst[-1] == data:
            continue
        lst.append(bytes(data))
    return out


def _describe(ch, data, lcm_py):
    """Best-effort field diff helper: decode one payload into a dict (None if impossible); the
    telemetry in the layout of the mission its layout version names (tools.iface)."""
    try:
        cls = lcmio.msg_type(lcmio.load_types(lcm_py), ch)
        msg = cls.decode(data)
    except Exception:
        return None
    d = {k: getattr(msg, k) for k in msg.__slots__}
    if ch == "GNC_TLM":
        from tools import iface
        buf = bytes(d.pop("tlm"))[:d["tlm_len"]]
        try:
            lay = iface.mission(d["tlm_layout_version"] & 0xFFFFFFFF).layout
            d.update({"tlm." + k: v for k, v in lay.decode(buf).items()})
        except iface.IfaceError as e:
            d["tlm"] = "undecodable: %s" % e
    return d


def main(args):
    channels = args.channel or list(DEFAULT_CHANNELS)
    a = payloads(args.log_a, channels, args.dedup)
    b = payloads(args.log_b, channels, args.dedup)
    ok = True
    for ch in channels:
        pa, pb = a[ch], b[ch]
        n = min(len(pa), len(pb))
        first = next((i for i in range(n) if pa[i] != pb[i]), None)
        if first is None and len(pa) == len(pb):
            if len(pa) == 0:
                print("%s: no messages in either log" % ch)
                ok = False
            else:
                print("%s: identical: %d messages" % (ch, len(pa)))
            continue
        ok = False
        if first is None:
            print("%s: differ: first %d messages identical, then message count %d vs %d (first differing index %d)"
                  % (ch, n, len(pa), len(pb), n))
            continue
        print("%s: differ: first differing index %d (of %d vs %d messages)" % (ch, first, len(pa), len(pb)))
        da, db = _describe(ch, pa[first], args.lcm_py), _describe(ch, pb[first], args.lcm_py)
        if da is not None and db is not None:
            keys = list(da) + [k for k in db if k not in da]
            diffs = [k for k in keys if da.get(k) != db.get(k)]
            for k in diffs[:12]:
                print("    %-28s A %s  B %s" % (k, da.get(k), db.get(k)))
            if len(diffs) > 12:
                print("    ... %d more fields differ" % (len(diffs) - 12))
    return 0 if ok else 1
