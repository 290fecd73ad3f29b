/* tests/fuzz/replay.c: main() of a fuzz harness outside libFuzzer builds:
 * runs LLVMFuzzerTestOneInput once on every regular file of the directories
 * (and files) given on the command line, in name order, and prints how many.
 * A crash or a violated property aborts (the ctest fails); a missing
 * directory is skipped. Usage: fuzz_NAME DIR_OR_FILE... */
#include "fuzz_common.h"

#include <dirent.h>
#include <sys/stat.h>

static int cmp_str(const void *a, const void *b)
{
    return strcmp(*(char *const *)a, *(char *const *)b);
}

static int run_file(const char *path)
{
    FILE *f = fopen(path, "rb");
    if (!f) {
        fprintf(stderr, "replay: cannot open %s\n", path);
        return 0;
    }
    uint8_t *buf = NULL;
    size_t n = 0, cap = 0;
    for (;;) {
        if (n == cap) {
            cap = cap ? 2 * cap : 4096;
            uint8_t *nb = realloc(buf, cap);
            if (!nb) abort();
            buf = nb;
        }
        size_t k = fread(buf + n, 1, cap - n, f);
        if (k == 0) break;
        n += k;
    }
    fclose(f);
    LLVMFuzzerTestOneInput(buf, n);
    free(buf);
    return 1;
}

int main(int argc, char **argv)
{
    int runs = 0;
    for (int a = 1; a < argc; a++) {
        struct stat sb;
        if (stat(argv[a], &sb) != 0) continue;
        if (S_ISREG(sb.st_mode)) {
            runs += run_file(argv[a]);
            continue;
        }
        DIR *d = opendir(argv[a]);
        if (!d) continue;
        char **names = NULL;
        size_t nn = 0, cap = 0;
        struct dirent *e;
        while ((e = readdir(d)) != NULL) {
            if (e->d_name[0] == '.') continue;
            if (nn == cap) {
                cap = cap ? 2 * cap : 64;
                char **nb = realloc(names, cap * sizeof *names);
                if (!nb) abort();
                names = nb;
            }
            size_t len = strlen(argv[a]) + strlen(e->d_name) + 2;
            names[nn] = malloc(len);
            if (!names[nn]) abort();
            snprintf(names[nn], len, "%s/%s", argv[a], e->d_name);
            nn++;
        }
        closedir(d);
        qsort(names, nn, sizeof *names, cmp_str);
        for (size_t i = 0; i < nn; i++) {
            if (stat(names[i], &sb) == 0 && S_ISREG(sb.st_mode)) runs += run_file(names[i]);
            free(names[i]);
        }
        free(names);
    }
    printf("replayed %d input%s\n", runs, runs == 1 ? "" : "s");
    return 0;
}
