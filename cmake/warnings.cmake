# Warning set of spec 00 §4; warnings are errors everywhere.
set(FSW_C_WARNINGS
  -Wall -Wextra -Wpedantic -Wconversion -Wsign-conversion -Wshadow -Wdouble-promotion
  -Wfloat-equal -Wcast-align -Wstrict-prototypes -Wmissing-prototypes -Wvla -Wundef -Werror)
# Flight code only: sections for --gc-sections, and no tentative definitions in common.
set(FSW_FLIGHT_FLAGS -ffunction-sections -fdata-sections -fno-common)
