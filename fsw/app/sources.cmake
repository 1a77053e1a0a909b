# fsw/app: parameter-table machinery (codec, loader, validation). Included by fsw/CMakeLists.txt.
list(APPEND FSW_SOURCES
  app/fsw_codec.c
  app/fsw_table.c
)
