/* What the plain C hosts of this folder share (free_rocking.c, coupled.c):
 * the FMI 2.0 types they use, written from the standard's function
 * signatures (not copied from its headers), a logger that prints to stderr,
 * and loading a library and its functions on Windows (LoadLibrary) and POSIX
 * (dlopen); a library or function that cannot be loaded ends the program with
 * status 2 and the loader's error on stderr. */
#ifndef FMI2_HOST_H
#define FMI2_HOST_H

#include <stdarg.h>
#include <stdint.h>
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
enum { fmi2OK = 0, fmi2Warning = 1, fmi2Discard = 2 };
enum { fmi2CoSimulation = 1 };
enum { fmi2LastSuccessfulTime = 2 };

typedef struct {
    void (*logger)(fmi2ComponentEnvironment, fmi2String, fmi2Status, fmi2String, fmi2String, ...);
    void *(*allocateMemory)(size_t, size_t);
    void (*freeMemory)(void *);
    void (*stepFinished)(fmi2ComponentEnvironment, fmi2Status);
    fmi2ComponentEnvironment componentEnvironment;
} fmi2CallbackFunctions;

static inline void logger(fmi2ComponentEnvironment env, fmi2String name, fmi2Status status,
                          fmi2String category, fmi2String message, ...) {
    va_list args;
    (void)env;
    fprintf(stderr, "[%s] status %d, %s: ", name, status, category);
    va_start(args, message);
    vfprintf(stderr, message, args);
    va_end(args);
    fputc('\n', stderr);
}

static inline void *allocate(size_t n, size_t size) { return calloc(n, size); }

static inline library_t open_library(const char *path) {
#ifdef _WIN32
    library_t library = LoadLibraryA(path);
    if (!library) {
        fprintf(stderr, "LoadLibrary(%s) failed: error %lu\n", path, GetLastError());
        exit(2);
    }
#else
    library_t library = dlopen(path, RTLD_NOW | RTLD_LOCAL);
    if (!library) {
        fprintf(stderr, "dlopen(%s) failed: %s\n", path, dlerror());
        exit(2);
    }
#endif
    return library;
}

static inline void *symbol(library_t library, const char *name) {
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

/* A double from the 16 hex digits of its bits (C's strtod differs between C
 * runtimes in the last bit; bit patterns do not), and back. */
static inline double real_from_hex(const char *s) {
    uint64_t bits = strtoull(s, NULL, 16);
    double x;
    memcpy(&x, &bits, sizeof x);
    return x;
}

static inline uint64_t bits_of(double x) {
    uint64_t bits;
    memcpy(&bits, &x, sizeof bits);
    return bits;
}

#endif
