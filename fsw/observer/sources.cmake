# fsw/observer: the adaptive observer step (spec 10-observer) and its generated boot tables.
list(APPEND FSW_SOURCES
  observer/obs.c
  observer/obs_tables.c
)
