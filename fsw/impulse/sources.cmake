# fsw/impulse: the impulse scheduler (spec 50-impulse): switching-time solver, module step and
# its generated default table (python -m tools.impulse ctable).
list(APPEND FSW_SOURCES
  impulse/imp_cw.c
  impulse/imp_log.c
  impulse/imp_solve.c
  impulse/imp_sched.c
  impulse/imp.c
  impulse/imp_tl.c
  impulse/imp_nav.c
  impulse/imp_tables.c
)
