/*
 * fuzz_replay_main — runs a libFuzzer entry point without libFuzzer (GCC host builds, spec 00
 * §8: "the same entry points run as corpus-replay tests where clang is absent").
 *
 * Usage: fuzz_replay_<target> CORPUS_DIR [N_RANDOM [SEED]]
 *   1. every regular file of CORPUS_DIR (sorted by name) through LLVMFuzzerTestOneInput;
 *   2. N_RANDOM (default 20000) pseudo-random inputs from splitmix64(SEED) (default 1):
 *      lengths 0..511, half of them mutations of a corpus file (byte flips, inserts, cuts)
 *      so the random part also reaches deep states.
 * A violated invariant traps (the test fails by signal); exit 0 otherwise.
 */
#define _POSIX_C_SOURCE 200809L
#include <dirent.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

#define RP_MAX_FILES 4096u
#define RP_MAX_BYTES 65536u

static uint64_t rp_splitmix64(uint64_t *s)
{
    uint64_t z;
    *s += UINT64_C(0x9E3779B97F4A7C15);
    z = *s;
    z = (z ^ (z >> 30)) * UINT64_C(0xBF58476D1CE4E5B9);
    z = (z ^ (z >> 27)) * UINT64_C(0x94D049BB133111EB);
    return z ^ (z >> 31);
}

static int rp_cmp(const void *a, const void *b)
{
    return strcmp(*(const char *const *)a, *(const char *const *)b);
}

typedef struct {
    uint8_t *data;
    size_t size;
} rp_file_t;

static size_t rp_read(const char *path, uint8_t *buf, size_t cap)
{
    size_t n = 0u;
    FILE *f = fopen(path, "rb");
    if (f != NULL) {
        n = fread(buf, 1u, cap, f);
        (void)fclose(f);
    }
    return n;
}

int main(int argc, char **argv)
{
    static char *names[RP_MAX_FILES];
    static rp_file_t files[RP_MAX_FILES];
    static uint8_t buf[RP_MAX_BYTES];
    size_t nfiles = 0u;
    size_t i;
    unsigned long nrand = 20000ul;
    uint64_t seed = 1u;
    DIR *dir;
    struct dirent *e;
    char path[4096];

    if (argc < 2) {
        (void)fprintf(stderr, "usage: %s CORPUS_DIR [N_RANDOM [SEED]]\n", argv[0]);
        return 2;
    }
    if (argc > 2) {
        nrand = strtoul(argv[2], NULL, 0);
    }
    if (argc > 3) {
        seed = (uint64_t)strtoull(argv[3], NULL, 0);
    }
    dir = opendir(argv[1]);
    if (dir == NULL) {
        (void)fprintf(stderr, "%s: cannot open corpus %s\n", argv[0], argv[1]);
        return 2;
    }
    while (((e = readdir(dir)) != NULL) && (nfiles < RP_MAX_FILES)) {
        if (e->d_name[0] != '.') {
            size_t l = strlen(e->d_name) + 1u;
            names[nfiles] = (char *)malloc(l);
            if (names[nfiles] == NULL) {
                return 2;
            }
            (void)memcpy(names[nfiles], e->d_name, l);
            nfiles++;
        }
    }
    (void)closedir(dir);
    qsort(names, nfiles, sizeof names[0], rp_cmp);
    for (i = 0u; i < nfiles; i++) {
        size_t n;
        (void)snprintf(path, sizeof path, "%s/%s", argv[1], names[i]);
        n = rp_read(path, buf, sizeof buf);
        files[i].data = (uint8_t *)malloc((n > 0u) ? n : 1u);
        if (files[i].data == NULL) {
            return 2;
        }
        (void)memcpy(files[i].data, buf, n);
        files[i].size = n;
        /* exact-size heap copy, so a sanitizer build sees an overread of the input */
        (void)LLVMFuzzerTestOneInput(files[i].data, n);
    }
    (void)printf("replayed %lu corpus files from %s\n", (unsigned long)nfiles, argv[1]);

    for (i = 0u; i < nrand; i++) {
        uint64_t r = rp_splitmix64(&seed);
        size_t n;
        uint8_t *in;
        size_t k;
        if (((r & 1u) != 0u) && (nfiles > 0u)) {
            const rp_file_t *f = &files[(size_t)((r >> 1) % nfiles)];
            uint32_t nmut = (uint32_t)((r >> 20) % 4u) + 1u;
            uint32_t m;
            n = f->size;
            (void)memcpy(buf, f->data, n);
            for (m = 0u; m < nmut; m++) {
                uint64_t q = rp_splitmix64(&seed);
                size_t at = (n > 0u) ? (size_t)((q >> 8) % n) : 0u;
                switch (q % 4u) {
                case 0u: /* flip a bit */
                    if (n > 0u) {
                        buf[at] ^= (uint8_t)(1u << ((q >> 40) % 8u));
                    }
                    break;
                case 1u: /* overwrite a byte */
                    if (n > 0u) {
                        buf[at] = (uint8_t)(q >> 48);
                    }
                    break;
                case 2u: /* insert a byte */
                    if (n < sizeof buf) {
                        (void)memmove(&buf[at + 1u], &buf[at], n - at);
                        buf[at] = (uint8_t)(q >> 48);
                        n++;
                    }
                    break;
                default: /* cut the tail */
                    n = at;
                    break;
                }
            }
        } else {
            n = (size_t)((r >> 1) % 512u);
            for (k = 0u; k < n; k++) {
                if ((k % 8u) == 0u) {
                    r = rp_splitmix64(&seed);
                }
                buf[k] = (uint8_t)(r >> (8u * (k % 8u)));
            }
        }
        in = (uint8_t *)malloc((n > 0u) ? n : 1u);
        if (in == NULL) {
            return 2;
        }
        (void)memcpy(in, buf, n);
        (void)LLVMFuzzerTestOneInput(in, n);
        free(in);
    }
    (void)printf("ran %lu seeded pseudo-random inputs\n", nrand);
    for (i = 0u; i < nfiles; i++) {
        free(files[i].data);
        free(names[i]);
    }
    return 0;
}
