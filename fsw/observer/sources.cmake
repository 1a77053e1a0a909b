# fsw/observer: the adaptive observer step (spec 10-observer), its generated boot tables, and the
# DETUMBLE mission: table codec, adapter, telemetry block (generated from obs_iface.py).
list(APPEND FSW_SOURCES
  observer/obs.c
  observer/obs_tables.c
  observer/obs_table.c
  observer/obs_mission.c
  observer/obs_tlm.c
)
