/* A plain C host for RockingBlock.fmu's binary (FMI 2.0 co-simulation), for
 * Windows (LoadLibrary) and POSIX (dlopen): it loads the library given on the
 * command line, instantiates it, switches the interface to the rigid law,
 * releases the block from theta0 at rest with no ground motion, steps with
 * fmi2DoStep and prints theta and omega at every communication point as the
 * bit patterns of the doubles, so that two platforms can be compared bit for
 * bit. fmpy-tests/test_platforms.py builds it (mingw-w64 for win64, run under
 * wine; the system compiler for linux64) and checks the output against the
 * exact solution of rigid free rocking.
 *
 * Usage: free_rocking LIBRARY GUID RESOURCE_URI TOL H STEPS VR_INTERFACE RIGID VR_THETA THETA0 VR_OMEGA
 * TOL, H and THETA0 are the 16 hex digits of an IEEE 754 double (C's strtod
 * differs between C runtimes in the last bit; bit patterns do not).
 *
 * Output: "step k theta omega", theta and omega as 16 hex digits, k = 0..STEPS;
 * on failure a message on stderr and exit status 1 (the FMI call failed) or 2
 * (the library or a function could not be loaded; the loader's error code).
 *
 * The FMI 2.0 types are written here from the standard's function signatures
 * (only those used), not copied from its headers. */
#include <inttypes.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#ifdef _WIN32
#include <windows.h>
typedef HMODULE library_t;
#else
#include <dlfcn.h>
typedef void *library_t;
#endif

typedef void *fmi2Component;
typedef void *fmi2ComponentEnvironment;
typedef unsigned int fmi2ValueReference;
typedef double fmi2Real;
typedef int fmi2Integer;
typedef int fmi2Boolean;
typedef const char *fmi2String;
typedef int fmi2Status; /* fmi2OK = 0, Warning, Discard, Error, Fatal, Pending */
enum { fmi2OK = 0, fmi2Warning = 1 };
enum { fmi2CoSimulation = 1 };

typedef struct {
    void (*logger)(fmi2ComponentEnvironment, fmi2String, fmi2Status, fmi2String, fmi2String, ...);
    void *(*allocateMemory)(size_t, size_t);
    void (*freeMemory)(void *);
    void (*stepFinished)(fmi2ComponentEnvironment, fmi2Status);
    fmi2ComponentEnvironment componentEnvironment;
} fmi2CallbackFunctions;

typedef const char *(*GetVersionFn)(void);
typedef const char *(*GetTypesPlatformFn)(void);
typedef fmi2Component (*InstantiateFn)(fmi2String, int, fmi2String, fmi2String,
                                     const fmi2CallbackFunctions *, fmi2Boolean, fmi2Boolean);
typedef fmi2Status (*SetupExperimentFn)(fmi2Component, fmi2Boolean, fmi2Real, fmi2Real, fmi2Boolean,
                                      fmi2Real);
typedef fmi2Status (*ComponentOnlyFn)(fmi2Component);
typedef void (*FreeInstanceFn)(fmi2Component);
typedef fmi2Status (*SetIntegerFn)(fmi2Component, const fmi2ValueReference *, size_t,
                                 const fmi2Integer *);
typedef fmi2Status (*SetRealFn)(fmi2Component, const fmi2ValueReference *, size_t, const fmi2Real *);
typedef fmi2Status (*GetRealFn)(fmi2Component, const fmi2ValueReference *, size_t, fmi2Real *);
typedef fmi2Status (*DoStepFn)(fmi2Component, fmi2Real, fmi2Real, fmi2Boolean);

static void logger(fmi2ComponentEnvironment env, fmi2String name, fmi2Status status,
                   fmi2String category, fmi2String message, ...) {
    va_list args;
    (void)env;
    fprintf(stderr, "[%s] status %d, %s: ", name, status, category);
    va_start(args, message);
    vfprintf(stderr, message, args);
    va_end(args);
    fputc('\n', stderr);
}

static void *allocate(size_t n, size_t size) { return calloc(n, size); }

static library_t library;

static void *symbol(const char *name) {
#ifdef _WIN32
    void *f = (void *)GetProcAddress(library, name);
    if (!f) {
        fprintf(stderr, "GetProcAddress(%s) failed: error %lu\n", name, GetLastError());
        exit(2);
    }
#else
    void *f = dlsym(library, name);
    if (!f) {
        fprintf(stderr, "dlsym(%s) failed: %s\n", name, dlerror());
        exit(2);
    }
#endif
    return f;
}

static double real_from_hex(const char *s) {
    uint64_t bits = strtoull(s, NULL, 16);
    double x;
    memcpy(&x, &bits, sizeof x);
    return x;
}

static uint64_t bits_of(double x) {
    uint64_t bits;
    memcpy(&bits, &x, sizeof bits);
    return bits;
}

static void check(fmi2Status status, const char *call) {
    if (status != fmi2OK) {
        fprintf(stderr, "%s returned status %d\n", call, status);
        exit(1);
    }
}

int main(int argc, char **argv) {
    if (argc != 12) {
        fprintf(stderr, "usage: %s LIBRARY GUID RESOURCE_URI TOL H STEPS VR_INTERFACE RIGID "
                        "VR_THETA THETA0 VR_OMEGA\n", argv[0]);
        return 2;
    }
    const char *path = argv[1], *guid = argv[2], *resources = argv[3];
    double tol = real_from_hex(argv[4]), h = real_from_hex(argv[5]);
    long steps = strtol(argv[6], NULL, 10);
    fmi2ValueReference vr_interface = (fmi2ValueReference)strtoul(argv[7], NULL, 10);
    fmi2Integer rigid = (fmi2Integer)strtol(argv[8], NULL, 10);
    fmi2ValueReference vr_theta = (fmi2ValueReference)strtoul(argv[9], NULL, 10);
    double theta0 = real_from_hex(argv[10]);
    fmi2ValueReference vr_omega = (fmi2ValueReference)strtoul(argv[11], NULL, 10);

#ifdef _WIN32
    library = LoadLibraryA(path);
    if (!library) {
        fprintf(stderr, "LoadLibrary(%s) failed: error %lu\n", path, GetLastError());
        return 2;
    }
#else
    library = dlopen(path, RTLD_NOW | RTLD_LOCAL);
    if (!library) {
        fprintf(stderr, "dlopen(%s) failed: %s\n", path, dlerror());
        return 2;
    }
#endif
    GetVersionFn get_version = (GetVersionFn)symbol("fmi2GetVersion");
    GetTypesPlatformFn get_types_platform = (GetTypesPlatformFn)symbol("fmi2GetTypesPlatform");
    InstantiateFn instantiate = (InstantiateFn)symbol("fmi2Instantiate");
    SetupExperimentFn setup = (SetupExperimentFn)symbol("fmi2SetupExperiment");
    ComponentOnlyFn enter_init = (ComponentOnlyFn)symbol("fmi2EnterInitializationMode");
    ComponentOnlyFn exit_init = (ComponentOnlyFn)symbol("fmi2ExitInitializationMode");
    ComponentOnlyFn terminate = (ComponentOnlyFn)symbol("fmi2Terminate");
    FreeInstanceFn free_instance = (FreeInstanceFn)symbol("fmi2FreeInstance");
    SetIntegerFn set_integer = (SetIntegerFn)symbol("fmi2SetInteger");
    SetRealFn set_real = (SetRealFn)symbol("fmi2SetReal");
    GetRealFn get_real = (GetRealFn)symbol("fmi2GetReal");
    DoStepFn do_step = (DoStepFn)symbol("fmi2DoStep");
    printf("version %s, types platform %s\n", get_version(), get_types_platform());

    fmi2CallbackFunctions callbacks = {logger, allocate, free, NULL, NULL};
    fmi2Component c = instantiate("free rocking", fmi2CoSimulation, guid, resources, &callbacks, 0, 0);
    if (!c) {
        fprintf(stderr, "fmi2Instantiate returned NULL\n");
        return 1;
    }
    check(setup(c, 1, tol, 0.0, 0, 0.0), "fmi2SetupExperiment");
    check(set_integer(c, &vr_interface, 1, &rigid), "fmi2SetInteger(interface)");
    check(set_real(c, &vr_theta, 1, &theta0), "fmi2SetReal(theta)");
    check(enter_init(c), "fmi2EnterInitializationMode");
    check(exit_init(c), "fmi2ExitInitializationMode");
    fmi2ValueReference vrs[2] = {vr_theta, vr_omega};
    fmi2Real x[2];
    for (long k = 0; k <= steps; k++) {
        if (k > 0) {
            /* communication points t_k = k h, without drift */
            check(do_step(c, (double)(k - 1) * h, h, 1), "fmi2DoStep");
        }
        check(get_real(c, vrs, 2, x), "fmi2GetReal");
        printf("step %ld %016" PRIx64 " %016" PRIx64 "\n", k, bits_of(x[0]), bits_of(x[1]));
    }
    check(terminate(c), "fmi2Terminate");
    free_instance(c);
    return 0;
}
