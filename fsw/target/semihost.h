/*
 * semihost.h — ARM semihosting calls (BKPT 0xAB on M-profile). Compiled only into the qemu
 * board variant: on a board without a debugger attached BKPT faults.
 */
#ifndef FSW_TARGET_SEMIHOST_H
#define FSW_TARGET_SEMIHOST_H

#include <stdint.h>

#define SEMIHOST_SYS_WRITEC         0x03u
#define SEMIHOST_SYS_WRITE0         0x04u
#define SEMIHOST_SYS_GET_CMDLINE    0x15u
#define SEMIHOST_SYS_EXIT_EXTENDED  0x20u
#define SEMIHOST_ADP_APP_EXIT       0x20026u   /* ADP_Stopped_ApplicationExit */

uint32_t semihost_call(uint32_t op, const void *arg);
void     semihost_write0(const char *s);
void     semihost_writec(char c);
/*
 * SYS_EXIT_EXTENDED carries a status code on AArch32; plain SYS_EXIT (0x18) there reports only
 * success or failure, so QEMU's exit status would be 0 or 1.
 */
void     semihost_exit(uint32_t code) __attribute__((noreturn));
/* Command line (QEMU: kernel file name followed by -append); length, or -1 if unavailable. */
int32_t  semihost_get_cmdline(char *buf, uint32_t len);

#endif /* FSW_TARGET_SEMIHOST_H */
