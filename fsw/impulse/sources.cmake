# fsw/impulse: the impulse scheduler (spec 50-impulse): switching-time solver, module step, its
# generated default tables (python -m tools.impulse ctable), and the RENDEZVOUS mission: table
# codec, adapter, telemetry block (generated from imp_iface.py).
list(APPEND FSW_SOURCES
  impulse/imp_cw.c
  impulse/imp_log.c
  impulse/imp_solve.c
  impulse/imp_sched.c
  impulse/imp.c
  impulse/imp_tl.c
  impulse/imp_nav.c
  impulse/imp_tables.c
  impulse/imp_table.c
  impulse/imp_mission.c
  impulse/imp_tlm.c
)
