#!/usr/bin/env python3
"""Cross-language check of the gnc LCM bindings (spec 00 §5.1, §5.3).

1. The C binding writes one event per type to an LCM event log (lcm_xlang_c write).
2. Python reads it with lcm.EventLog, decodes each event with the lcm-gen Python types, checks
   every field against the pattern of tests/lcm/lcm_pattern.h (rebuilt here), and checks that the
   Python re-encoding is byte-identical.
3. Python writes the pattern to a second log; the C binding decodes it (lcm_xlang_c check).

usage: lcm_xlang_check.py <lcm_xlang_c> <generated python dir> <work dir>
"""
import os
import struct
import subprocess
import sys

M64 = (1 << 64) - 1


class Pattern:
    """splitmix64, one draw per field element, truncated two's complement (lcm_pattern.h)."""

    def __init__(self, seed):
        self.s = seed

    def u64(self):
        self.s = (self.s + 0x9E3779B97F4A7C15) & M64
        z = self.s
        z = ((z ^ (z >> 30)) * 0xBF58476D1CE4E5B9) & M64
        z = ((z ^ (z >> 27)) * 0x94D049BB133111EB) & M64
        return z ^ (z >> 31)

    def signed(self, bits):
        v = self.u64() & ((1 << bits) - 1)
        return v - (1 << bits) if v >> (bits - 1) else v

    def i64(self): return self.signed(64)
    def i32(self): return self.signed(32)
    def i16(self): return self.signed(16)
    def i8(self): return self.signed(8)
    def u8(self): return self.u64() & 0xFF
    def f64(self): return self.i32() / 1024.0


def bits_to_double(b):
    return struct.unpack('>d', struct.pack('>Q', b))[0]


def expected(gnc):
    """Type name -> (class, expected message) in lcm_pattern.h order."""
    out = {}
    p = Pattern(101); m = gnc.sensor_frame_t()
    m.utime, m.seq, m.period_us, m.n_counts = p.i64(), p.i64(), p.i32(), p.i16()
    m.counts = [p.i32() for _ in range(16)]; m.status = [p.i8() for _ in range(16)]
    m.scenario_flags, m.plant_flags = p.i32(), p.i32()
    out['sensor_frame_t'] = m

    p = Pattern(102); m = gnc.actuator_cmd_t()
    m.utime, m.seq, m.n_counts = p.i64(), p.i64(), p.i16()
    m.counts = [p.i32() for _ in range(16)]
    m.fsw_mode, m.fsw_health = p.i32(), p.i32()
    out['actuator_cmd_t'] = m

    p = Pattern(103); m = gnc.fsw_tlm_frame_t()
    m.utime, m.seq, m.tlm_layout_version, m.tlm_len = p.i64(), p.i64(), p.i32(), p.i16()
    m.tlm = bytes(p.u8() for _ in range(512))
    (m.dups, m.stale, m.gaps, m.rejected, m.nonfinite_rej, m.range_rej, m.missed,
     m.table_rej) = [p.i32() for _ in range(8)]
    out['fsw_tlm_frame_t'] = m

    p = Pattern(104); m = gnc.sim_truth_t()
    m.utime, m.seq = p.i64(), p.i64()
    m.state = [p.f64() for _ in range(16)]
    extra = [p.f64() for _ in range(8)]
    for i, b in enumerate((0x8000000000000000, 0x1, 0x7FF0000000000000, 0xFFEBCCA8F4D0C3E2)):
        extra[i] = bits_to_double(b)
    m.extra = extra
    m.events = p.i32()
    out['sim_truth_t'] = m

    p = Pattern(105); m = gnc.table_upload_t()
    m.utime, m.table_id, m.revision, m.total_len, m.offset, m.n = (
        p.i64(), p.i32(), p.i32(), p.i32(), p.i32(), p.i16())
    m.data = bytes(p.u8() for _ in range(256))
    out['table_upload_t'] = m

    p = Pattern(106); m = gnc.table_ack_t()
    m.utime, m.table_id, m.revision, m.result, m.reason, m.bytes_received = (
        p.i64(), p.i32(), p.i32(), p.i32(), p.i32(), p.i32())
    out['table_ack_t'] = m

    p = Pattern(107); m = gnc.sil_ctl_t()
    m.utime, m.command = p.i64(), p.i32()
    m.scenario = bytes(p.u8() for _ in range(32))
    m.seed, m.node_id, m.status = p.i64(), p.i32(), p.i32()
    out['sil_ctl_t'] = m

    p = Pattern(108); m = gnc.fsw_cmd_t()
    m.utime, m.apply_seq, m.cmd = p.i64(), p.i64(), p.i32()
    m.args = [p.i32() for _ in range(8)]
    out['fsw_cmd_t'] = m

    # The v2 types: the v1 fields, then crc32 as one more draw (lcm_pattern.h pat_*2).
    p = Pattern(109); m = gnc.sensor_frame_v2_t()
    m.utime, m.seq, m.period_us, m.n_counts = p.i64(), p.i64(), p.i32(), p.i16()
    m.counts = [p.i32() for _ in range(16)]; m.status = [p.i8() for _ in range(16)]
    m.scenario_flags, m.plant_flags, m.crc32 = p.i32(), p.i32(), p.i32()
    out['sensor_frame_v2_t'] = m

    p = Pattern(110); m = gnc.actuator_cmd_v2_t()
    m.utime, m.seq, m.n_counts = p.i64(), p.i64(), p.i16()
    m.counts = [p.i32() for _ in range(16)]
    m.fsw_mode, m.fsw_health, m.crc32 = p.i32(), p.i32(), p.i32()
    out['actuator_cmd_v2_t'] = m

    p = Pattern(111); m = gnc.table_upload_v2_t()
    m.utime, m.table_id, m.revision, m.total_len, m.offset, m.n = (
        p.i64(), p.i32(), p.i32(), p.i32(), p.i32(), p.i16())
    m.data = bytes(p.u8() for _ in range(256))
    m.crc32 = p.i32()
    out['table_upload_v2_t'] = m

    p = Pattern(112); m = gnc.fsw_cmd_v2_t()
    m.utime, m.apply_seq, m.cmd = p.i64(), p.i64(), p.i32()
    m.args = [p.i32() for _ in range(8)]
    m.crc32 = p.i32()
    out['fsw_cmd_v2_t'] = m
    return out


def norm(v):
    """Comparable form: doubles by bit pattern, sequences as tuples, bytes as bytes."""
    if isinstance(v, float):
        return ('f', struct.pack('>d', v))
    if isinstance(v, (bytes, bytearray)):
        return bytes(v)
    if isinstance(v, (list, tuple)):
        return tuple(norm(x) for x in v)
    return v


def main():
    if len(sys.argv) != 4:
        print(__doc__)
        return 2
    exe, pydir, work = sys.argv[1:]
    sys.path.insert(0, pydir)
    import lcm
    import gnc
    os.makedirs(work, exist_ok=True)
    exp = expected(gnc)
    errors = 0

    # 1-2: C writes, Python reads.
    c_log = os.path.join(work, 'xlang_c.lcmlog')
    subprocess.run([exe, 'write', c_log], check=True)
    seen = set()
    for ev in lcm.EventLog(c_log, 'r'):
        name = ev.channel
        if name not in exp:
            print('unexpected channel', name); errors += 1; continue
        cls = type(exp[name])
        msg = cls.decode(ev.data)
        for field in cls.__slots__:
            got, want = norm(getattr(msg, field)), norm(getattr(exp[name], field))
            if got != want:
                print(f'{name}.{field}: Python decoded {got!r}, pattern {want!r}'); errors += 1
        if msg.encode() != ev.data:
            print(f'{name}: Python re-encoding differs from the C encoding'); errors += 1
        if exp[name].encode() != ev.data:
            print(f'{name}: Python encoding of the pattern differs from the C encoding'); errors += 1
        seen.add(name)
    if seen != set(exp):
        print('missing types in the C log:', sorted(set(exp) - seen)); errors += 1
    print(f'Python decoded {len(seen)} types from {c_log}: {errors} error(s)')

    # 3: Python writes, C reads.
    py_log = os.path.join(work, 'xlang_py.lcmlog')
    log = lcm.EventLog(py_log, 'w', overwrite=True)
    for i, (name, m) in enumerate(exp.items()):
        log.write_event(1000000 + i, name, m.encode())
    log.close()
    r = subprocess.run([exe, 'check', py_log])
    if r.returncode != 0:
        errors += 1

    print('PASS' if errors == 0 else f'FAIL: {errors} error(s)')
    return 0 if errors == 0 else 1


if __name__ == '__main__':
    sys.exit(main())
