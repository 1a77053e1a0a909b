# fsw/app: the mission-agnostic executive, the table loader and codec, the telemetry header.
# Included by fsw/CMakeLists.txt; the missions' sources come from fsw/<module>/sources.cmake.
list(APPEND FSW_SOURCES
  app/fsw_codec.c
  app/fsw_link.c
  app/fsw_pil.c
  app/fsw_pil_board.c
  app/fsw_table.c
  app/fsw_exec.c
  app/fsw_tlm.c
  app/fsw_tlm_head.c
)
