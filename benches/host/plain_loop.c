/* The plain C loop over an FMI 2.0 co-simulation FMU's binary: the baseline
 * of benches/host_loop.py. It loads the library, instantiates, sets the
 * parameters, steps through the input (value and slope at every communication
 * point, as rocking.fmu does) and reads the real outputs after every step
 * into memory; it prints the CPU time of this process from instantiate to
 * free in seconds (CLOCK_PROCESS_CPUTIME_ID: other processes on a shared
 * machine do not count), the number of rows and a checksum of the outputs.
 *
 * Usage: plain_loop LIBRARY GUID TOL INPUT N VR_AG ARG...
 *   INPUT: N+1 grid points, then N+1 inputs, then N+1 slopes (float64, native order)
 *   ARG:   r:VR:VALUE (fmi2SetReal), i:VR:VALUE (fmi2SetInteger), o:VR (a real output)
 * The FMI 2.0 types are written here from the standard's signatures (only those used). */
#include <dlfcn.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

typedef void *C;
typedef struct {
    void (*logger)(void *, const char *, int, const char *, const char *, ...);
    void *(*alloc)(size_t, size_t);
    void (*free)(void *);
    void *step_finished;
    void *env;
} Callbacks;
static void logger(void *e, const char *n, int s, const char *c, const char *m, ...) {
    (void)e; (void)n; (void)c;
    if (s > 1) fprintf(stderr, "[%d] %s\n", s, m);
}

static void *sym(void *lib, const char *name) {
    void *f = dlsym(lib, name);
    if (!f) { fprintf(stderr, "%s: not found\n", name); exit(2); }
    return f;
}

int main(int argc, char **argv) {
    if (argc < 7) { fprintf(stderr, "usage: see the header of plain_loop.c\n"); return 2; }
    void *lib = dlopen(argv[1], RTLD_NOW | RTLD_LOCAL);
    if (!lib) { fprintf(stderr, "%s\n", dlerror()); return 2; }
    double tol = atof(argv[3]);
    size_t n = strtoul(argv[5], NULL, 10);
    unsigned vr_ag = strtoul(argv[6], NULL, 10);
    double *buf = malloc(3 * (n + 1) * sizeof(double));
    FILE *f = fopen(argv[4], "rb");
    if (!f || fread(buf, sizeof(double), 3 * (n + 1), f) != 3 * (n + 1)) { fprintf(stderr, "input\n"); return 2; }
    fclose(f);
    double *grid = buf, *acc = buf + n + 1, *slope = buf + 2 * (n + 1);
    unsigned out_vr[64]; size_t n_out = 0;

    C (*inst)(const char *, int, const char *, const char *, const Callbacks *, int, int) = sym(lib, "fmi2Instantiate");
    int (*setup)(C, int, double, double, int, double) = sym(lib, "fmi2SetupExperiment");
    int (*set_real)(C, const unsigned *, size_t, const double *) = sym(lib, "fmi2SetReal");
    int (*set_int)(C, const unsigned *, size_t, const int *) = sym(lib, "fmi2SetInteger");
    int (*get_real)(C, const unsigned *, size_t, double *) = sym(lib, "fmi2GetReal");
    int (*set_der)(C, const unsigned *, size_t, const int *, const double *) = sym(lib, "fmi2SetRealInputDerivatives");
    int (*enter)(C) = sym(lib, "fmi2EnterInitializationMode");
    int (*exit_)(C) = sym(lib, "fmi2ExitInitializationMode");
    int (*do_step)(C, double, double, int) = sym(lib, "fmi2DoStep");
    int (*terminate)(C) = sym(lib, "fmi2Terminate");
    void (*free_)(C) = sym(lib, "fmi2FreeInstance");

    struct timespec t0, t1;
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t0);
    Callbacks cb = {logger, calloc, free, NULL, NULL};
    C c = inst("plain", 1, argv[2], "", &cb, 0, 0);
    if (!c) { fprintf(stderr, "instantiate failed\n"); return 1; }
    setup(c, 1, tol, grid[0], 1, grid[n]);
    for (int a = 7; a < argc; a++) {
        char kind = argv[a][0];
        char *p = argv[a] + 2;
        unsigned vr = strtoul(p, &p, 10);
        if (kind == 'o') { out_vr[n_out++] = vr; continue; }
        if (kind == 'r') { double v = atof(p + 1); set_real(c, &vr, 1, &v); }
        else { int v = atoi(p + 1); set_int(c, &vr, 1, &v); }
    }
    enter(c);
    set_real(c, &vr_ag, 1, &acc[0]);
    if (exit_(c) > 1) { fprintf(stderr, "initialisation failed\n"); return 1; }
    double *rows = malloc((n + 1) * n_out * sizeof(double));
    size_t rows_n = 0;
    get_real(c, out_vr, n_out, rows);
    rows_n = 1;
    const int order = 1;
    for (size_t k = 0; k < n; k++) {
        set_real(c, &vr_ag, 1, &acc[k]);
        set_der(c, &vr_ag, 1, &order, &slope[k]);
        int s = do_step(c, grid[k], grid[k + 1] - grid[k], 1);
        if (s > 1) { /* overturned (discard: the outputs at the last successful time) or failed */
            if (s == 2 && get_real(c, out_vr, n_out, rows + rows_n * n_out) <= 1) rows_n++;
            break;
        }
        get_real(c, out_vr, n_out, rows + rows_n * n_out);
        rows_n++;
    }
    terminate(c);
    free_(c);
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t1);
    double sum = 0;
    for (size_t i = 0; i < rows_n * n_out; i++) sum += rows[i];
    printf("%.9f %zu %.17g\n", (t1.tv_sec - t0.tv_sec) + 1e-9 * (t1.tv_nsec - t0.tv_nsec), rows_n, sum);
    return 0;
}
