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
 * The FMI 2.0 types and the loading are in fmi2_host.h. */
#include <inttypes.h>

#include "fmi2_host.h"

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

    library_t library = open_library(path);
    GetVersionFn get_version = (GetVersionFn)symbol(library, "fmi2GetVersion");
    GetTypesPlatformFn get_types_platform = (GetTypesPlatformFn)symbol(library, "fmi2GetTypesPlatform");
    InstantiateFn instantiate = (InstantiateFn)symbol(library, "fmi2Instantiate");
    SetupExperimentFn setup = (SetupExperimentFn)symbol(library, "fmi2SetupExperiment");
    ComponentOnlyFn enter_init = (ComponentOnlyFn)symbol(library, "fmi2EnterInitializationMode");
    ComponentOnlyFn exit_init = (ComponentOnlyFn)symbol(library, "fmi2ExitInitializationMode");
    ComponentOnlyFn terminate = (ComponentOnlyFn)symbol(library, "fmi2Terminate");
    FreeInstanceFn free_instance = (FreeInstanceFn)symbol(library, "fmi2FreeInstance");
    SetIntegerFn set_integer = (SetIntegerFn)symbol(library, "fmi2SetInteger");
    SetRealFn set_real = (SetRealFn)symbol(library, "fmi2SetReal");
    GetRealFn get_real = (GetRealFn)symbol(library, "fmi2GetReal");
    DoStepFn do_step = (DoStepFn)symbol(library, "fmi2DoStep");
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
