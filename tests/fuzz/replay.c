/* Replays inputs through a fuzz harness without libFuzzer: each argument is a file, or a
 * directory whose files are replayed in name order. Built with the project's compiler, plain
 * and under the sanitizers, so `make check` runs the committed corpus and every past crash or
 * hang reproducer; a crash, a sanitizer report or an abort fails it. Prints "replayed N inputs". */
#include <dirent.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "fuzz.h"

static int replay_file(const char *path)
{
    FILE *fp = fopen(path, "rb");
    if (fp == NULL) {
        fprintf(stderr, "replay: cannot read '%s'\n", path);
        return -1;
    }
    size_t cap = 4096, n = 0;
    unsigned char *buf = malloc(cap);
    for (size_t got; buf != NULL && (got = fread(buf + n, 1, cap - n, fp)) > 0;) {
        n += got;
        if (n == cap) {
            unsigned char *bigger = realloc(buf, cap *= 2);
            if (bigger == NULL) free(buf);
            buf = bigger;
        }
    }
    fclose(fp);
    if (buf == NULL) return -1;
    LLVMFuzzerTestOneInput(buf, n);
    free(buf);
    return 0;
}

static int by_name(const void *a, const void *b)
{
    return strcmp(*(char *const *)a, *(char *const *)b);
}

int main(int argc, char **argv)
{
    long count = 0;
    for (int i = 1; i < argc; i++) {
        struct stat st;
        if (stat(argv[i], &st) != 0) {
            fprintf(stderr, "replay: no such file or directory '%s'\n", argv[i]);
            return 1;
        }
        if (!S_ISDIR(st.st_mode)) {
            if (replay_file(argv[i]) != 0) return 1;
            count++;
            continue;
        }
        DIR *dir = opendir(argv[i]);
        if (dir == NULL) return 1;
        size_t n = 0, cap = 64;
        char **names = malloc(cap * sizeof *names);
        for (struct dirent *e; names != NULL && (e = readdir(dir)) != NULL;) {
            if (e->d_name[0] == '.') continue;
            if (n == cap) {
                char **bigger = realloc(names, (cap *= 2) * sizeof *names);
                if (bigger == NULL) break;
                names = bigger;
            }
            size_t len = strlen(argv[i]) + strlen(e->d_name) + 2;
            if ((names[n] = malloc(len)) == NULL) break;
            snprintf(names[n++], len, "%s/%s", argv[i], e->d_name);
        }
        closedir(dir);
        if (names == NULL) return 1;
        qsort(names, n, sizeof *names, by_name);
        int bad = 0;
        for (size_t k = 0; k < n; k++) {
            if (!bad && replay_file(names[k]) != 0) bad = 1;
            free(names[k]);
        }
        free(names);
        if (bad) return 1;
        count += (long)n;
    }
    printf("replayed %ld inputs\n", count);
    return 0;
}
