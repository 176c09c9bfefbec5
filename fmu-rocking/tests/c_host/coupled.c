/* A plain C host (POSIX, dlopen) that couples FMI 2.0 co-simulation FMUs
 * with a Jacobi master holding inputs constant over a communication step: the
 * project's third host of the block-on-frame system (docs/cosimulation-hosts.md),
 * written without fmpy or the container runtime. fmpy-tests/test_cosim_hosts.py
 * builds it with the system compiler and compares it with the Python master.
 *
 * Usage: coupled CONFIG GROUND
 * CONFIG: one directive a line ('#' starts a comment):
 *   fmu LIBRARY GUID RESOURCE_URI     an instance (numbered from 0 in order)
 *   step H STEPS                      communication step (s) and number of steps
 *   tolerance I TOL                   fmi2SetupExperiment's tolerance of instance I
 *   real I VR VALUE / integer I VR VALUE   a start value set before initialization
 *   link I VR J VR2 FACTOR            output VR of I times FACTOR feeds input VR2 of J
 *   ground I VR                       the input fed from GROUND
 *   out I VR                          a Real printed at every communication point
 * GROUND: one value a line, the ground acceleration at t_k = k H (held over the step).
 * Output: "t v1 v2 ..." (%.17g) at t_0 .. t_STEPS; if an instance returns
 * fmi2Discard (a body overturned) the line "discard I T" follows the last
 * point, the time from fmi2LastSuccessfulTime, and the run ends with status 0.
 * Any other failure: a message on stderr, status 1 (an FMI call) or 2 (usage,
 * files, loading).
 *
 * The FMI 2.0 types and the loading are in fmi2_host.h. */
#include "fmi2_host.h"

typedef struct {
    fmi2Component (*instantiate)(fmi2String, int, fmi2String, fmi2String, const fmi2CallbackFunctions *,
                                 fmi2Boolean, fmi2Boolean);
    fmi2Status (*setup)(fmi2Component, fmi2Boolean, fmi2Real, fmi2Real, fmi2Boolean, fmi2Real);
    fmi2Status (*enter_init)(fmi2Component);
    fmi2Status (*exit_init)(fmi2Component);
    fmi2Status (*terminate)(fmi2Component);
    void (*free_instance)(fmi2Component);
    fmi2Status (*set_integer)(fmi2Component, const fmi2ValueReference *, size_t, const fmi2Integer *);
    fmi2Status (*set_real)(fmi2Component, const fmi2ValueReference *, size_t, const fmi2Real *);
    fmi2Status (*get_real)(fmi2Component, const fmi2ValueReference *, size_t, fmi2Real *);
    fmi2Status (*do_step)(fmi2Component, fmi2Real, fmi2Real, fmi2Boolean);
    fmi2Status (*get_real_status)(fmi2Component, int, fmi2Real *);
    fmi2Component c;
    double tolerance;
    int has_tolerance;
} Instance;

typedef struct {
    int from, to;
    fmi2ValueReference out, in;
    double factor;
} Link;

enum { MAX = 64 };
static Instance inst[MAX];
static int n_inst;
static Link links[MAX];
static int n_links;
static int out_i[MAX];
static fmi2ValueReference out_vr[MAX];
static int n_out;

static void check(fmi2Status status, const char *call, int i) {
    if (status != fmi2OK && status != fmi2Warning) {
        fprintf(stderr, "%s of instance %d returned status %d\n", call, i, status);
        exit(1);
    }
}

static void load(int i, const char *path, const char *guid, const char *resources) {
    library_t lib = open_library(path);
    Instance *f = &inst[i];
    *(void **)&f->instantiate = symbol(lib, "fmi2Instantiate");
    *(void **)&f->setup = symbol(lib, "fmi2SetupExperiment");
    *(void **)&f->enter_init = symbol(lib, "fmi2EnterInitializationMode");
    *(void **)&f->exit_init = symbol(lib, "fmi2ExitInitializationMode");
    *(void **)&f->terminate = symbol(lib, "fmi2Terminate");
    *(void **)&f->free_instance = symbol(lib, "fmi2FreeInstance");
    *(void **)&f->set_integer = symbol(lib, "fmi2SetInteger");
    *(void **)&f->set_real = symbol(lib, "fmi2SetReal");
    *(void **)&f->get_real = symbol(lib, "fmi2GetReal");
    *(void **)&f->do_step = symbol(lib, "fmi2DoStep");
    *(void **)&f->get_real_status = symbol(lib, "fmi2GetRealStatus");
    static const fmi2CallbackFunctions callbacks = {logger, allocate, free, NULL, NULL};
    char name[32];
    snprintf(name, sizeof name, "instance %d", i);
    f->c = f->instantiate(name, fmi2CoSimulation, guid, resources, &callbacks, 0, 0);
    if (!f->c) {
        fprintf(stderr, "fmi2Instantiate of %s returned NULL\n", path);
        exit(1);
    }
}

static double get(int i, fmi2ValueReference vr) {
    fmi2Real x;
    check(inst[i].get_real(inst[i].c, &vr, 1, &x), "fmi2GetReal", i);
    return x;
}

static void set(int i, fmi2ValueReference vr, double x) {
    check(inst[i].set_real(inst[i].c, &vr, 1, &x), "fmi2SetReal", i);
}

static void print_point(double t) {
    printf("%.17g", t);
    for (int k = 0; k < n_out; k++) printf(" %.17g", get(out_i[k], out_vr[k]));
    putchar('\n');
}

int main(int argc, char **argv) {
    if (argc != 3) {
        fprintf(stderr, "usage: %s CONFIG GROUND\n", argv[0]);
        return 2;
    }
    FILE *cfg = fopen(argv[1], "r"), *gnd = fopen(argv[2], "r");
    if (!cfg || !gnd) {
        fprintf(stderr, "cannot open %s or %s\n", argv[1], argv[2]);
        return 2;
    }
    char line[4096], a[1024], b[1024], c[1024];
    double h = 0.0, x;
    long steps = 0;
    int ground_i = -1, i, j, initialized = 0;
    unsigned vr, vr2;
    fmi2ValueReference ground_vr = 0;
    while (fgets(line, sizeof line, cfg)) {
        if (line[0] == '#' || line[0] == '\n') continue;
        if (!initialized && strncmp(line, "fmu ", 4) != 0 && strncmp(line, "tolerance ", 10) != 0) {
            for (int k = 0; k < n_inst; k++)
                check(inst[k].setup(inst[k].c, inst[k].has_tolerance, inst[k].tolerance, 0.0, 0, 0.0),
                      "fmi2SetupExperiment", k);
            initialized = 1;
        }
        if (sscanf(line, "fmu %1023s %1023s %1023s", a, b, c) == 3 && n_inst < MAX) {
            load(n_inst++, a, b, c);
        } else if (sscanf(line, "tolerance %d %lf", &i, &x) == 2 && i >= 0 && i < n_inst) {
            inst[i].tolerance = x;
            inst[i].has_tolerance = 1;
        } else if (sscanf(line, "step %lf %ld", &h, &steps) == 2) {
        } else if (sscanf(line, "real %d %u %lf", &i, &vr, &x) == 3 && i >= 0 && i < n_inst) {
            set(i, vr, x);
        } else if (sscanf(line, "integer %d %u %lf", &i, &vr, &x) == 3 && i >= 0 && i < n_inst) {
            fmi2ValueReference r = vr;
            fmi2Integer v = (fmi2Integer)x;
            check(inst[i].set_integer(inst[i].c, &r, 1, &v), "fmi2SetInteger", i);
        } else if (sscanf(line, "link %d %u %d %u %lf", &i, &vr, &j, &vr2, &x) == 5 && n_links < MAX &&
                   i >= 0 && i < n_inst && j >= 0 && j < n_inst) {
            links[n_links++] = (Link){i, j, vr, vr2, x};
        } else if (sscanf(line, "ground %d %u", &i, &vr) == 2 && i >= 0 && i < n_inst) {
            ground_i = i;
            ground_vr = vr;
        } else if (sscanf(line, "out %d %u", &i, &vr) == 2 && n_out < MAX && i >= 0 && i < n_inst) {
            out_i[n_out] = i;
            out_vr[n_out++] = vr;
        } else {
            fprintf(stderr, "%s: cannot read the line: %s", argv[1], line);
            return 2;
        }
    }
    if (n_inst == 0 || h <= 0.0 || steps <= 0) {
        fprintf(stderr, "%s: needs at least one fmu and a step\n", argv[1]);
        return 2;
    }
    for (int k = 0; k < n_inst; k++) {
        check(inst[k].enter_init(inst[k].c), "fmi2EnterInitializationMode", k);
        check(inst[k].exit_init(inst[k].c), "fmi2ExitInitializationMode", k);
    }
    double values[MAX];
    for (long k = 0; k <= steps; k++) {
        double t = (double)k * h; /* communication points without drift */
        print_point(t);
        if (k == steps) break;
        /* Jacobi: every link's value from the outputs at t, then every input set */
        for (int l = 0; l < n_links; l++) values[l] = links[l].factor * get(links[l].from, links[l].out);
        for (int l = 0; l < n_links; l++) set(links[l].to, links[l].in, values[l]);
        if (ground_i >= 0) {
            if (fscanf(gnd, "%lf", &x) != 1) {
                fprintf(stderr, "%s: no ground value for step %ld\n", argv[2], k);
                return 2;
            }
            set(ground_i, ground_vr, x);
        }
        for (int m = 0; m < n_inst; m++) {
            fmi2Status s = inst[m].do_step(inst[m].c, t, h, 1);
            if (s == fmi2Discard) {
                fmi2Real last;
                check(inst[m].get_real_status(inst[m].c, fmi2LastSuccessfulTime, &last), "fmi2GetRealStatus",
                      m);
                printf("discard %d %.17g\n", m, last);
                return 0;
            }
            check(s, "fmi2DoStep", m);
        }
    }
    for (int k = 0; k < n_inst; k++) {
        check(inst[k].terminate(inst[k].c), "fmi2Terminate", k);
        inst[k].free_instance(inst[k].c);
    }
    return 0;
}
