/* SPDX-License-Identifier: GPL-3.0-or-later */
/* Without libFuzzer (gcc builds): run the harness over the files of the
 * directories given on the command line (the seed corpus: every scene and
 * scene test file; the MatrixMarket seeds), so that the suite checks its
 * contract too. */
#include <dirent.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

static uint8_t buf[1 << 20];

int main(int argc, char **argv)
{
    int done = 0;
    for (int k = 1; k < argc; k++) {
        DIR *dir = opendir(argv[k]);
        if (!dir) {
            fprintf(stderr, "replay: cannot open %s\n", argv[k]);
            return 1;
        }
        for (struct dirent *e; (e = readdir(dir));) {
            size_t len = strlen(e->d_name);
            if (len < 4 || (strcmp(e->d_name + len - 4, ".ini") != 0 && strcmp(e->d_name + len - 4, ".mtx") != 0))
                continue;
            char path[4096];
            snprintf(path, sizeof path, "%s/%s", argv[k], e->d_name);
            FILE *f = fopen(path, "rb");
            if (!f)
                continue;
            size_t n = fread(buf, 1, sizeof buf, f);
            fclose(f);
            LLVMFuzzerTestOneInput(buf, n);
            done++;
        }
        closedir(dir);
    }
    printf("replay: %d inputs, no contract broken\n", done);
    return done > 0 ? 0 : 1;
}
