/* Fuzz harness: the CSV reader of `whirl fit` (points_csv_read) on arbitrary bytes, then, for a
 * few points that pass it, the checks and the distances of whirl_fit_residuals. Every input must
 * end in points or a one-line error. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli/points_csv.h"
#include "fuzz.h"
#include "whirl/optimize.h"

#define FIT_POINTS_MAX 32

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    static const cli_command cmd = {"fit", "", "", NULL};
    FILE *fp = fmemopen((void *)data, size, "r");
    if (fp == NULL) return 0;
    fuzz_quiet q; /* the reader's one-line errors are expected */
    fuzz_quiet_begin(&q);
    points_csv p = {0, 0, NULL, NULL};
    int rc = points_csv_read(&cmd, fp, "fuzz.csv", &p);
    fclose(fp);
    fuzz_quiet_end(&q);
    if (rc == 0 && p.n >= 3 && p.n <= FIT_POINTS_MAX) {
        whirl_fit_model m = whirl_fit_model_defaults();
        m.samples = 201;
        double resid[FIT_POINTS_MAX];
        if (whirl_fit_residuals(&m, 2.7, 1, 0, p.n, p.r, p.z, resid) == GSL_SUCCESS)
            for (size_t i = 0; i < p.n; i++)
                if (resid[i] != resid[i]) abort(); /* a NaN distance of finite points */
    }
    points_csv_free(&p);
    return 0;
}
