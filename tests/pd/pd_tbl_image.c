/* Writes the C encoder's image of PD_TBL_DEFAULT: pd_tbl_image REVISION FILE (host
   test helper of CTest golden_pd_table_image). */
#include <stdio.h>
#include <stdlib.h>

#include "pd_mission.h"
#include "pd_tables.h"

int main(int argc, char **argv)
{
    uint8_t img[FSW_TABLE_HDR_BYTES + PD_TBL_PAYLOAD];
    uint32_t n;
    FILE *f;
    if (argc != 3) {
        fprintf(stderr, "usage: pd_tbl_image REVISION FILE\n");
        return 2;
    }
    n = pd_table_encode(&PD_TBL_DEFAULT, (uint32_t)strtoul(argv[1], NULL, 10), img, (uint32_t)sizeof(img));
    f = fopen(argv[2], "wb");
    if ((n == 0u) || (f == NULL) || (fwrite(img, 1u, n, f) != n)) {
        fprintf(stderr, "pd_tbl_image: cannot write %s\n", argv[2]);
        return 1;
    }
    return (fclose(f) == 0) ? 0 : 1;
}
