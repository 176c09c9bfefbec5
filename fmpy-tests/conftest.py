"""Fixtures for the RockingBlock FMU tests.

Nothing is built here: the test command runs `cargo xtask fmu` first, which
writes target/fmu/RockingBlock.fmu and target/release/run_direct.
"""

import os
import pathlib

import pytest

ROOT = pathlib.Path(__file__).resolve().parent.parent
TARGET = pathlib.Path(os.environ.get("CARGO_TARGET_DIR", ROOT / "target"))
if not TARGET.is_absolute():
    TARGET = ROOT / TARGET
FMU = TARGET / "fmu" / "RockingBlock.fmu"
RUN_DIRECT = TARGET / "release" / "run_direct"


def _require(path: pathlib.Path, what: str) -> pathlib.Path:
    if not path.is_file():
        pytest.fail(
            f"{what} not found at {path}: run `cargo xtask fmu` first "
            "(it builds the FMU and the run_direct tool)",
            pytrace=False,
        )
    return path


@pytest.fixture(scope="session")
def fmu_path() -> str:
    """Path of the packaged FMU (fails clearly if it was not built)."""
    return str(_require(FMU, "The packaged FMU"))


@pytest.fixture(scope="session")
def run_direct_path() -> str:
    """Path of the tool that runs the Rust engine directly."""
    return str(_require(RUN_DIRECT, "The run_direct tool"))


@pytest.fixture(scope="session")
def model_description(fmu_path):
    from fmpy import read_model_description

    return read_model_description(fmu_path)


@pytest.fixture(scope="session")
def unzipped(fmu_path, tmp_path_factory) -> str:
    """The FMU extracted once per session."""
    from fmpy import extract

    return extract(fmu_path, unzipdir=str(tmp_path_factory.mktemp("fmu")))


# The test files that take longest, collected first. The test command hands
# whole files to two pytest-xdist workers (--dist loadfile) in collection
# order as each worker frees up, so a long file collected last runs alone at
# the end while the other worker idles; longest first, the other worker takes
# the short files meanwhile. (test_wheel, 155 s of cross builds, runs in
# tools/wheel-check.sh.)
LONGEST_FIRST = ("test_wheel", "test_examples", "test_first_hour", "test_platforms", "test_round_body",
                 "test_space", "test_cosim_hosts", "test_vertical", "test_cli")


def size_input_derivative_buffer(monkeypatch):
    """fmpy 0.3.32 keeps input derivatives in a buffer of 9 elements and assigns one per input, which
    fails unless there are 9 continuous inputs: size the buffer to the inputs (needed with
    set_input_derivatives)."""
    from fmpy import simulation

    original = simulation.Input.__init__

    def init(self, *args, **kwargs):
        original(self, *args, **kwargs)
        self.continuous = [
            c._replace(derivatives=(c.derivatives._type_ * len(c.vrs))()) for c in getattr(self, "continuous", [])
        ]

    monkeypatch.setattr(simulation.Input, "__init__", init)

def pytest_collection_modifyitems(session, config, items):
    rank = {name: i for i, name in enumerate(LONGEST_FIRST)}
    # a stable sort: within a file, and among the other files, the order stays
    items.sort(key=lambda item: rank.get(item.path.stem, len(rank)))


_FMPY_LOGGER = []


# The test modules of the FMU itself (the others manage fmpy's logger themselves).
FMU_MODULES = {"test_model_description", "test_fmi_calls", "test_state", "test_simulation", "test_crosscheck",
               "test_robustness", "test_input_derivatives", "test_shear_frame"}


@pytest.fixture(autouse=True)
def fmpy_logger_proxy(request):
    """fmpy formats FMU messages with a C proxy that keeps the last Python
    logger given to `addLoggerProxy` in one process-wide variable. A test (or
    a library under test) whose logger is garbage collected leaves it
    dangling, and the next FMU message through fmpy's default callbacks then
    crashes the process. Around every test of the FMU modules, point it at
    fmpy's own logger, kept alive for the process."""
    if request.module.__name__ not in FMU_MODULES:
        yield
        return
    from ctypes import byref

    from fmpy.fmi2 import fmi2CallbackFunctions, fmi2CallbackLoggerTYPE, printLogMessage
    from fmpy.logging import addLoggerProxy

    def restore():
        if not _FMPY_LOGGER:
            callbacks = fmi2CallbackFunctions()
            thunk = fmi2CallbackLoggerTYPE(printLogMessage)
            _FMPY_LOGGER.extend([callbacks, thunk])
        callbacks, thunk = _FMPY_LOGGER
        callbacks.logger = thunk  # the proxy only takes over a logger that is not itself
        addLoggerProxy(byref(callbacks))

    restore()
    yield
    restore()
