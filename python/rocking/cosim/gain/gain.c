/* Gain.fmu: an FMI 2.0 co-simulation FMU whose outputs are its inputs times
 * constant factors, y[i] = k[i] u[i] (i = 1..N, N fixed when compiled with
 * -DGAIN_N=N, the factors' start values by -DGAIN_K={k1,...}). It stands for the LinearTransformation of an SSP connection in
 * hosts that copy connected values as they are (the fmu-manipulation-toolbox
 * container runtime): rocking/cosim/ssp.py compiles it with the system C
 * compiler and puts it between the two ends of such a connection.
 *
 * Value references: k[i] = i - 1, u[i] = N + i - 1, y[i] = 2N + i - 1. The
 * outputs depend directly on the inputs (read at any time, also before the
 * first step); a step changes nothing. The FMI 2.0 types are written here
 * from the standard's function signatures, not copied from its headers. */
#include <stdarg.h>
#include <stdlib.h>
#include <string.h>

#ifndef GAIN_N
#define GAIN_N 2
#endif
/* the start values of k[i], as in modelDescription.xml (an FMU starts from them) */
#ifndef GAIN_K
#define GAIN_K {-1.0, -1.0}
#endif
static const double start_k[GAIN_N] = GAIN_K;

#define EXPORT __attribute__((visibility("default")))

typedef void *fmi2Component;
typedef void *fmi2FMUstate;
typedef unsigned int fmi2ValueReference;
typedef double fmi2Real;
typedef int fmi2Integer;
typedef int fmi2Boolean;
typedef char fmi2Char;
typedef const char *fmi2String;
typedef char fmi2Byte;
typedef int fmi2Status;
enum { fmi2OK = 0, fmi2Warning, fmi2Discard, fmi2Error, fmi2Fatal };

typedef struct {
    void (*logger)(void *, fmi2String, fmi2Status, fmi2String, fmi2String, ...);
    void *(*allocateMemory)(size_t, size_t);
    void (*freeMemory)(void *);
    void (*stepFinished)(void *, fmi2Status);
    void *componentEnvironment;
} fmi2CallbackFunctions;

typedef struct {
    double k[GAIN_N], u[GAIN_N];
    double time;
} Gain;

EXPORT const char *fmi2GetTypesPlatform(void) { return "default"; }
EXPORT const char *fmi2GetVersion(void) { return "2.0"; }
EXPORT fmi2Status fmi2SetDebugLogging(fmi2Component c, fmi2Boolean on, size_t n, const fmi2String *cats) {
    (void)c, (void)on, (void)n, (void)cats;
    return fmi2OK;
}

EXPORT fmi2Component fmi2Instantiate(fmi2String name, int type, fmi2String guid, fmi2String resources,
                                     const fmi2CallbackFunctions *f, fmi2Boolean visible, fmi2Boolean log) {
    (void)name, (void)guid, (void)resources, (void)f, (void)visible, (void)log;
    if (type != 1) return NULL; /* co-simulation only */
    Gain *g = calloc(1, sizeof *g);
    if (g)
        for (int i = 0; i < GAIN_N; i++) g->k[i] = start_k[i];
    return g;
}

EXPORT void fmi2FreeInstance(fmi2Component c) { free(c); }

EXPORT fmi2Status fmi2SetupExperiment(fmi2Component c, fmi2Boolean tol_defined, fmi2Real tol, fmi2Real start,
                                      fmi2Boolean stop_defined, fmi2Real stop) {
    (void)tol_defined, (void)tol, (void)stop_defined, (void)stop;
    ((Gain *)c)->time = start;
    return fmi2OK;
}

static fmi2Status ok(fmi2Component c) { return c ? fmi2OK : fmi2Error; }
EXPORT fmi2Status fmi2EnterInitializationMode(fmi2Component c) { return ok(c); }
EXPORT fmi2Status fmi2ExitInitializationMode(fmi2Component c) { return ok(c); }
EXPORT fmi2Status fmi2Terminate(fmi2Component c) { return ok(c); }
EXPORT fmi2Status fmi2Reset(fmi2Component c) {
    Gain *g = c;
    for (int i = 0; i < GAIN_N; i++) g->k[i] = start_k[i], g->u[i] = 0.0;
    return fmi2OK;
}

EXPORT fmi2Status fmi2GetReal(fmi2Component c, const fmi2ValueReference vr[], size_t n, fmi2Real v[]) {
    Gain *g = c;
    for (size_t j = 0; j < n; j++) {
        unsigned r = vr[j];
        if (r < GAIN_N) v[j] = g->k[r];
        else if (r < 2 * GAIN_N) v[j] = g->u[r - GAIN_N];
        else if (r < 3 * GAIN_N) v[j] = g->k[r - 2 * GAIN_N] * g->u[r - 2 * GAIN_N];
        else return fmi2Error;
    }
    return fmi2OK;
}

EXPORT fmi2Status fmi2SetReal(fmi2Component c, const fmi2ValueReference vr[], size_t n, const fmi2Real v[]) {
    Gain *g = c;
    for (size_t j = 0; j < n; j++) {
        unsigned r = vr[j];
        if (r < GAIN_N) g->k[r] = v[j];
        else if (r < 2 * GAIN_N) g->u[r - GAIN_N] = v[j];
        else return fmi2Error;
    }
    return fmi2OK;
}

EXPORT fmi2Status fmi2DoStep(fmi2Component c, fmi2Real t, fmi2Real h, fmi2Boolean no_prior) {
    (void)no_prior;
    ((Gain *)c)->time = t + h;
    return fmi2OK;
}

EXPORT fmi2Status fmi2GetRealStatus(fmi2Component c, int kind, fmi2Real *v) {
    if (kind != 2) return fmi2Error; /* fmi2LastSuccessfulTime */
    *v = ((Gain *)c)->time;
    return fmi2OK;
}

EXPORT fmi2Status fmi2GetBooleanStatus(fmi2Component c, int kind, fmi2Boolean *v) {
    (void)c;
    if (kind != 3) return fmi2Error; /* fmi2Terminated */
    *v = 0;
    return fmi2OK;
}

/* Everything else: no integer, boolean or string variables, no states, no derivatives. */
#define REFUSE(name, ...) \
    EXPORT fmi2Status name(__VA_ARGS__) { return fmi2Error; }
REFUSE(fmi2GetInteger, fmi2Component c, const fmi2ValueReference vr[], size_t n, fmi2Integer v[])
REFUSE(fmi2SetInteger, fmi2Component c, const fmi2ValueReference vr[], size_t n, const fmi2Integer v[])
REFUSE(fmi2GetBoolean, fmi2Component c, const fmi2ValueReference vr[], size_t n, fmi2Boolean v[])
REFUSE(fmi2SetBoolean, fmi2Component c, const fmi2ValueReference vr[], size_t n, const fmi2Boolean v[])
REFUSE(fmi2GetString, fmi2Component c, const fmi2ValueReference vr[], size_t n, fmi2String v[])
REFUSE(fmi2SetString, fmi2Component c, const fmi2ValueReference vr[], size_t n, const fmi2String v[])
REFUSE(fmi2GetFMUstate, fmi2Component c, fmi2FMUstate *s)
REFUSE(fmi2SetFMUstate, fmi2Component c, fmi2FMUstate s)
REFUSE(fmi2FreeFMUstate, fmi2Component c, fmi2FMUstate *s)
REFUSE(fmi2SerializedFMUstateSize, fmi2Component c, fmi2FMUstate s, size_t *n)
REFUSE(fmi2SerializeFMUstate, fmi2Component c, fmi2FMUstate s, fmi2Byte b[], size_t n)
REFUSE(fmi2DeSerializeFMUstate, fmi2Component c, const fmi2Byte b[], size_t n, fmi2FMUstate *s)
REFUSE(fmi2GetDirectionalDerivative, fmi2Component c, const fmi2ValueReference a[], size_t na,
       const fmi2ValueReference b[], size_t nb, const fmi2Real dv[], fmi2Real d[])
REFUSE(fmi2SetRealInputDerivatives, fmi2Component c, const fmi2ValueReference vr[], size_t n,
       const fmi2Integer o[], const fmi2Real v[])
REFUSE(fmi2GetRealOutputDerivatives, fmi2Component c, const fmi2ValueReference vr[], size_t n,
       const fmi2Integer o[], fmi2Real v[])
REFUSE(fmi2CancelStep, fmi2Component c)
REFUSE(fmi2GetStatus, fmi2Component c, int kind, fmi2Status *v)
REFUSE(fmi2GetIntegerStatus, fmi2Component c, int kind, fmi2Integer *v)
REFUSE(fmi2GetStringStatus, fmi2Component c, int kind, fmi2String *v)
