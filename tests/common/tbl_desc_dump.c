/* tbl_desc_dump.c — print a module's table limits descriptor (host tool of the configuration
 * tests): the flight loader's per-field limits and relations, so that the Python image writer's
 * mirror of them (tools/<module>/image.py, Layout.descriptor_text) is compared with the C table
 * itself. Built once per module with TBL_DESC_HDR (its mission header) and TBL_DESC (the
 * descriptor). Output, one line each:
 *   desc <table_id> <layout_version> <payload_len> <n_fields> <n_rels>
 *   lim <offset> <type> <min> <max>
 *   rel <a> <b> <margin>
 */
#include <inttypes.h>
#include <stdio.h>

#include TBL_DESC_HDR

int main(void)
{
    const fsw_table_desc_t *d = &TBL_DESC;
    uint32_t i;
    printf("desc %u %u %" PRIu32 " %" PRIu32 " %" PRIu32 "\n", (unsigned)d->table_id, (unsigned)d->layout_version,
           d->payload_len, d->n_fields, d->n_rels);
    for (i = 0u; i < d->n_fields; i++) {
        printf("lim %u %u %" PRId64 " %" PRId64 "\n", (unsigned)d->fields[i].offset, (unsigned)d->fields[i].type,
               d->fields[i].min, d->fields[i].max);
    }
    for (i = 0u; i < d->n_rels; i++) {
        printf("rel %u %u %" PRId32 "\n", (unsigned)d->rels[i].a, (unsigned)d->rels[i].b, d->rels[i].margin);
    }
    return 0;
}
