/* A plain C host for RockingBlock's binary through its FMI 3.0 functions,
 * for Windows (LoadLibrary) and POSIX (dlopen): rigid free rocking from
 * theta0 at rest, no ground motion, printed as the bit patterns of the
 * doubles so that two platforms can be compared bit for bit
 * (fmpy-tests/test_platforms.py builds it with mingw-w64 for the win64 DLL,
 * run under wine, and with the system compiler for linux64).
 *
 * Usage: free_rocking3 LIBRARY MODE TOKEN RESOURCE_PATH TOL H STEPS VR_INTERFACE RIGID VR_THETA THETA0 VR_OMEGA
 * MODE "cs": co-simulation with event mode and early return, steps of H to
 *   the communication points k H; prints "step k theta omega" at each and
 *   "event t theta omega" at each early return (then event mode, step mode).
 * MODE "me": Model Exchange, explicit Euler steps of H on the continuous
 *   states, event mode where an event indicator changes sign or
 *   fmi3CompletedIntegratorStep asks for it; prints "me k t x1 ... xn" after
 *   each step and "event t" at each event.
 * TOL, H and THETA0 are the 16 hex digits of an IEEE 754 double. On failure
 * a message on stderr and exit status 1 (an FMI call) or 2 (loading).
 *
 * The FMI 3.0 types below are written from the standard's function
 * signatures; the loading is fmi2_host.h's. */
#include <inttypes.h>
#include <stdbool.h>

#include "fmi2_host.h"

typedef void *fmi3Instance;
typedef unsigned int fmi3ValueReference;
typedef int fmi3Status; /* fmi3OK = 0, Warning, Discard, Error, Fatal */
typedef void (*LogFn)(void *, fmi3Status, const char *, const char *);
typedef fmi3Instance (*InstantiateCsFn)(const char *, const char *, const char *, bool, bool, bool, bool,
                                       const fmi3ValueReference *, size_t, void *, LogFn, void *);
typedef fmi3Instance (*InstantiateMeFn)(const char *, const char *, const char *, bool, bool, void *, LogFn);
typedef fmi3Status (*EnterInitFn)(fmi3Instance, bool, double, double, bool, double);
typedef fmi3Status (*InstanceFn)(fmi3Instance);
typedef void (*FreeFn)(fmi3Instance);
typedef fmi3Status (*SetInt64Fn)(fmi3Instance, const fmi3ValueReference *, size_t, const int64_t *, size_t);
typedef fmi3Status (*Float64sFn)(fmi3Instance, const fmi3ValueReference *, size_t, double *, size_t);
typedef fmi3Status (*DoStepFn)(fmi3Instance, double, double, bool, bool *, bool *, bool *, double *);
typedef fmi3Status (*UpdateFn)(fmi3Instance, bool *, bool *, bool *, bool *, bool *, double *);
typedef fmi3Status (*SetTimeFn)(fmi3Instance, double);
typedef fmi3Status (*ArrayFn)(fmi3Instance, double *, size_t);
typedef fmi3Status (*CountFn)(fmi3Instance, size_t *);
typedef fmi3Status (*CompletedFn)(fmi3Instance, bool, bool *, bool *);

static void log3(void *env, fmi3Status status, const char *category, const char *message) {
    (void)env;
    fprintf(stderr, "status %d, %s: %s\n", status, category, message);
}

static void check(fmi3Status status, const char *call) {
    if (status != 0) {
        fprintf(stderr, "%s returned status %d\n", call, status);
        exit(1);
    }
}

static library_t library;
#define FN(type, name) ((type)symbol(library, name))

/* Event mode until the discrete states settle; false at terminateSimulation. */
static bool update(fmi3Instance c) {
    bool need = true, terminate = false, nominals, values, defined;
    double next;
    while (need) {
        check(FN(UpdateFn, "fmi3UpdateDiscreteStates")(c, &need, &terminate, &nominals, &values, &defined, &next),
              "fmi3UpdateDiscreteStates");
        if (terminate) {
            return false;
        }
    }
    return true;
}

static void co_simulation(fmi3Instance c, double h, long steps, const fmi3ValueReference *vrs) {
    double x[2], t = 0.0;
    check(FN(InstanceFn, "fmi3EnterStepMode")(c), "fmi3EnterStepMode");
    for (long k = 0; k <= steps; k++) {
        /* communication points t_k = k h; early returns in between */
        double end = (double)k * h;
        while (t < end) {
            bool event, terminate, early;
            double last;
            check(FN(DoStepFn, "fmi3DoStep")(c, t, end - t, true, &event, &terminate, &early, &last), "fmi3DoStep");
            if (terminate) {
                return;
            }
            t = early ? last : end;
            if (early) {
                check(FN(Float64sFn, "fmi3GetFloat64")(c, vrs, 2, x, 2), "fmi3GetFloat64");
                printf("event %016" PRIx64 " %016" PRIx64 " %016" PRIx64 "\n", bits_of(t), bits_of(x[0]),
                       bits_of(x[1]));
            }
            if (event) {
                check(FN(InstanceFn, "fmi3EnterEventMode")(c), "fmi3EnterEventMode");
                if (!update(c)) {
                    return;
                }
                check(FN(InstanceFn, "fmi3EnterStepMode")(c), "fmi3EnterStepMode");
            }
        }
        check(FN(Float64sFn, "fmi3GetFloat64")(c, vrs, 2, x, 2), "fmi3GetFloat64");
        printf("step %ld %016" PRIx64 " %016" PRIx64 "\n", k, bits_of(x[0]), bits_of(x[1]));
    }
}

/* Event mode at t; false when the run ends there. */
static bool event_at(fmi3Instance c, double t) {
    printf("event %016" PRIx64 "\n", bits_of(t));
    check(FN(InstanceFn, "fmi3EnterEventMode")(c), "fmi3EnterEventMode");
    if (!update(c)) {
        return false;
    }
    check(FN(InstanceFn, "fmi3EnterContinuousTimeMode")(c), "fmi3EnterContinuousTimeMode");
    return true;
}

static void model_exchange(fmi3Instance c, double h, long steps) {
    size_t nx, nz;
    check(FN(CountFn, "fmi3GetNumberOfContinuousStates")(c, &nx), "fmi3GetNumberOfContinuousStates");
    check(FN(CountFn, "fmi3GetNumberOfEventIndicators")(c, &nz), "fmi3GetNumberOfEventIndicators");
    double *x = calloc(nx, sizeof *x), *dx = calloc(nx, sizeof *dx);
    double *z = calloc(nz, sizeof *z), *z_new = calloc(nz, sizeof *z_new);
    check(FN(InstanceFn, "fmi3EnterContinuousTimeMode")(c), "fmi3EnterContinuousTimeMode");
    check(FN(ArrayFn, "fmi3GetEventIndicators")(c, z, nz), "fmi3GetEventIndicators");
    for (long k = 1; k <= steps; k++) {
        double t = (double)k * h;
        check(FN(ArrayFn, "fmi3GetContinuousStates")(c, x, nx), "fmi3GetContinuousStates");
        check(FN(ArrayFn, "fmi3GetContinuousStateDerivatives")(c, dx, nx), "fmi3GetContinuousStateDerivatives");
        for (size_t i = 0; i < nx; i++) {
            x[i] += h * dx[i];
        }
        check(FN(SetTimeFn, "fmi3SetTime")(c, t), "fmi3SetTime");
        check(FN(ArrayFn, "fmi3SetContinuousStates")(c, x, nx), "fmi3SetContinuousStates");
        check(FN(ArrayFn, "fmi3GetEventIndicators")(c, z_new, nz), "fmi3GetEventIndicators");
        bool crossed = false, enter = false, terminate = false;
        for (size_t i = 0; i < nz; i++) {
            crossed = crossed || (z[i] > 0.0) != (z_new[i] > 0.0);
        }
        check(FN(CompletedFn, "fmi3CompletedIntegratorStep")(c, true, &enter, &terminate),
              "fmi3CompletedIntegratorStep");
        if (terminate || ((crossed || enter) && !event_at(c, t))) {
            break;
        }
        check(FN(ArrayFn, "fmi3GetEventIndicators")(c, z, nz), "fmi3GetEventIndicators");
        check(FN(ArrayFn, "fmi3GetContinuousStates")(c, x, nx), "fmi3GetContinuousStates");
        printf("me %ld %016" PRIx64, k, bits_of(t));
        for (size_t i = 0; i < nx; i++) {
            printf(" %016" PRIx64, bits_of(x[i]));
        }
        printf("\n");
    }
    free(x), free(dx), free(z), free(z_new);
}

int main(int argc, char **argv) {
    if (argc != 13 || (strcmp(argv[2], "cs") && strcmp(argv[2], "me"))) {
        fprintf(stderr, "usage: %s LIBRARY cs|me TOKEN RESOURCE_PATH TOL H STEPS VR_INTERFACE RIGID "
                        "VR_THETA THETA0 VR_OMEGA\n", argv[0]);
        return 2;
    }
    bool me = !strcmp(argv[2], "me");
    const char *token = argv[3], *resources = argv[4];
    double tol = real_from_hex(argv[5]), h = real_from_hex(argv[6]);
    long steps = strtol(argv[7], NULL, 10);
    fmi3ValueReference vr_interface = (fmi3ValueReference)strtoul(argv[8], NULL, 10);
    int64_t rigid = strtol(argv[9], NULL, 10);
    fmi3ValueReference vrs[2] = {(fmi3ValueReference)strtoul(argv[10], NULL, 10),
                                 (fmi3ValueReference)strtoul(argv[12], NULL, 10)};
    double theta0 = real_from_hex(argv[11]);

    library = open_library(argv[1]);
    printf("version %s\n", FN(const char *(*)(void), "fmi3GetVersion")());
    fmi3Instance c = me ? FN(InstantiateMeFn, "fmi3InstantiateModelExchange")("free rocking", token, resources,
                                                                              false, false, NULL, log3)
                        : FN(InstantiateCsFn, "fmi3InstantiateCoSimulation")("free rocking", token, resources,
                                                                            false, false, true, true, NULL, 0,
                                                                            NULL, log3, NULL);
    if (!c) {
        fprintf(stderr, "fmi3Instantiate... returned NULL\n");
        return 1;
    }
    check(FN(SetInt64Fn, "fmi3SetInt64")(c, &vr_interface, 1, &rigid, 1), "fmi3SetInt64(interface)");
    check(FN(Float64sFn, "fmi3SetFloat64")(c, vrs, 1, &theta0, 1), "fmi3SetFloat64(theta)");
    check(FN(EnterInitFn, "fmi3EnterInitializationMode")(c, true, tol, 0.0, false, 0.0),
          "fmi3EnterInitializationMode");
    check(FN(InstanceFn, "fmi3ExitInitializationMode")(c), "fmi3ExitInitializationMode");
    if (update(c)) {
        if (me) {
            model_exchange(c, h, steps);
        } else {
            co_simulation(c, h, steps, vrs);
        }
    }
    check(FN(InstanceFn, "fmi3Terminate")(c), "fmi3Terminate");
    FN(FreeFn, "fmi3FreeInstance")(c);
    return 0;
}
