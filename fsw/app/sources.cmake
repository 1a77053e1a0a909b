# fsw/app: tables (codec, loader, validation), the observer and impulse table images, the executive and its
# telemetry encoder. Included by fsw/CMakeLists.txt.
list(APPEND FSW_SOURCES
  app/fsw_codec.c
  app/fsw_table.c
  app/fsw_obs_table.c
  app/fsw_imp_table.c
  app/fsw_exec.c
  app/fsw_tlm.c
  app/fsw_tlm_rdv.c
)
