/* A test-only stand-in for Windows' bcryptprimitives.dll exporting
 * ProcessPrng, for wine releases that lack it (wine 8: LoadLibrary of a
 * Rust DLL fails with error 126, ERROR_MOD_NOT_FOUND). Rust's standard
 * library calls ProcessPrng for the random keys of HashMap/HashSet; Windows 10
 * and later have it, so the shipped DLL is left as it is and this file is
 * only ever placed beside the test host (fmpy-tests/test_platforms.py).
 * The bytes come from RtlGenRandom (advapi32's SystemFunction036). */
#include <windows.h>

BOOLEAN WINAPI SystemFunction036(PVOID buffer, ULONG length);

__declspec(dllexport) BOOL WINAPI ProcessPrng(PBYTE data, SIZE_T length) {
    while (length > 0) {
        ULONG chunk = length > 0x40000000 ? 0x40000000 : (ULONG)length;
        if (!SystemFunction036(data, chunk)) {
            return FALSE;
        }
        data += chunk;
        length -= chunk;
    }
    return TRUE;
}
