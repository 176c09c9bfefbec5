"""The FMU's platforms: `binaries/linux64` needs no glibc newer than 2.17 and
`binaries/win64` loads and runs on Windows (here: under wine).

A plain C host (`fmu-rocking/tests/c_host/free_rocking.c`, no fmpy) loads the
binary from the extracted FMU, releases the rigid block from 0.8 alpha with no
ground motion and prints theta and omega at every communication point. Built
with mingw-w64 and run under wine against the win64 DLL, and built with the
system compiler against the linux64 library, its output is checked against the
exact solution of rigid free rocking (Housner: energy conservation between
impacts, elliptic integrals for the times, the restitution eta at impacts),
and the two platforms against each other bit for bit.

A machine without the Windows toolchain (the Rust target
x86_64-pc-windows-gnu, mingw-w64) or wine reports these tests as skipped with
the reason; `tools/cross-deps.sh` installs them.
"""

import math
import os
import re
import shutil
import struct
import subprocess
import zipfile

import numpy as np
import pytest
from scipy.integrate import quad
from scipy.special import elliprf

from conftest import ROOT, TARGET

C_HOST = ROOT / "fmu-rocking" / "tests" / "c_host"
GLIBC_BASELINE = (2, 17)
WIN64_TARGET = "x86_64-pc-windows-gnu"
MINGW_GCC = "x86_64-w64-mingw32-gcc"
MINGW_OBJDUMP = "x86_64-w64-mingw32-objdump"
# Windows' own DLLs: the win64 binary may import nothing else (no mingw
# runtime DLL, which a Windows user would not have)
WINDOWS_SYSTEM_DLLS = {
    "kernel32.dll",
    "ntdll.dll",
    "msvcrt.dll",
    "userenv.dll",
    "ws2_32.dll",
    "bcryptprimitives.dll",
    "api-ms-win-core-synch-l1-2-0.dll",
}
RTOL = 1e-9  # the FMU's tolerance (fmi2SetupExperiment) and the bound on the errors
N_IMPACTS = 10
THETA0_OVER_ALPHA = 0.8
ERROR_MOD_NOT_FOUND = 126


# ---------------------------------------------------------------- exact solution


class Housner:
    """Rigid free rocking, exactly: a block (p² = W R0 / IO, slenderness
    alpha) conserves e = omega²/2 + V(|theta|)/IO between impacts,
    V(phi)/IO = p² (cos(alpha - phi) - cos(alpha)), and each impact (theta
    through zero) multiplies omega by eta. The time from a peak Phi to psi is
    F(varphi | m) / p with s = sin((alpha - psi)/2), k = sin((alpha - Phi)/2),
    m = 1 - k², sin²(varphi) = (s² - k²) / (s² (1 - k²)) (Byrd & Friedman
    217.00), F evaluated with Carlson's R_F (scipy.special.elliprf). Energy
    conservation reads s² - k² = omega² / (4 p²): everything follows from a
    sampled state (theta, omega) without cancellation, even next to a peak.
    The same construction as fmi-import/src/lib.rs (the `fmi` crate host's
    reference), written again here with scipy's R_F and checked against a
    direct quadrature below."""

    def __init__(self, p2, alpha, eta):
        self.p2, self.alpha, self.eta = p2, alpha, eta

    def potential(self, phi):
        return 2.0 * self.p2 * math.sin(0.5 * phi) * math.sin(self.alpha - 0.5 * phi)

    def _s2_d_k2(self, theta, omega):
        s2 = math.sin(0.5 * (self.alpha - abs(theta))) ** 2
        d = omega * omega / (4.0 * self.p2)
        k2 = s2 - d
        assert k2 > 0.0, f"({theta}, {omega}) reaches the overturning rotation"
        return s2, d, k2

    def amplitude(self, theta, omega):
        """The peak |theta| of the half-cycle through (theta, omega)."""
        _, d, k2 = self._s2_d_k2(theta, omega)
        # Phi = alpha - 2 asin(k) cancels when Phi << alpha: Newton on the rise
        # delta = Phi - |theta|, sin(delta/2) sin(c - delta/2) = d, c = alpha - |theta|
        c = self.alpha - abs(theta)
        delta = c - 2.0 * math.asin(math.sqrt(k2))
        for _ in range(3):
            f = math.sin(0.5 * delta) * math.sin(c - 0.5 * delta) - d
            delta -= f / (0.5 * math.sin(c - delta))
        return abs(theta) + delta

    def time_from_peak(self, theta, omega):
        s2, d, k2 = self._s2_d_k2(theta, omega)
        sin2 = d / (s2 * (1.0 - k2))
        cos2 = k2 * (1.0 - s2) / (s2 * (1.0 - k2))
        return math.sqrt(sin2) * float(elliprf(cos2, k2 / s2, 1.0)) / math.sqrt(self.p2)

    def fall_time(self, theta, omega):
        omega0 = math.sqrt(omega * omega + 2.0 * self.potential(abs(theta)))
        return self.time_from_peak(0.0, omega0)

    def time_to_impact(self, theta, omega):
        fall, from_peak = self.fall_time(theta, omega), self.time_from_peak(theta, omega)
        return fall - from_peak if theta * omega < 0.0 else fall + from_peak

    def time_since_impact(self, theta, omega):
        return self.time_to_impact(theta, -omega)  # symmetric in time about each peak

    def impacts(self, theta0, n):
        """Released from theta0 at rest: (time, amplitude after) of the first n impacts."""
        t = self.fall_time(theta0, 0.0)
        omega = math.sqrt(2.0 * self.potential(theta0))
        out = []
        for _ in range(n):
            omega *= self.eta
            out.append((t, self.amplitude(0.0, omega)))
            t += 2.0 * self.fall_time(0.0, omega)
        return out


def _block(b, h, g):
    """The solid prism B x H: tan(alpha) = B/H, R0 = hypot(B, H)/2,
    IO = (4/3) m R0², so p² = W R0 / IO = 3 g / (4 R0); Housner's
    eta = 1 - 1.5 sin²(alpha)."""
    alpha = math.atan2(b, h)
    return Housner(0.75 * g / (0.5 * math.hypot(b, h)), alpha, 1.0 - 1.5 * math.sin(alpha) ** 2)


def test_the_exact_times_match_a_direct_quadrature():
    hb = _block(0.5, 2.5, 9.81)
    for frac in [1e-3, 0.1, 0.5, 0.8, 0.99]:
        peak = frac * hb.alpha
        for psi_frac in [0.0, 0.3, 0.9]:
            psi = psi_frac * peak
            # omega² = 4 p² sin((Phi - psi)/2) sin(alpha - (Phi + psi)/2)
            omega = math.sqrt(4 * hb.p2 * math.sin(0.5 * (peak - psi)) * math.sin(hb.alpha - 0.5 * (peak + psi)))
            assert hb.amplitude(psi, omega) == pytest.approx(peak, rel=1e-13)
            # dpsi / |omega| from psi to the peak; psi = Phi - d u² removes the turning point's singularity
            d = peak - psi

            def f(u):
                x = d * u * u
                if u == 0.0:
                    return 2.0 * d / math.sqrt(2.0 * hb.p2 * d * math.sin(hb.alpha - peak))
                return 2.0 * d * u / math.sqrt(4.0 * hb.p2 * math.sin(0.5 * x) * math.sin(hb.alpha - peak + 0.5 * x))

            direct, _ = quad(f, 0.0, 1.0, epsabs=0.0, epsrel=1e-13, limit=200)
            assert hb.time_from_peak(psi, omega) == pytest.approx(direct, rel=1e-12)


# ---------------------------------------------------------------- the archive


def _windows_toolchain_missing():
    """Why this machine cannot build the win64 binary, or None."""
    try:
        sysroot = subprocess.run(["rustc", "--print", "sysroot"], capture_output=True, text=True, check=True)
    except (OSError, subprocess.CalledProcessError) as e:
        return f"rustc --print sysroot failed: {e}"
    if not os.path.isdir(os.path.join(sysroot.stdout.strip(), "lib", "rustlib", WIN64_TARGET)):
        return f"the Rust target {WIN64_TARGET} is not installed (rustup target add {WIN64_TARGET})"
    if shutil.which(MINGW_GCC) is None:
        return f"{MINGW_GCC} not found (Debian: gcc-mingw-w64-x86-64)"
    return None


@pytest.fixture(scope="module")
def win64_dll(unzipped):
    """The win64 binary of the extracted FMU; skipped with the reason when
    the machine cannot build it, an error when it could and the FMU lacks it."""
    path = os.path.join(unzipped, "binaries", "win64", "RockingBlock.dll")
    if not os.path.isfile(path):
        why = _windows_toolchain_missing()
        if why:
            pytest.skip(f"no win64 binary: {why}; tools/cross-deps.sh installs the toolchain")
        pytest.fail("the Windows toolchain is installed but the FMU has no binaries/win64: run `cargo xtask fmu`")
    return path


@pytest.fixture(scope="module")
def linux64_so(unzipped):
    path = os.path.join(unzipped, "binaries", "linux64", "RockingBlock.so")
    assert os.path.isfile(path), "the FMU has no binaries/linux64/RockingBlock.so"
    return path


def test_the_archive_holds_only_known_platforms(fmu_path):
    names = zipfile.ZipFile(fmu_path).namelist()
    binaries = sorted(n for n in names if n.startswith("binaries/"))
    assert set(binaries) <= {"binaries/linux64/RockingBlock.so", "binaries/win64/RockingBlock.dll"}, binaries
    assert "binaries/linux64/RockingBlock.so" in binaries


def test_linux64_needs_no_glibc_above_2_17(linux64_so):
    if shutil.which("readelf") is None:
        pytest.skip("readelf (binutils) not found")
    out = subprocess.run(
        ["readelf", "--version-info", "--wide", linux64_so], capture_output=True, text=True, check=True
    ).stdout
    # the version needs (.gnu.version_r): "0x0010:   Name: GLIBC_2.14  Flags: none  Version: 4"
    needs = out[out.index("Version needs section") :] if "Version needs section" in out else ""
    names = set(re.findall(r"Name: (GLIBC_[^\s]+)", needs))
    assert names, f"no GLIBC version needed by {linux64_so}?\n{out}"
    versions = []
    for name in names:
        m = re.fullmatch(r"GLIBC_(\d+)\.(\d+)(?:\.(\d+))?", name)
        assert m, f"{name}: not a public glibc version"
        versions.append(tuple(int(x) for x in m.groups(default="0")))
    newest = max(versions)
    print("linux64 needs", ", ".join(sorted(names, key=lambda n: [int(x) for x in n[6:].split(".")])))
    assert newest[:2] <= GLIBC_BASELINE, (
        f"binaries/linux64 needs GLIBC_{'.'.join(map(str, newest))}, above the baseline "
        f"{GLIBC_BASELINE[0]}.{GLIBC_BASELINE[1]}: it was not built by cargo-zigbuild (tools/cross-deps.sh)"
    )


def test_win64_imports_only_windows_system_dlls(win64_dll):
    out = subprocess.run([MINGW_OBJDUMP, "-p", win64_dll], capture_output=True, text=True, check=True).stdout
    dlls = {d.lower() for d in re.findall(r"DLL Name: (\S+)", out)}
    assert "kernel32.dll" in dlls, out
    assert dlls <= WINDOWS_SYSTEM_DLLS, f"imports beyond Windows' own DLLs: {sorted(dlls - WINDOWS_SYSTEM_DLLS)}"
    assert "fmi2DoStep" in out  # the export table


def test_win64_binary_carries_no_coff_symbol_table(win64_dll):
    """Stripped (xtask): the exports are the export table; the COFF header's
    PointerToSymbolTable and NumberOfSymbols are 0."""
    data = open(win64_dll, "rb").read()
    pe = struct.unpack_from("<I", data, 0x3C)[0]
    assert data[pe:pe + 4] == b"PE\0\0"
    assert data[pe + 12:pe + 20] == bytes(8), "a COFF symbol table"
    out = subprocess.run([MINGW_OBJDUMP, "-p", win64_dll], capture_output=True, text=True, check=True).stdout
    assert "fmi2GetRealOutputDerivatives" in out and "fmi3DoStep" in out


def test_win64_binary_carries_no_link_time(win64_dll):
    """The archive is reproducible: GNU ld's PE time stamp is off (xtask)."""
    out = subprocess.run([MINGW_OBJDUMP, "-p", win64_dll], capture_output=True, text=True, check=True).stdout
    stamp = re.search(r"^Time/Date\s+(.*)$", out, re.M)
    assert stamp and stamp.group(1).strip() == "Thu Jan  1 00:00:00 1970", stamp and stamp.group(0)


def test_win64_crosscheck_artefacts_pass_the_vendor_repository_validation(win64_dll):
    from fmpy.cross_check.validate_vendor_repo import validate_test_fmu

    base = TARGET / "cross-check" / "fmus" / "2.0" / "cs" / "win64" / "RockingBlock"
    dirs = sorted(base.glob("*/RockingBlock")) if base.is_dir() else []
    if not dirs:
        pytest.skip(f"no cross-check artefacts under {base}: run `cargo xtask crosscheck`")
    assert validate_test_fmu(str(dirs[-1])) == []


# ---------------------------------------------------------------- the C host


def _hex(x):
    return "%016x" % struct.unpack("<Q", struct.pack("<d", x))[0]


def _from_hex(s):
    return struct.unpack("<d", struct.pack("<Q", int(s, 16)))[0]


@pytest.fixture(scope="module")
def case(model_description):
    """The host's arguments (all from the model description) and the exact solution."""
    md = model_description
    var = {v.name: v for v in md.modelVariables}
    rigid = {i.name: i.value for i in var["interface"].declaredType.items}["rigid"]
    hb = _block(*(float(var[n].start) for n in ("B", "H", "g")))
    theta0 = THETA0_OVER_ALPHA * hb.alpha
    h = float(md.defaultExperiment.stepSize)
    exact = hb.impacts(theta0, N_IMPACTS)
    steps = math.ceil(exact[-1][0] / h) + 2
    args = [
        md.guid,
        None,  # the resource URI, per platform
        _hex(RTOL),
        _hex(h),
        str(steps),
        str(var["interface"].valueReference),
        str(rigid),
        str(var["theta"].valueReference),
        _hex(theta0),
        str(var["omega"].valueReference),
    ]
    return {"args": args, "hb": hb, "theta0": theta0, "h": h, "exact": exact}


def _parse(stdout):
    rows = [line.split() for line in stdout.splitlines() if line.startswith("step ")]
    assert rows, stdout
    assert [int(r[1]) for r in rows] == list(range(len(rows)))
    theta_bits = np.array([int(r[2], 16) for r in rows], dtype=np.uint64)
    omega_bits = np.array([int(r[3], 16) for r in rows], dtype=np.uint64)
    return theta_bits, omega_bits


def _check_against_exact(theta_bits, omega_bits, case, label):
    """Locates each impact from the samples (theta changes sign within a step)
    and reconstructs its time from the state before and after it with the
    exact solution, so that what is measured is the FMU's error in the sampled
    states, not the communication step's; likewise the amplitude of every
    sample. Returns the worst relative errors."""
    hb, h, exact = case["hb"], case["h"], case["exact"]
    theta = theta_bits.view(np.float64)
    omega = omega_bits.view(np.float64)
    assert theta[0] == case["theta0"] and omega[0] == 0.0
    worst = {"time before": 0.0, "time after": 0.0, "amplitude": 0.0, "between": 0.0}
    amplitude, found = case["theta0"], 0
    for k in range(1, len(theta)):
        if found == len(exact):
            break
        t, t_next = (k - 1) * h, k * h
        if theta[k - 1] * theta[k] < 0.0:
            te, phi = exact[found]
            found += 1
            assert t < te <= t_next, f"{label}: impact {found} in ({t}, {t_next}], exact time {te}"
            t_before = t + hb.time_to_impact(theta[k - 1], omega[k - 1])
            t_after = t_next - hb.time_since_impact(theta[k], omega[k])
            worst["time before"] = max(worst["time before"], abs(t_before - te) / te)
            worst["time after"] = max(worst["time after"], abs(t_after - te) / te)
            worst["amplitude"] = max(worst["amplitude"], abs(hb.amplitude(theta[k], omega[k]) - phi) / phi)
            amplitude = phi
        else:
            e = abs(hb.amplitude(theta[k], omega[k]) - amplitude) / amplitude
            worst["between"] = max(worst["between"], e)
    assert found == len(exact), f"{label}: {found} impacts, expected {len(exact)}"
    print(label, "worst relative errors against the exact solution:", {k: f"{v:.1e}" for k, v in worst.items()})
    for what, e in worst.items():
        assert e < RTOL, f"{label}: {what} off by {e:.1e} > {RTOL:.0e}"
    return worst


def _run(cmd, env=None):
    return subprocess.run(cmd, capture_output=True, text=True, env=env, timeout=600)


@pytest.fixture(scope="module")
def linux64_result(linux64_so, case, tmp_path_factory, unzipped):
    if shutil.which("cc") is None:
        pytest.skip("no C compiler (cc) on this machine")
    exe = tmp_path_factory.mktemp("c_host_linux64") / "free_rocking"
    subprocess.run(
        ["cc", "-O2", "-std=c99", "-Wall", "-Wextra", "-Werror", "-o", str(exe), str(C_HOST / "free_rocking.c"), "-ldl"],
        check=True,
    )
    args = list(case["args"])
    args[1] = "file://" + os.path.join(unzipped, "resources")
    r = _run([str(exe), linux64_so] + args)
    assert r.returncode == 0, r.stderr
    return _parse(r.stdout)


def test_linux64_through_a_c_host_matches_the_exact_solution(linux64_result, case):
    _check_against_exact(*linux64_result, case, "linux64")


def _windows_path(path):
    """wine's default prefix maps the Unix root to drive Z:."""
    return "Z:" + os.path.abspath(path).replace("/", "\\")


def _wine_run(source, dll, args, work):
    """Builds the C host `source` with mingw-w64 in `work` and runs it under
    wine with the DLL `dll` and `args`; the finished process."""
    wine = shutil.which("wine") or shutil.which("wine64")
    if wine is None:
        pytest.skip("wine not found (Debian: wine64); tools/cross-deps.sh installs it")
    exe = work / (source.stem + ".exe")
    cflags = ["-O2", "-Wall", "-Wextra", "-Werror", "-static-libgcc"]
    subprocess.run([MINGW_GCC, "-std=c99"] + cflags + ["-o", str(exe), str(source)], check=True)
    env = dict(os.environ)
    env.update(
        WINEPREFIX=str(TARGET / "wine"),  # kept: creating it takes seconds
        WINEDEBUG="-all",
        # no dialogs offering to install wine-mono and wine-gecko
        WINEDLLOVERRIDES="mscoree,mshtml=",
    )
    cmd = [wine, str(exe), _windows_path(dll)] + args
    r = _run(cmd, env)
    if r.returncode == 2 and f"error {ERROR_MOD_NOT_FOUND}" in r.stderr:
        # Rust's std imports ProcessPrng from bcryptprimitives.dll (Windows 10
        # and later), which wine 8 lacks: a stand-in beside the host only
        imports = subprocess.run([MINGW_OBJDUMP, "-p", dll], capture_output=True, text=True).stdout
        assert "ProcessPrng" in imports, f"LoadLibrary failed for another reason: {r.stderr}"
        subprocess.run(
            [MINGW_GCC] + cflags + ["-shared", "-o", str(work / "bcryptprimitives.dll"),
                                    str(C_HOST / "bcryptprimitives_stub.c"), "-ladvapi32"],
            check=True,
        )
        print("wine lacks ProcessPrng: the host runs with the test's bcryptprimitives.dll stand-in")
        r = _run(cmd, env)
    assert r.returncode == 0, r.stderr
    return r


def test_win64_under_wine_matches_the_exact_solution_and_linux64(win64_dll, case, linux64_result, tmp_path_factory,
                                                                 unzipped):
    args = list(case["args"])
    args[1] = "file:///" + _windows_path(os.path.join(unzipped, "resources")).replace("\\", "/")
    r = _wine_run(C_HOST / "free_rocking.c", win64_dll, args, tmp_path_factory.mktemp("c_host_win64"))
    theta_bits, omega_bits = _parse(r.stdout)
    _check_against_exact(theta_bits, omega_bits, case, "win64 under wine")

    # the same IEEE 754 arithmetic: the same results bit for bit
    lin_theta, lin_omega = linux64_result
    assert len(theta_bits) == len(lin_theta)
    for name, w, lx in [("theta", theta_bits, lin_theta), ("omega", omega_bits, lin_omega)]:
        differ = np.flatnonzero(w != lx)
        if differ.size:
            a, b = w.view(np.float64), lx.view(np.float64)
            rel = np.max(np.abs(a - b) / np.maximum(np.abs(b), 1e-300))
            pytest.fail(f"{name}: win64 and linux64 differ at {differ.size} of {len(w)} points "
                        f"(first at step {differ[0]}), by up to {rel:.1e} relative")


@pytest.fixture(scope="module")
def fmi3_binaries(tmp_path_factory):
    """The FMI 3.0 archive extracted: (linux64 .so, win64 .dll, resources)."""
    path = TARGET / "fmu" / "fmi3" / "RockingBlock.fmu"
    assert path.is_file(), f"{path} not found: run `cargo xtask fmu` first"
    out = tmp_path_factory.mktemp("fmu3")
    with zipfile.ZipFile(path) as z:
        z.extractall(out)
    dll = out / "binaries" / "x86_64-windows" / "RockingBlock.dll"
    if not dll.is_file():
        pytest.skip(f"no x86_64-windows binary: {_windows_toolchain_missing()}")
    return str(out / "binaries" / "x86_64-linux" / "RockingBlock.so"), str(dll), str(out / "resources")


def test_fmi3_win64_under_wine_matches_linux64(fmi3_binaries, case, tmp_path_factory):
    """The 3.0 functions of both binaries through a plain C host
    (`free_rocking3.c`): rigid free rocking in co-simulation with event mode
    and early return, and in Model Exchange (explicit Euler, event mode at
    each sign change of an indicator). Both platforms print the same bits;
    in co-simulation each early return is at an exact impact time. (One
    test for both modes: the second wine run finds wineserver running, which
    saves most of a run's time.)"""
    if shutil.which("cc") is None:
        pytest.skip("no C compiler (cc) on this machine")
    so, dll, resources = fmi3_binaries
    work = tmp_path_factory.mktemp("c_host3")
    exe = work / "free_rocking3"
    subprocess.run(["cc", "-O2", "-std=c99", "-Wall", "-Wextra", "-Werror", "-o", str(exe),
                    str(C_HOST / "free_rocking3.c"), "-ldl"], check=True)
    for mode in ["cs", "me"]:
        args = list(case["args"])
        args[1] = resources + os.sep
        linux = _run([str(exe), so, mode] + args)
        assert linux.returncode == 0, linux.stderr
        args[1] = _windows_path(resources) + "\\"
        win = _wine_run(C_HOST / "free_rocking3.c", dll, [mode] + args, work)
        lines = linux.stdout.splitlines()
        assert win.stdout.replace("\r", "").splitlines() == lines, f"{mode}: win64 and linux64 differ"
        events = [_from_hex(line.split()[1]) for line in lines if line.startswith("event ")]
        if mode == "cs":
            exact = [te for te, _ in case["exact"]]
            assert len(events) == len(exact), (events, exact)
            worst = max(abs(t - te) / te for t, te in zip(events, exact))
            print(f"fmi3 cs: {len(events)} early returns, worst relative error of their times {worst:.1e}")
            assert worst < RTOL
        else:
            assert events, "Model Exchange met no event"
